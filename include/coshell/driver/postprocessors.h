#pragma once

// What a staged run writes as it goes, step by step: the load-displacement
// curve and Newton history, the time history with the energy balance,
// the contact rows and the obstacles' Force files, and the VTU of a step.
// Each works on the run's StagedOutput (staged_output.h); the columns of
// every file are listed in doc/user-guide/outputs.md.

#include <coshell/driver/staged_output.h>
#include <coshell/io/results.h>
#include <coshell/io/vtu_output.h>
#include <coshell/model/internal_force.h>
#include <coshell/model/quantities.h>
#include <coshell/model/shell_model.h>
#include <coshell/model/shell_problem.h>
#include <coshell/model/shell_state.h>
#include <coshell/solvers/time_integration.h>

#include <deal.II/lac/vector.h>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace coshell::driver
{
  /// "stem-NNNNN", the file name of step 'step' of a series.
  std::string step_file_name(unsigned int       step,
                             const std::string &stem = "solution");
  /// 'columns', then the names of 'quantities', then 'after'.
  std::vector<std::string>
  with_quantities(std::vector<std::string>             columns,
                  const std::map<std::string, double> &quantities,
                  const std::vector<std::string>      &after = {});
  /// reference_points.csv: the quantities' reference curves.
  void write_reference_points(const model::QuantitiesOfInterest &quantities,
                              const std::string                 &directory);

  /// load_displacement.csv and newton_history.csv of a staged run.
  StagedOutput
  open_staged_outputs(const model::QuantitiesOfInterest &quantities,
                      const model::ShellModel           &model,
                      const model::ShellState           &state,
                      const std::string                 &directory);

  /// The quantities of interest of a dynamic step, with the largest
  /// strains if asked for ('internal' null: before the first step, zero).
  std::map<std::string, double>
  step_quantities(const model::QuantitiesOfInterest &quantities,
                  const model::ShellModel           &model,
                  const model::ShellState           &state,
                  const model::InternalForce        *internal);
  /// time_history.csv of a run with a dynamic stage.
  void open_time_history(StagedOutput                      &out,
                         const model::QuantitiesOfInterest &quantities,
                         const model::ShellModel           &model,
                         const model::ShellState           &state,
                         const std::string                 &directory);
  /// Appends the dynamic step's row to time_history.csv (energies,
  /// momenta, the contact's work and energy, the quantities of interest)
  /// and keeps its quantities as the level's. 'known_strain_energy': the
  /// state's, if the energy guard computed it already. The kinetic
  /// measures are computed here, for the rows only.
  void
  write_history_row(const model::QuantitiesOfInterest          &quantities,
                    const model::ShellProblem                  &problem,
                    const solvers::TimeIntegration::StepRecord &record,
                    unsigned int                                stage,
                    StagedOutput                               &out,
                    io::LevelResult                            &result,
                    std::optional<double> known_strain_energy = std::nullopt);

  /// contact_forces.csv and every Contact/Obstacle k/Force file.
  void open_contact_files(StagedOutput &out, const std::string &directory);
  /// Appends the step's rows to contact_forces.csv and the obstacles'
  /// Force files, and follows the extremes of the gap.
  void record_contact(StagedOutput &out, unsigned int step, double time);

  /// The energy balance of a converged dynamic step: the work of the
  /// loads and reactions (g: the working forces), of the damping and
  /// drag and of friction, and of every contact force on the shell, each
  /// trapezoidal on the step increment q. 'damping_force' is scratch.
  void account_step_energies(model::ShellProblem    &problem,
                             StagedOutput           &out,
                             dealii::Vector<double> &g,
                             dealii::Vector<double> &q,
                             dealii::Vector<double> &damping_force);
  /// The step's work of the contact forces on the shell (trapezoidal on
  /// the step increment q).
  void add_contact_work(const model::ShellProblem    &problem,
                        const dealii::Vector<double> &q,
                        StagedOutput                 &out);

  /// Writes the step's VTU (with the contact fields and the obstacles);
  /// 'internal' gives the resultants.
  void write_step_vtu(io::VtuOutput              &output,
                      const model::InternalForce &internal,
                      const model::ShellState    &state,
                      StagedOutput               &out,
                      const std::string          &directory,
                      unsigned int                step,
                      double                      time);
} // namespace coshell::driver
