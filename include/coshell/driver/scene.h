#pragma once

#include <coshell/contact/contact.h>
#include <coshell/driver/analyses.h>
#include <coshell/driver/interactive.h>
#include <coshell/driver/stage.h>
#include <coshell/io/checkpoint.h>
#include <coshell/io/json.h>
#include <coshell/io/results.h>
#include <coshell/io/vtu_output.h>
#include <coshell/mesh/mesh.h>
#include <coshell/model/boundary_conditions.h>
#include <coshell/model/element_parameters.h>
#include <coshell/model/inertia.h>
#include <coshell/model/internal_force.h>
#include <coshell/model/loads.h>
#include <coshell/model/prescribed_motions.h>
#include <coshell/model/quantities.h>
#include <coshell/model/shell_problem.h>
#include <coshell/model/tangent_settings.h>
#include <coshell/solvers/linear_solver.h>
#include <coshell/solvers/path_following.h>
#include <coshell/solvers/time_integration.h>

#include <deal.II/base/parameter_handler.h>

#include <chrono>
#include <functional>
#include <istream>
#include <map>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace coshell::driver
{
  /// Reads a .prm file, applying "Section/Sub/Name=value" overrides.
  /// Throws std::runtime_error naming the file, line or parameter.
  void read_parameters(dealii::ParameterHandler       &prm,
                       const std::string              &file,
                       const std::vector<std::string> &overrides);

  struct StagedOutput;

  /// A scene: mesh, element, boundary conditions, loads, quantities of
  /// interest, solver and output, all from one parameter file. Runs each
  /// refinement level and writes per-level results plus, for a study,
  /// convergence.csv.
  class Scene
  {
  public:
    /// Declares every subsection of every component.
    static void declare_parameters(dealii::ParameterHandler &prm);
    void        parse_parameters(dealii::ParameterHandler &prm,
                                 const std::string        &prm_file);

    /// Runs all levels; returns the summary written to summary.json.
    io::Json run(const std::string &output_directory, std::ostream &log);
    /// Removes the summary.json and convergence.csv of an earlier run from
    /// 'directory' (if any), so that a run that fails or is refused does
    /// not leave them looking like its own.
    static void forget_results(const std::string &directory);

    const io::VtuOutput &output() const;

    /// Interactive coupling: dynamic stages advance to the target times
    /// read from 'commands', one per line, instead of running through,
    /// and every step writes one line to 'replies' (the protocol:
    /// doc/user-guide/interactive.md).
    void drive_interactively(std::istream &commands, std::ostream &replies);

    /// Resumes the run from a checkpoint written by Output/Checkpoint
    /// interval or on SIGINT/SIGTERM: the stages before the checkpoint's
    /// are skipped, its stage continues from its time, and the earlier
    /// run's CSV files and PVD series next to the checkpoint are carried
    /// over up to its step. Throws std::invalid_argument naming the file
    /// when it cannot be read or does not fit this scene.
    void restart_from(const std::string &file);

  private:
    std::string                 prm_file_;
    mesh::MeshParameters        mesh_;
    model::ElementParameters    element_;
    model::BoundaryConditions   boundary_conditions_;
    model::Loads                loads_;
    model::QuantitiesOfInterest quantities_;
    solvers::LinearSolver       linear_solver_;
    solvers::PathFollowing      path_following_;
    model::TangentSettings      tangent_settings_;
    model::CorrectionLimits     correction_limits_;
    AnalysisType                analysis_type_ = AnalysisType::linear_static;
    model::PrescribedMotions    motions_;
    Stages                      stages_;
    model::InertiaParameters    inertia_;
    solvers::TimeIntegration    time_integration_;
    ModalAnalysis               modal_analysis_;
    contact::ContactParameters  contact_;
    std::optional<InteractiveSession> interactive_;
    io::VtuOutput                     output_;
    std::vector<io::LevelResult>      levels_;
    /// Output/Checkpoint interval, s of simulated time (0: none), the
    /// time of the next checkpoint, and the checkpoint to resume from.
    double                        checkpoint_interval_  = 0;
    double                        next_checkpoint_time_ = 0;
    std::optional<io::Checkpoint> restart_;
    std::string                   restart_file_;
    /// Output/Steps between history rows: time_history.csv gets every
    /// n-th step of a dynamic stage and the stage's last.
    unsigned int steps_between_history_rows_ = 1;
    /// The time integrator's carry-over within the current dynamic stage.
    solvers::TimeIntegration::Carry carry_;

    io::Json run_level(unsigned int       level,
                       const std::string &directory,
                       std::ostream      &log);
    /// The level's analysis, chosen by Analysis/Type (the staged ones
    /// run the stages).
    io::LevelResult run_analysis(const model::ShellModel &model,
                                 const std::string       &directory,
                                 std::ostream            &log);
    /// Runs the stages (nonlinear static or dynamic) in order, carrying
    /// the configuration over.
    io::LevelResult run_stages(const model::ShellModel &model,
                               const std::string       &directory,
                               std::ostream            &log);
    /// The contact of the run (nothing when Contact is off), checked
    /// against the initial configuration, and its contact_forces.csv.
    std::unique_ptr<contact::Contact>
    start_contact(const model::ShellModel &model,
                  const model::ShellState &state,
                  StagedOutput            &out,
                  const std::string       &directory) const;
    /// Builds the stage's problem on 'state' and runs it.
    void run_stage(const Stage             &stage,
                   const model::ShellModel &model,
                   model::ShellState       &state,
                   double                   start_time,
                   StagedOutput            &out,
                   io::LevelResult         &result,
                   const std::string       &directory,
                   std::ostream            &log);
    /// The last step's VTU if not written yet, the CSV files closed, and
    /// the contact's extremes and timings in the level's result.
    void finish_staged_outputs(const model::ShellModel &model,
                               const model::ShellState &state,
                               double                   end_time,
                               StagedOutput            &out,
                               io::LevelResult         &result,
                               const std::string       &directory);
    /// Writes the step's VTU (with the contact fields and the obstacles).
    void write_step(const model::ShellModel &model,
                    const model::ShellState &state,
                    StagedOutput            &out,
                    const std::string       &directory,
                    unsigned int             step,
                    double                   time);
    void run_static_stage(const Stage         &stage,
                          model::ShellProblem &problem,
                          StagedOutput        &out,
                          io::LevelResult     &result,
                          const std::string   &directory,
                          std::ostream        &log);
    struct DynamicStageRun;
    /// Integrates a dynamic stage (or, interactively, up to each target),
    /// with its time history, contact rows, VTU, checkpoints and replies.
    void run_dynamic_stage(DynamicStageRun &run);
    /// The dynamic stage's parts: the forces at its start (or the
    /// restart's) and its energy guard; the step's energies, rows, files,
    /// checkpoint and reply; and the pending row and totals at its end.
    void begin_dynamic_stage(DynamicStageRun &run);
    void
         record_dynamic_step(DynamicStageRun                            &run,
                             const solvers::TimeIntegration::StepRecord &record);
    void finish_dynamic_stage(DynamicStageRun &run, double reached);
    bool has_dynamic_stage() const;
    /// Checkpointing (scene_checkpoint.cc): the earlier run's CSV rows
    /// up to the restart's step (curve, Newton history, time history,
    /// contact forces, the obstacles' Force files), read
    /// before this run overwrites those files; the restored state and
    /// outputs; the checkpoint after a dynamic step when one is due or a
    /// signal came (then throws Interrupted); the signal check of static
    /// steps.
    std::vector<std::string> read_earlier_outputs() const;
    std::vector<std::string> staged_csv_files() const;
    void                     restore_checkpoint(model::ShellState              &state,
                                                StagedOutput                   &out,
                                                const std::vector<std::string> &earlier,
                                                const std::string              &directory,
                                                std::ostream                   &log);
    void                     checkpoint_step(const model::ShellProblem &problem,
                                             const StagedOutput        &out,
                                             const Stage               &stage,
                                             double                     time,
                                             const std::string         &directory,
                                             std::ostream              &log);
    void                     restore_contact(const io::Checkpoint    &checkpoint,
                                             const model::ShellState &state,
                                             StagedOutput            &out) const;
    static void              stop_if_interrupted_in_static_stage();
    /// Whether stage 'number' is skipped or resumed by the restart.
    bool skipped_by_restart(unsigned int stage_number) const;
    /// Runs the time integration of a dynamic stage from 'start' to
    /// 'end', or, when driven interactively, to each target read until
    /// the stage's end, "quit" or the end of the input (a target past the
    /// end is kept for the next stage); returns the time reached. 'check'
    /// judges each converged step (the energy guard).
    double advance_dynamic_stage(
        model::ShellProblem                               &problem,
        double                                             start,
        double                                             end,
        unsigned int                                      &step,
        const solvers::TimeIntegration::StepObserver      &on_step,
        const solvers::TimeIntegration::IterationObserver &on_iteration,
        const solvers::TimeIntegration::StepCheck         &check,
        std::ostream                                      &log);
    /// The --interactive replies of one step (InteractiveSession): its
    /// line and, with driven obstacles, its slope line.
    void reply_step(model::ShellProblem &problem,
                    const StagedOutput  &out,
                    double               time);
    /// Supports less the released ones, plus the stage's motions.
    dealii::AffineConstraints<double>
    stage_constraints(const model::ShellModel &model, const Stage &stage) const;

    void check_analysis_choice() const;
    /// Throws if a dynamic stage or modal analysis has no mass.
    void require_mass(double mean_density) const;
  };
} // namespace coshell::driver
