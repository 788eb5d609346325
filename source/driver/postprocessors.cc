#include <coshell/driver/postprocessors.h>

#include "energy_guard.h"
#include <coshell/base/csv_file.h>
#include <coshell/io/json.h>
#include <coshell/model/inertia.h>
#include <coshell/model/thickness_stretch.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <iomanip>
#include <sstream>

namespace coshell::driver
{
  using namespace dealii;

  namespace
  {
    /// The Name with every character but letters and digits as '_'.
    std::string column_name(std::string name)
    {
      for (char &c : name)
        if (!std::isalnum(static_cast<unsigned char>(c)))
          c = '_';
      return name;
    }
  } // namespace

  std::string step_file_name(unsigned int step, const std::string &stem)
  {
    std::ostringstream name;
    name << stem << "-" << std::setw(5) << std::setfill('0') << step;
    return name.str();
  }

  void write_reference_points(const model::QuantitiesOfInterest &quantities,
                              const std::string                 &directory)
  {
    std::ostringstream csv;
    csv << "qoi,load_factor,value\n" << std::setprecision(base::csv_digits);
    for (const auto &[name, curve] : quantities.reference_curves())
      for (const auto &[factor, value] : curve)
        csv << name << ',' << factor << ',' << value << '\n';
    io::write_file_atomically(directory + "/reference_points.csv", csv.str());
  }

  std::vector<std::string>
  with_quantities(std::vector<std::string>             columns,
                  const std::map<std::string, double> &quantities,
                  const std::vector<std::string>      &after)
  {
    for (const auto &[name, value] : quantities)
      columns.push_back(name);
    columns.insert(columns.end(), after.begin(), after.end());
    return columns;
  }

  /// The quantities of interest of a dynamic step, with the largest
  /// strains if asked for ('internal' null: before the first step, zero).
  std::map<std::string, double>
  step_quantities(const model::QuantitiesOfInterest &quantities,
                  const model::ShellModel           &model,
                  const model::ShellState           &state,
                  const model::InternalForce        *internal)
  {
    auto values = quantities.evaluate(model, state.values());
    if (quantities.largest_strains())
    {
      model::LargestStrains largest;
      if (internal)
        largest = model::largest_strains(model, internal->resultants(state));
      values["max_membrane_strain"] = largest.membrane;
      values["max_bending_strain"]  = largest.bending;
      values["max_surface_strain"]  = largest.surface;
    }
    return values;
  }

  StagedOutput
  open_staged_outputs(const model::QuantitiesOfInterest &quantities,
                      const model::ShellModel           &model,
                      const model::ShellState           &state,
                      const std::string                 &directory)
  {
    return StagedOutput(
        base::CsvFile(
            directory + "/load_displacement.csv",
            with_quantities({"step", "load_factor", "iterations"},
                            quantities.evaluate(model, state.values()),
                            {"stage", "time"})),
        base::CsvFile(directory + "/newton_history.csv",
                      {"step", "iteration", "load_factor", "relative_residual",
                       "correction_norm", "relative_energy"}));
  }

  void open_time_history(StagedOutput                      &out,
                         const model::QuantitiesOfInterest &quantities,
                         const model::ShellModel           &model,
                         const model::ShellState           &state,
                         const std::string                 &directory)
  {
    out.time_history.emplace(
        directory + "/time_history.csv",
        with_quantities(
            {"step", "time", "dt", "iterations", "kinetic_energy",
             "strain_energy", "external_work", "dissipated_energy",
             "total_energy", "linear_momentum_x", "linear_momentum_y",
             "linear_momentum_z", "angular_momentum_x", "angular_momentum_y",
             "angular_momentum_z", "contact_work", "contact_energy"},
            step_quantities(quantities, model, state, nullptr), {"stage"}));
  }

  void open_contact_files(StagedOutput &out, const std::string &directory)
  {
    out.contact_forces.emplace(
        directory + "/contact_forces.csv",
        std::vector<std::string>{"step", "time", "obstacle", "fx", "fy", "fz",
                                 "mx", "my", "mz", "active_pairs",
                                 "min_distance", "work", "ux", "uy", "uz"});
    const auto &obstacles = out.contact->obstacles();
    for (unsigned int o = 0; o < obstacles.size(); ++o)
      if (!obstacles[o].force_file.empty())
        out.obstacle_force_files.emplace_back(
            o, base::CsvFile(directory + "/" + obstacles[o].force_file,
                             {"time",
                              column_name(obstacles[o].name) + "_displacement",
                              "force_n"}));
  }

