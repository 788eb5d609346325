#include "energy_guard.h"

#include <coshell/model/inertia.h>
#include <coshell/model/internal_force.h>
#include <coshell/model/thickness_stretch.h>

#include <algorithm>
#include <cmath>

namespace coshell::driver
{
  void working_forces(const model::ShellProblem &problem,
                      dealii::Vector<double>    &g)
  {
    using model::ForceKind;
    g                       = problem.force(ForceKind::external);
    const auto &constraints = problem.constraints();
    for (unsigned int i = 0; i < g.size(); ++i)
      if (constraints.is_constrained(i))
        g[i] = -problem.force(ForceKind::internal)[i] -
               problem.force(ForceKind::inertia)[i];
  }

  EnergyGuard::EnergyGuard(const model::ShellProblem    &problem,
                           const contact::Contact       *contact,
                           const dealii::Vector<double> &working_force,
                           const dealii::Vector<double> &contact_force,
                           double                        limit)
      : problem_(problem), contact_(contact), limit_(limit), energy_(0),
        working_force_(working_force), contact_force_(contact_force)
  {
    energy_ = mechanical_energy();
  }

  double EnergyGuard::mechanical_energy()
  {
    const auto &state = problem_.state();
    strain_energy_    = model::stored_energy(problem_, state);
    return problem_.find<model::Inertia>()->measures(state).kinetic_energy +
           strain_energy_;
  }

  std::optional<double> EnergyGuard::accepted_strain_energy(double time) const
  {
    if (accepted_time_ == time)
      return accepted_strain_energy_;
    return std::nullopt;
  }

  std::string
  EnergyGuard::check(const solvers::TimeIntegration::StepRecord &record)
  {
    dealii::Vector<double> g, q(working_force_.size());
    working_forces(problem_, g);
    problem_.state().step_displacement(q);
    // Trapezoidal on the increment, as the energy bookkeeping.
    double                        work = 0.5 * ((g * q) + (working_force_ * q));
    const dealii::Vector<double> *contact_force = nullptr;
    if (contact_)
    {
      contact_force = &problem_.force(model::ForceKind::contact);
      work += 0.5 * ((*contact_force * q) + (contact_force_ * q));
    }
    const double energy = mechanical_energy();
    const double growth = energy - energy_ - work;
    const double scale  = std::max(energy_, std::abs(work));
    if (growth > limit_ * scale)
    {
      ++rejections_;
      return "the energy guard rejects the step: the mechanical energy went "
             "from " +
             solvers::short_number(energy_) + " to " +
             solvers::short_number(energy) + " while " +
             solvers::short_number(work) +
             " of work was done on the shell, more than Time integration/"
             "Energy growth limit = " +
             solvers::short_number(limit_) +
             " allows (dt = " + solvers::short_number(record.dt) + " s)";
    }
    energy_                 = energy;
    accepted_time_          = record.time;
    accepted_strain_energy_ = strain_energy_;
    working_force_          = g;
    if (contact_force)
      contact_force_ = *contact_force;
    return {};
  }
} // namespace coshell::driver
