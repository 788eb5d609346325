#pragma once

// The energy guard of dynamic stages (Time integration/Energy growth
// limit), and the working forces the energy bookkeeping shares with it.

#include <coshell/contact/contact.h>
#include <coshell/model/shell_problem.h>
#include <coshell/solvers/time_integration.h>

#include <deal.II/lac/vector.h>

#include <optional>
#include <string>

namespace coshell::driver
{
  /// The forces whose work on the step increment changes the shell's
  /// energy: the external loads at free DoFs, the supports' reactions at
  /// constrained ones (a reaction R balances the residual
  /// r = f_ext - f_int - f_inertia on its row: R = -r).
  void working_forces(const model::ShellProblem &problem,
                      dealii::Vector<double>    &g);

  /// Rejects a converged time step whose energy (kinetic and strain) grew
  /// by more than the work done on the shell in the step (loads,
  /// reactions and every contact force, the barrier's included, so the
  /// energy contact stores needs no term of its own) plus 'limit' times
  /// the larger of the step's starting energy and that work. Newton can
  /// converge, after many iterations, to a state far from the step's
  /// start: the residual is small there too, and only the energy tells
  /// (the released strip of prm/dynamics/strip_roll_up.prm jumped from 158
  /// to 13 139 in one step). Everything it compares is part of the state
  /// a checkpoint stores, so a restarted run judges its steps as the
  /// uninterrupted one does.
  class EnergyGuard
  {
  public:
    /// 'working_force' and 'contact_force' are those of the stage's
    /// current state (a restart's are the checkpoint's).
    EnergyGuard(const model::ShellProblem    &problem,
                const contact::Contact       *contact,
                const dealii::Vector<double> &working_force,
                const dealii::Vector<double> &contact_force,
                double                        limit);

    /// An empty string accepts the step (and remembers its energy and
    /// forces); a reason rejects it.
    std::string check(const solvers::TimeIntegration::StepRecord &record);
    /// Steps rejected so far.
    unsigned int rejections() const
    {
      return rejections_;
    }
    /// The strain energy of the step the guard accepted last if that step
    /// ended at 'time' (the time history then need not compute it again),
    /// else nothing: linearized steps are not judged.
    std::optional<double> accepted_strain_energy(double time) const;

  private:
    /// Kinetic and strain energy of the current state; keeps the strain
    /// energy in 'strain_energy_'.
    double mechanical_energy();

    const model::ShellProblem &problem_;
    const contact::Contact    *contact_;
    double                     limit_, energy_;
    double                     strain_energy_ = 0, accepted_strain_energy_ = 0;
    std::optional<double>      accepted_time_;
    unsigned int               rejections_ = 0;
    dealii::Vector<double>     working_force_, contact_force_;
  };
} // namespace coshell::driver