  void record_contact(StagedOutput &out, unsigned int step, double time)
  {
    if (!out.contact)
      return;
    out.smallest_gap = std::min(out.smallest_gap, out.contact->smallest_gap());
    out.largest_penetration =
        std::max(out.largest_penetration, out.contact->largest_penetration());
    const auto &loads = out.contact->obstacle_loads();
    const auto  work  = out.contact->obstacle_work();
    for (unsigned int o = 0; o < loads.size(); ++o)
    {
      std::vector<double> row = {double(step), time, double(o + 1)};
      for (unsigned int d = 0; d < 3; ++d)
        row.push_back(loads[o].force[d]);
      for (unsigned int d = 0; d < 3; ++d)
        row.push_back(loads[o].moment[d]);
      row.push_back(loads[o].active_pairs);
      row.push_back(out.contact->smallest_obstacle_gap(o));
      row.push_back(work[o]);
      const Tensor<1, 3> moved = out.contact->obstacle_displacement(o);
      for (unsigned int d = 0; d < 3; ++d)
        row.push_back(moved[d]);
      out.contact_forces->row(row);
    }
    for (auto &[o, file] : out.obstacle_force_files)
    {
      const Tensor<1, 3> &direction =
          out.contact->obstacles()[o].force_direction;
      // loads[o].force is the shell's push on the obstacle ('0 -' writes
      // no force as 0, not -0).
      file.row({time, out.contact->obstacle_displacement(o) * direction,
                0.0 - loads[o].force * direction});
    }
    // Self contact: obstacle 0, no net force (internal to the shell).
    if (out.contact->self_contact())
      out.contact_forces->row({double(step), time, 0, 0, 0, 0, 0, 0, 0,
                               double(out.contact->self_active_pairs()),
                               out.contact->smallest_self_gap(), 0, 0, 0, 0});
  }

  void write_history_row(const model::QuantitiesOfInterest          &quantities,
                         const model::ShellProblem                  &problem,
                         const solvers::TimeIntegration::StepRecord &record,
                         unsigned int                                stage,
                         StagedOutput                               &out,
                         io::LevelResult                            &result,
                         std::optional<double> known_strain_energy)
  {
    const auto  &state    = problem.state();
    const auto  *internal = problem.find<model::InternalForce>();
    const auto   kinetic  = problem.find<model::Inertia>()->measures(state);
    const double strain_energy = known_strain_energy
                                     ? *known_strain_energy
                                     : model::stored_energy(problem, state);
    result.qoi = step_quantities(quantities, problem.model(), state, internal);
    std::vector<double> row = {double(out.step),
                               record.time,
                               record.dt,
                               double(record.iterations),
                               kinetic.kinetic_energy,
                               strain_energy,
                               out.external_work,
                               out.dissipated_energy,
                               kinetic.kinetic_energy + strain_energy};
    for (unsigned int d = 0; d < 3; ++d)
      row.push_back(kinetic.linear_momentum[d]);
    for (unsigned int d = 0; d < 3; ++d)
      row.push_back(kinetic.angular_momentum[d]);
    row.push_back(out.contact_work);
    row.push_back(out.contact ? out.contact->potential() : 0.0);
    for (const auto &[name, value] : result.qoi)
      row.push_back(value);
    row.push_back(stage);
    out.time_history->row(row);
  }

  /// The step's work of the contact forces on the shell (trapezoidal on
  /// the step increment q).
  void add_contact_work(const model::ShellProblem &problem,
                        const Vector<double>      &q,
                        StagedOutput              &out)
  {
    if (!out.contact)
      return;
    const Vector<double> &force = problem.force(model::ForceKind::contact);
    out.contact_work += 0.5 * ((force * q) + (out.contact_force * q));
    out.contact_force = force;
  }

  void account_step_energies(model::ShellProblem &problem,
                             StagedOutput        &out,
                             Vector<double>      &g,
                             Vector<double>      &q,
                             Vector<double>      &damping_force)
  {
    working_forces(problem, g);
    // Displacement since the previous save (global axes, also with SE3).
    problem.state().step_displacement(q);
    out.external_work += 0.5 * ((g * q) + (out.generalized_force * q));
    out.generalized_force = g;
    problem.find<model::Inertia>()->damping_force(problem.state(),
                                                  damping_force);
    out.dissipated_energy +=
        0.5 * ((damping_force * q) + (out.damping_force * q));
    // Friction's dissipation over the step (0 without friction).
    if (out.contact)
      out.dissipated_energy += out.contact->step_friction_dissipation();
    out.damping_force = damping_force;
    add_contact_work(problem, q, out);
  }

  void write_step_vtu(io::VtuOutput              &output,
                      const model::InternalForce &internal,
                      const model::ShellState    &state,
                      StagedOutput               &out,
                      const std::string          &directory,
                      unsigned int                step,
                      double                      time)
  {
    const model::ShellModel             &model = state.model();
    std::vector<io::VtuOutput::DofField> fields;
    std::vector<std::string>             companions;
    Vector<double>                       contact_fields;
    if (out.contact && output.writes_vtu())
    {
      contact_fields = out.contact->vertex_fields();
      fields.push_back({{"contact_force", "contact_force", "contact_force",
                         "contact_gap", "contact_pressure", "unused"},
                        &contact_fields});
      companions.push_back(step_file_name(step, "obstacles") + ".vtu");
      std::filesystem::create_directories(directory);
      out.contact->write_obstacles_vtu(directory + "/" + companions.back());
    }
    output.write(model, state.values(), internal.resultants(state), directory,
                 step_file_name(step), time, fields, companions);
    out.last_written = step;
  }
} // namespace coshell::driver
