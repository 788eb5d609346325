#include <coshell/driver/scene.h>

#include <coshell/driver/analyses.h>
#include <coshell/driver/contributions.h>
#include <coshell/driver/postprocessors.h>

#include "energy_guard.h"
#include <coshell/base/csv_file.h>
#include <coshell/base/expressions.h>
#include <coshell/base/parallel_environment.h>
#include <coshell/driver/linear_static.h>
#include <coshell/driver/staged_output.h>
#include <coshell/io/results.h>
#include <coshell/model/external_loads.h>
#include <coshell/model/inertia.h>
#include <coshell/model/internal_force.h>
#include <coshell/model/prescribed_motions.h>
#include <coshell/model/rigid_body_modes.h>
#include <coshell/model/shell_model.h>
#include <coshell/model/shell_problem.h>
#include <coshell/model/shell_state.h>
#include <coshell/model/thickness_stretch.h>
#include <coshell/solvers/modal_analysis.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace coshell
{
  /// Defined in the build tree (cmake/write_git_commit.cmake).
  extern const char *const git_commit;
} // namespace coshell

namespace coshell::driver
{
  using namespace dealii;

  namespace
  {
    std::string exception_details(const ExceptionBase &error)
    {
      std::ostringstream info;
      error.print_info(info);
      return Utilities::trim(info.str());
    }

    /// Sets "A/B/Name=value" in its subsection.
    void apply_override(ParameterHandler &prm, const std::string &assignment)
    {
      const auto equal = assignment.find('=');
      if (equal == std::string::npos)
        throw std::runtime_error("--set '" + assignment +
                                 "' is not of the form 'Section/Name=value'");
      auto path =
          Utilities::split_string_list(assignment.substr(0, equal), '/');
      const std::string value = Utilities::trim(assignment.substr(equal + 1));
      for (unsigned int i = 0; i + 1 < path.size(); ++i)
        prm.enter_subsection(path[i]);
      try
      {
        prm.set(path.back(), value);
      }
      catch (const ExceptionBase &error)
      {
        for (unsigned int i = 0; i + 1 < path.size(); ++i)
          prm.leave_subsection();
        throw std::runtime_error("--set '" + assignment +
                                 "': " + exception_details(error));
      }
      for (unsigned int i = 0; i + 1 < path.size(); ++i)
        prm.leave_subsection();
    }

    double seconds_since(const std::chrono::steady_clock::time_point &start)
    {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                           start)
          .count();
    }

    double longest_edge(const mesh::Surface &surface)
    {
      double h = 0;
      for (const auto &cell : surface.active_cell_iterators())
        for (unsigned int l = 0; l < cell->n_lines(); ++l)
          h = std::max(h, cell->line(l)->diameter());
      return h;
    }
  } // namespace

  void read_parameters(ParameterHandler               &prm,
                       const std::string              &file,
                       const std::vector<std::string> &overrides)
  {
    if (!std::filesystem::is_regular_file(file) || !std::ifstream(file))
      throw std::runtime_error("cannot read parameter file '" + file +
                               "': no such readable file");
    try
    {
      prm.parse_input(file);
    }
    catch (const ExceptionBase &error)
    {
      throw std::runtime_error("parameter file '" + file +
                               "': " + exception_details(error));
    }
    for (const auto &assignment : overrides)
      apply_override(prm, assignment);
  }

  namespace
  {

    void declare_analysis_entries(ParameterHandler &prm)
    {
      prm.enter_subsection("Analysis");
      prm.declare_entry(
          "Type", "linear static",
          Patterns::Selection("linear static|nonlinear static|dynamic|modes"),
          "linear static: one linear solve (Element/Formulation = linear); "
          "nonlinear static: the equilibrium path by Newton (subsection "
          "Nonlinear solver), with linear or co-rotational kinematics; "
          "dynamic: implicit time integration (subsections Time "
          "integration, Mass and damping); modes: the lowest natural "
          "frequencies and mode shapes of the undeformed shell (subsection "
          "Modal analysis; modes.csv). Stages (subsections Stage k) "
          "give each stage its own type instead.");
      prm.leave_subsection();
    }

    /// The scene's own Output entries (VtuOutput declares the rest).
    void declare_output_entries(ParameterHandler &prm)
    {
      prm.enter_subsection("Output");
      prm.declare_entry(
          "Checkpoint interval", "0", Patterns::Double(0),
          "Dynamic stages: write checkpoint-NNNNNN.h5 (HDF5; NNNNNN the "
          "step) to the output directory whenever the time passes a "
          "multiple of this, in simulated time (0: never). "
          "`coshell scene.prm --restart FILE` resumes from one. SIGINT and "
          "SIGTERM write one at the end of the current step and stop with "
          "status 3. Unit: time (s).");
      prm.declare_entry(
          "Steps between history rows", "1", Patterns::Integer(1),
          "Dynamic stages: time_history.csv gets the rows of the steps whose "
          "number (the step column, counted over all stages) is a multiple "
          "of n, of each stage's last step and of the step where an "
          "interactive run stops. Their "
          "strain energy, largest strains and quantities of interest are "
          "computed for those steps only; the work and the dissipation are "
          "still summed over every step, so each row's energy balance holds "
          "as with 1. A haptic loop that reads only the interactive replies "
          "saves those passes over the elements, a noticeable part of a "
          "linearized step (doc/performance/iol.md). Peaks between rows are "
          "not seen, and a run that fails keeps the rows up to its last "
          "multiple of n. Unit: dimensionless (a step count).");
      prm.leave_subsection();
    }
  } // namespace

  void Scene::declare_parameters(ParameterHandler &prm)
  {
    base::Constants::declare_parameters(prm);
    mesh::MeshParameters::declare_parameters(prm);
    model::ElementParameters::declare_parameters(prm);
    model::BoundaryConditions::declare_parameters(prm);
    model::Loads::declare_parameters(prm);
    model::QuantitiesOfInterest::declare_parameters(prm);
    solvers::LinearSolver::declare_parameters(prm);
    solvers::PathFollowing::declare_parameters(prm);
    model::TangentSettings::declare_parameters(prm);
    model::CorrectionLimits::declare_parameters(prm);
    model::PrescribedMotions::declare_parameters(prm);
    model::InertiaParameters::declare_parameters(prm);
    contact::ContactParameters::declare_parameters(prm);
    ModalAnalysis::declare_parameters(prm);
    solvers::TimeIntegration::declare_parameters(prm);
    Stages::declare_parameters(prm);
    declare_analysis_entries(prm);
    io::VtuOutput::declare_parameters(prm);
    declare_output_entries(prm);
    base::ThreadSettings::declare_parameters(prm);
  }

  void Scene::parse_parameters(ParameterHandler  &prm,
                               const std::string &prm_file)
  {
    prm_file_ = prm_file;
    // First: every expression parsed below may use the constants.
    base::Constants::parse_parameters(prm);
    mesh_.parse_parameters(
        prm, std::filesystem::path(prm_file).parent_path().string());
    element_.parse_parameters(prm);
    boundary_conditions_.parse_parameters(prm);
    loads_.parse_parameters(prm);
    quantities_.parse_parameters(prm);
    linear_solver_.parse_parameters(prm);
    path_following_.parse_parameters(prm);
    tangent_settings_.parse_parameters(prm);
    correction_limits_.parse_parameters(prm);
    prm.enter_subsection("Analysis");
    analysis_type_ = analysis_type(prm.get("Type"));
    prm.leave_subsection();
    motions_.parse_parameters(prm);
    inertia_.parse_parameters(prm);
    contact_.parse_parameters(
        prm, std::filesystem::path(prm_file).parent_path().string());
    modal_analysis_.parse_parameters(prm);
    time_integration_.parse_parameters(prm);
    Stage single;
    single.analysis    = analysis_type_;
    single.duration    = analysis_type_ == AnalysisType::dynamic
                             ? time_integration_.end_time()
                             : 1.0;
    single.load_factor = Stages::default_load_factor(analysis_type_);
    single.motions     = motions_.defined();
    stages_.parse_parameters(prm, motions_.defined(), single);
    if (stages_.staged())
      analysis_type_ = AnalysisType::nonlinear_static;
    check_analysis_choice();
    output_.parse_parameters(prm);
    prm.enter_subsection("Output");
    checkpoint_interval_        = prm.get_double("Checkpoint interval");
    steps_between_history_rows_ = prm.get_integer("Steps between history rows");
    prm.leave_subsection();
    base::ThreadSettings().parse_parameters(prm);
  }

  const io::VtuOutput &Scene::output() const
  {
    return output_;
  }

  io::Json Scene::run_level(unsigned int       level,
                            const std::string &directory,
                            std::ostream      &log)
  {
    const auto    start = std::chrono::steady_clock::now();
    mesh::Surface surface;
    mesh_.build(surface, level);
    if (base::distributed())
      mesh::partition(surface, base::n_ranks());
    model::ShellModel model(surface, element_, mesh_.normal_reference);
    linear_solver_.set_row_partition(model.locally_owned_dofs());
    require_mass(model.element_parameters().material.density);
    const double setup = seconds_since(start);
    log << "level " << level << ": " << surface.n_active_cells() << " cells, "
        << model.n_dofs() << " dofs, " << element_.formulation_name()
        << " formulation\n";

    io::LevelResult result = run_analysis(model, directory, log);
    result.wall_time_s.setup += setup;
    result.wall_time_s.total    = seconds_since(start);
    result.level                = level;
    result.h                    = longest_edge(surface);
    result.n_cells              = surface.n_active_cells();
    result.n_vertices           = surface.n_used_vertices();
    result.n_dofs               = model.n_dofs();
    result.mass                 = model.mass();
    result.reference            = quantities_.references();
    result.cholmod_fallbacks    = linear_solver_.cholmod_fallbacks();
    result.factorizations       = linear_solver_.factorizations();
    result.reused_factor_solves = linear_solver_.reused_factor_solves();
    for (const auto &[name, value] : result.qoi)
      log << "  " << name << " = " << value << '\n';
    for (const auto &[name, error] : result.relative_errors())
      log << "  relative error of " << name << " = " << error << '\n';
    levels_.push_back(result);
    return result.to_json();
  }

  io::LevelResult Scene::run_analysis(const model::ShellModel &model,
                                      const std::string       &directory,
                                      std::ostream            &log)
  {
    switch (analysis_type_)
    {
    case AnalysisType::linear_static:
      return LinearStaticAnalysis(boundary_conditions_, loads_, quantities_,
                                  linear_solver_, output_)
          .run(model, directory, log);
    case AnalysisType::modes:
      return modal_analysis_.run(model, boundary_conditions_, inertia_,
                                 linear_solver_, output_, directory, log);
    case AnalysisType::nonlinear_static:
    case AnalysisType::dynamic:
      return run_stages(model, directory, log);
    }
    throw std::logic_error("Scene::run_analysis: no such AnalysisType");
  }

  bool Scene::has_dynamic_stage() const
  {
    for (const Stage &stage : stages_.list())
      if (stage.analysis == AnalysisType::dynamic)
        return true;
    return false;
  }

  void Scene::require_mass(double mean_density) const
  {
    if ((has_dynamic_stage() || analysis_type_ == AnalysisType::modes) &&
        !(mean_density > 0))
      throw std::invalid_argument(
          "dynamics and modes need mass: Material/Density must be "
          "positive");
  }

  void Scene::check_analysis_choice() const
  {
    // A density expression is checked once the mesh is there.
    if (element_.uniform_properties())
      require_mass(element_.material.density);
    const bool unstaged = analysis_type_ == AnalysisType::linear_static ||
                          analysis_type_ == AnalysisType::modes;
    if (unstaged && (stages_.staged() || !motions_.empty()))
      throw std::invalid_argument(
          "Analysis/Type = linear static runs no stages and no prescribed "
          "motions; set Analysis/Type = nonlinear static (or define the "
          "stages' Analysis type)");
    if (contact_.enabled() && unstaged)
      throw std::invalid_argument(
          "Contact is nonlinear: Contact/Method = barrier or penalty needs "
          "Analysis/Type = nonlinear static or dynamic (or stages)");
    if (contact_.enabled() && path_following_.arc_length())
      throw std::invalid_argument(
          "Contact works with load control, not with the arc-length method "
          "(Nonlinear solver/Method): its predictor is not filtered for "
          "collisions");
    if (analysis_type_ == AnalysisType::linear_static &&
        element_.formulation == model::Formulation::corotational)
      throw std::invalid_argument(
          "Analysis/Type = linear static solves the small-displacement "
          "problem once, but Element/Formulation = corotational asks for "
          "finite rotations; set Analysis/Type = nonlinear static");
  }

  namespace
  {
    /// The magnitudes of the dead loads' vertex forces over the shell's
    /// area, N/mm^2 (Contact/Barrier stiffness scale = load).
    double mean_dead_load_pressure(const model::ShellModel &model,
                                   const model::Loads      &loads)
    {
      dealii::Vector<double> force(model.n_dofs());
      std::ostringstream     quiet; // the run's log already names the vertices
      loads.assemble(model, force, quiet);
      double total = 0, area = 0;
      for (unsigned int v = 0; v < model.surface().n_vertices(); ++v)
        if (model.vertex_is_used(v))
          total += model::vertex_block(force, model.vertex_dofs(v), model::ux)
                       .norm();
      for (const auto &cell : model.dof_handler().active_cell_iterators())
        area += element::area(model.triangle(cell));
      return total / area;
    }

    std::string non_symmetric_reason(const model::ShellProblem &problem)
    {
      return problem.symmetric_tangent()
                 ? ""
                 : "the tangent of this scene (the consistent co-rotational "
                   "tangent, or a follower pressure)";
    }
  } // namespace

  AffineConstraints<double>
  Scene::stage_constraints(const model::ShellModel &model,
                           const Stage             &stage) const
  {
    AffineConstraints<double> motions, supports;
    motions_.make_constraints(model, stage.motions, motions);
    boundary_conditions_.without(stage.released)
        .make_constraints(model, supports);
    // A prescribed motion overrides the supports at the vertices it moves.
    motions.merge(
        supports,
        AffineConstraints<double>::MergeConflictBehavior::left_object_wins);
    motions.close();
    // Inertia, or contact with obstacles, may hold what supports do not.
    if (stage.analysis != AnalysisType::dynamic && !contact_.enabled())
      model::check_supports(model, motions);
    return motions;
  }

  /// One dynamic stage as its step observer sees it: the stage, its
  /// outputs, the energy guard, and the scratch of the step's bookkeeping.
  struct Scene::DynamicStageRun
  {
    DynamicStageRun(const Stage         &stage,
                    model::ShellProblem &problem,
                    double               start_time,
                    StagedOutput        &out,
                    io::LevelResult     &result,
                    const std::string   &directory,
                    std::ostream        &log)
        : stage(stage), problem(problem), start_time(start_time), out(out),
          result(result), directory(directory), log(log)
    {
    }

    const Stage         &stage;
    model::ShellProblem &problem;
    double               start_time;
    StagedOutput        &out;
    io::LevelResult     &result;
    const std::string   &directory;
    std::ostream        &log;
    /// Where the integration starts: the stage's start, or the restart's
    /// time when the checkpoint lies inside this stage.
    double                     from     = 0;
    bool                       resuming = false;
    std::optional<EnergyGuard> guard;
    /// The step's working force, increment and damping force.
    Vector<double> working_force, increment, damping_force;
    /// Output/Steps between history rows: the last step's record while
    /// its row is not written yet.
    std::optional<solvers::TimeIntegration::StepRecord> unwritten_row;

    double end() const
    {
      return start_time + stage.duration;
    }
    bool ends_stage(double time) const
    {
      return time >= end() - 1e-12 * std::max(1.0, std::abs(end()));
    }
  };

  void Scene::run_dynamic_stage(DynamicStageRun &run)
  {
    auto &problem = run.problem;
    auto &out     = run.out;
    auto &result  = run.result;
    begin_dynamic_stage(run);
    solvers::TimeIntegration::StepCheck check;
    if (run.guard)
      check = [&run](const auto &record) { return run.guard->check(record); };
    const auto wall    = std::chrono::steady_clock::now();
    const auto on_step = [&](const solvers::TimeIntegration::StepRecord &record)
    { record_dynamic_step(run, record); };
    const auto on_iteration =
        [&](unsigned int step, const solvers::NewtonIteration &record)
    {
      out.history.row({double(step), double(record.iteration),
                       problem.load_factor(), record.relative_residual,
                       record.correction_norm, record.relative_energy});
      // The converged evaluation reports no correction.
      result.newton_corrections += record.correction_norm != 0;
    };
    const double solver_before   = linear_solver_.seconds();
    const double factors_before  = linear_solver_.factorization_seconds();
    const double assembly_before = problem.assembly_seconds();
    const double reached =
        advance_dynamic_stage(problem, run.from, run.end(), out.step, on_step,
                              on_iteration, check, run.log);
    finish_dynamic_stage(run, reached);
    const double stage_seconds = seconds_since(wall);
    result.dynamic_wall_time_s += stage_seconds;
    result.dynamic_stages.push_back(
        {run.stage.number, reached - run.from, stage_seconds});
    result.dynamic_assembly_s += problem.assembly_seconds() - assembly_before;
    result.dynamic_linear_solver_s += linear_solver_.seconds() - solver_before;
    result.dynamic_factorization_s +=
        linear_solver_.factorization_seconds() - factors_before;
  }

  void Scene::begin_dynamic_stage(DynamicStageRun &run)
  {
    auto          &out     = run.out;
    auto          &problem = run.problem;
    const auto    &model   = problem.model();
    const auto    &state   = problem.state();
    const auto    *inertia = problem.find<model::Inertia>();
    const unsigned n       = model.n_dofs();
    run.working_force.reinit(n);
    run.increment.reinit(n);
    run.damping_force.reinit(n);
    // A restart resumes at the checkpoint's time with its carry-over.
    run.resuming = restart_ && restart_->stage == run.stage.number;
    run.from     = run.resuming ? restart_->time : run.start_time;
    if (!run.resuming)
      carry_ = {};
    // The forces at the start of the stage, for the work of the first step.
    Vector<double> residual(n);
    problem.set_time(run.from);
    problem.evaluate(residual, nullptr);
    working_forces(problem, out.generalized_force);
    out.damping_force.reinit(n);
    inertia->damping_force(state, out.damping_force);
    if (out.contact)
      out.contact_force = problem.force(model::ForceKind::contact);
    const auto *internal = problem.find<model::InternalForce>();
    if (run.resuming)
    {
      out.generalized_force =
          model.from_vertex_order(restart_->generalized_force);
      out.damping_force = model.from_vertex_order(restart_->damping_force);
      // A restart from the stage's last step takes no step: its summary
      // reports the checkpoint's quantities.
      run.result.qoi = step_quantities(quantities_, model, state, internal);
    }
    else if (std::isnan(run.result.initial_total_energy))
      run.result.initial_total_energy =
          inertia->measures(state).kinetic_energy +
          model::stored_energy(problem, state);
    if (time_integration_.energy_growth_limit() > 0)
      run.guard.emplace(problem, out.contact, out.generalized_force,
                        out.contact_force,
                        time_integration_.energy_growth_limit());
  }

  void
  Scene::record_dynamic_step(DynamicStageRun                            &run,
                             const solvers::TimeIntegration::StepRecord &record)
  {
    auto              &out     = run.out;
    const auto        &problem = run.problem;
    const unsigned int step    = ++out.step;
    account_step_energies(run.problem, run.out, run.working_force,
                          run.increment, run.damping_force);
    // Output/Steps between history rows: the stage's last step has a row
    // too, written before a checkpoint of that step records the rows. An
    // interactive run that stops inside the stage writes its last step's
    // row when it stops (finish_dynamic_stage).
    if (step % steps_between_history_rows_ == 0 || run.ends_stage(record.time))
    {
      write_history_row(
          quantities_, problem, record, run.stage.number, out, run.result,
          run.guard ? run.guard->accepted_strain_energy(record.time)
                    : std::nullopt);
      run.unwritten_row.reset();
    }
    else
      run.unwritten_row = record;
    run.result.steps = step;
    run.result.newton_iterations += record.iterations;
    record_contact(out, step, record.time);
    if (output_.wants_step(step, run.ends_stage(record.time)))
      write_step(problem.model(), problem.state(), out, run.directory, step,
                 record.time);
    checkpoint_step(problem, out, run.stage, record.time, run.directory,
                    run.log);
    if (interactive_)
      reply_step(run.problem, out, record.time);
  }

  void Scene::finish_dynamic_stage(DynamicStageRun &run, double reached)
  {
    auto &result = run.result;
    if (run.unwritten_row)
      write_history_row(quantities_, run.problem, *run.unwritten_row,
                        run.stage.number, run.out, result);
    result.simulated_time_s += reached - run.from;
    if (run.guard)
      result.energy_guard_rejections =
          result.energy_guard_rejections.value_or(0) + run.guard->rejections();
    if (run.resuming)
      restart_.reset();
  }

  void Scene::drive_interactively(std::istream &commands, std::ostream &replies)
  {
    if (!has_dynamic_stage())
      throw std::invalid_argument(
          "--interactive drives dynamic stages, and this scene has none "
          "(Analysis/Type = dynamic, or a Stage k with Analysis type = "
          "dynamic)");
    // Every level would read the same input, which the first one uses up.
    if (mesh_.refinement_levels.size() > 1)
      throw std::invalid_argument(
          "--interactive drives one run: Mesh/Refinement levels lists " +
          std::to_string(mesh_.refinement_levels.size()) + " levels; give one");
    interactive_.emplace(commands, replies);
    interactive_->connect_driven_obstacles(contact_);
    if (interactive_->drives_obstacles() && checkpoint_interval_ > 0)
      throw std::invalid_argument(
          "Output/Checkpoint interval: a checkpoint would not hold the "
          "input of the obstacles with an Input direction, and a restart "
          "would put them back on their Translation; set it to 0 with "
          "--interactive");
  }

  double Scene::advance_dynamic_stage(
      model::ShellProblem                               &problem,
      double                                             start,
      double                                             end,
      unsigned int                                      &step,
      const solvers::TimeIntegration::StepObserver      &on_step,
      const solvers::TimeIntegration::IterationObserver &on_iteration,
      const solvers::TimeIntegration::StepCheck         &check,
      std::ostream                                      &log)
  {
    if (!interactive_)
    {
      time_integration_.run(problem, linear_solver_, path_following_.newton(),
                            start, end, step, on_step, on_iteration, log,
                            &carry_, check);
      return end;
    }
    return interactive_->advance(
        start, end,
        [&](double from, double to)
        {
          time_integration_.run(problem, linear_solver_,
                                path_following_.newton(), from, to, step,
                                on_step, on_iteration, log, &carry_, check);
        });
  }

  void Scene::reply_step(model::ShellProblem &problem,
                         const StagedOutput  &out,
                         double               time)
  {
    interactive_->reply_step(problem, out.contact, out.step, time);
    if (interactive_->drives_obstacles() && out.contact)
      interactive_->reply_input_slopes(
          problem, *out.contact, out.step, time, linear_solver_,
          [&]()
          {
            // A linearized step's system is the step itself, and its
            // factors serve; Newton's last factors may be an iterate
            // behind, so the state reached gets its exact tangent.
            if (!time_integration_.linearized())
              solvers::Newton(path_following_.newton(), linear_solver_)
                  .factorize_tangent(problem);
          });
  }

  void Scene::write_step(const model::ShellModel &model,
                         const model::ShellState &state,
                         StagedOutput            &out,
                         const std::string       &directory,
                         unsigned int             step,
                         double                   time)
  {
    const model::InternalForce internal(model, element_.formulation,
                                        tangent_settings_.tangent());
    write_step_vtu(output_, internal, state, out, directory, step, time);
  }

  void Scene::run_static_stage(const Stage         &stage,
                               model::ShellProblem &problem,
                               StagedOutput        &out,
                               io::LevelResult     &result,
                               const std::string   &directory,
                               std::ostream        &log)
  {
    const auto &model   = problem.model();
    const auto  on_step = [&](unsigned int, double, unsigned int iterations)
    {
      stop_if_interrupted_in_static_stage();
      const unsigned int step = ++out.step;
      result.qoi = quantities_.evaluate(model, problem.state().values());
      std::vector<double> row = {double(step), problem.load_factor(),
                                 double(iterations)};
      for (const auto &[name, value] : result.qoi)
        row.push_back(value);
      row.push_back(stage.number);
      row.push_back(problem.time());
      out.curve.row(row);
      log << "  step " << step << ": load factor " << problem.load_factor()
          << ", time " << problem.time() << ", " << iterations
          << " Newton iterations\n";
      result.load_steps = step;
      result.newton_iterations += iterations;
      record_contact(out, step, problem.time());
      if (output_.wants_step(step))
        write_step(model, problem.state(), out, directory, step,
                   problem.time());
    };
    const auto on_iteration =
        [&](unsigned int, const solvers::NewtonIteration &record)
    {
      // Also between iterations: one step of a large scene can take
      // minutes, and a stop request should not wait for it.
      stop_if_interrupted_in_static_stage();
      out.history.row({double(out.step + 1), double(record.iteration),
                       problem.load_factor(), record.relative_residual,
                       record.correction_norm, record.relative_energy});
      result.newton_corrections += record.correction_norm != 0;
    };
    const auto   wall            = std::chrono::steady_clock::now();
    const double solver_before   = linear_solver_.seconds();
    const double factors_before  = linear_solver_.factorization_seconds();
    const double assembly_before = problem.assembly_seconds();
    path_following_.run(problem, linear_solver_,
                        stages_.staged() ? std::vector<double>()
                                         : quantities_.reference_load_factors(),
                        on_step, on_iteration, log);
    result.static_wall_time_s += seconds_since(wall);
    result.static_assembly_s += problem.assembly_seconds() - assembly_before;
    result.static_linear_solver_s += linear_solver_.seconds() - solver_before;
    result.static_factorization_s +=
        linear_solver_.factorization_seconds() - factors_before;
  }

  io::LevelResult Scene::run_stages(const model::ShellModel &model,
                                    const std::string       &directory,
                                    std::ostream            &log)
  {
    io::LevelResult result;
    const bool      finite =
        element_.formulation == model::Formulation::corotational;
    model::ShellState state(model, finite);
    if (has_dynamic_stage())
      state.set_body_frame_translations(time_integration_.se3());
    // Read before the files below overwrite them (same directory).
    const std::vector<std::string> earlier = read_earlier_outputs();
    next_checkpoint_time_                  = checkpoint_interval_;
    StagedOutput out =
        open_staged_outputs(quantities_, model, state, directory);
    if (has_dynamic_stage())
    {
      if (const std::string risk = time_integration_.known_risk();
          !risk.empty())
        log << risk << '\n';
      open_time_history(out, quantities_, model, state, directory);
      model::Inertia(model, inertia_, time_integration_.se3())
          .set_initial_velocity(state);
      state.save();
    }
    const auto contact = start_contact(model, state, out, directory);
    if (restart_)
      restore_checkpoint(state, out, earlier, directory, log);
    double start_time = 0;
    for (const Stage &stage : stages_.list())
    {
      if (interactive_ && stage.analysis != AnalysisType::dynamic)
        interactive_->read_ahead(start_time);
      if (interactive_ && interactive_->ended())
        break; // "quit": the stages after it do not start
      if (!skipped_by_restart(stage.number))
        run_stage(stage, model, state, start_time, out, result, directory, log);
      start_time += stage.duration;
    }
    if (interactive_ && interactive_->has_target()) // past the scene's end
      interactive_->reply_done(start_time);
    finish_staged_outputs(model, state,
                          interactive_ && interactive_->ended()
                              ? interactive_->reached()
                              : start_time,
                          out, result, directory);
    return result;
  }

  std::unique_ptr<contact::Contact>
  Scene::start_contact(const model::ShellModel &model,
                       const model::ShellState &state,
                       StagedOutput            &out,
                       const std::string       &directory) const
  {
    if (!contact_.enabled())
      return nullptr;
    auto contact = std::make_unique<contact::Contact>(
        model, contact_,
        contact_.barrier_stiffness_from_load
            ? mean_dead_load_pressure(model, loads_)
            : 0.0);
    contact->check_initial_configuration(state, 0);
    // A linearized step reports its obstacles' forces at its end only
    // through their slopes (Contact::extrapolate_loads()).
    if (time_integration_.linearized())
      contact->follow_force_slopes();
    out.contact = contact.get();
    open_contact_files(out, directory);
    return contact;
  }

  namespace
  {
    // A restart runs no stage before its checkpoint's, which is dynamic,
    // so a static stage that runs after one has run after a dynamic stage
    // exactly when one comes before it in the list.
    bool follows_a_dynamic_stage(const std::vector<Stage> &stages,
                                 const Stage              &stage)
    {
      return std::any_of(stages.begin(), stages.end(),
                         [&](const Stage &earlier)
                         {
                           return earlier.number < stage.number &&
                                  earlier.analysis == AnalysisType::dynamic;
                         });
    }

    // An equilibrium is a state at rest: a dynamic stage after a static
    // one must not start from the velocities a dynamic stage before it
    // left (the shell would move off a configuration they do not belong
    // to). The initial velocities, before any dynamic stage, are not
    // touched. The next dynamic stage makes its acceleration consistent
    // anyway (generalized alpha); zeroing it keeps a stale inertia force
    // out of the reactions read at that stage's start.
    void settle_at_rest(model::ShellState &state)
    {
      state.velocity()     = 0;
      state.acceleration() = 0;
      state.save();
    }
  } // namespace

  void Scene::run_stage(const Stage             &stage,
                        const model::ShellModel &model,
                        model::ShellState       &state,
                        double                   start_time,
                        StagedOutput            &out,
                        io::LevelResult         &result,
                        const std::string       &directory,
                        std::ostream            &log)
  {
    auto phase = std::chrono::steady_clock::now();
    if (stages_.staged())
      log << stage.name() << ", t = " << start_time << " .. "
          << start_time + stage.duration << " s\n";
    const bool dynamic = stage.analysis == AnalysisType::dynamic;
    auto       contributions =
        make_contributions({element_, tangent_settings_, loads_, inertia_,
                            time_integration_.se3()},
                           {model, stage, out.contact, log});
    model::ShellProblem problem(model, state, stage_constraints(model, stage),
                                std::move(contributions),
                                motions_.increments(model, stage.motions));
    problem.set_schedule({start_time, stage.duration, stage.load_factor});
    problem.set_correction_limits(correction_limits_);
    linear_solver_.check_applicable(non_symmetric_reason(problem));
    if (restart_ && restart_->stage == stage.number)
      problem.set_converged_force_scale(restart_->converged_force_scale);
    result.wall_time_s.setup += seconds_since(phase);
    phase = std::chrono::steady_clock::now();
    if (dynamic)
    {
      DynamicStageRun run(stage, problem, start_time, out, result, directory,
                          log);
      run_dynamic_stage(run);
    }
    else
    {
      run_static_stage(stage, problem, out, result, directory, log);
      if (follows_a_dynamic_stage(stages_.list(), stage))
        settle_at_rest(state);
    }
    result.wall_time_s.solve += seconds_since(phase);
  }

  void Scene::finish_staged_outputs(const model::ShellModel &model,
                                    const model::ShellState &state,
                                    double                   end_time,
                                    StagedOutput            &out,
                                    io::LevelResult         &result,
                                    const std::string       &directory)
  {
    const auto phase = std::chrono::steady_clock::now();
    if (out.last_written != out.step)
      write_step(model, state, out, directory, out.step, end_time);
    out.curve.finish();
    out.history.finish();
    for (auto &[o, file] : out.obstacle_force_files)
      file.finish();
    if (out.contact_forces)
    {
      out.contact_forces->finish();
      const auto &timing = out.contact->timing();
      result.contact     = {
              {"smallest_gap", out.smallest_gap},
              {"largest_penetration", out.largest_penetration},
              {"barrier_stiffness", out.contact->barrier_stiffness()},
              {"activation_distance", out.contact->activation_distance()},
              {"detection_s", timing.detection},
              {"pair_terms_s", timing.pair_terms},
              {"collision_filter_s", timing.filter},
              {"tree_build_s", timing.tree_build}};
    }
    if (out.time_history)
      out.time_history->finish();
    if (!quantities_.reference_curves().empty())
      write_reference_points(quantities_, directory);
    result.wall_time_s.output = seconds_since(phase);
  }

  void Scene::forget_results(const std::string &directory)
  {
    // Every rank of an MPI run may get here: a file another rank removed
    // first is no error.
    std::error_code ignored;
    std::filesystem::remove(directory + "/summary.json", ignored);
    std::filesystem::remove(directory + "/convergence.csv", ignored);
  }

  io::Json Scene::run(const std::string &output_directory, std::ostream &log)
  {
    std::filesystem::create_directories(output_directory);
    const std::string summary_file = output_directory + "/summary.json";
    const std::string csv_file     = output_directory + "/convergence.csv";
    forget_results(output_directory);

    levels_.clear();
    const bool      study = mesh_.refinement_levels.size() > 1;
    io::Json        summary;
    io::Json::Array level_summaries;
    for (const unsigned int level : mesh_.refinement_levels)
    {
      const std::string directory =
          study ? output_directory + "/level-" + std::to_string(level)
                : output_directory;
      level_summaries.push_back(run_level(level, directory, log));
      summary = level_summaries.back();
    }
    summary["prm_file"]    = prm_file_;
    summary["commit"]      = git_commit;
    summary["formulation"] = element_.formulation_name();
    summary["analysis"] =
        stages_.staged() ? "staged" : analysis_name(analysis_type_);
    if (has_dynamic_stage())
      summary["time_integration"] = time_integration_.method();
    summary["element"]       = element_.element_name();
    summary["linear_solver"] = linear_solver_.method();
    summary["threads"]       = base::ThreadSettings::n_threads();
    summary["mpi_ranks"]     = base::n_ranks();
    // The design values this run used, Changes applied: a checker or a
    // study reads them here instead of assuming the prm's.
    io::Json::Object constants(base::expression_constants().begin(),
                               base::expression_constants().end());
    constants.erase("pi");
    if (!constants.empty())
      summary["constants"] = constants;
    if (study)
    {
      summary["levels"] = level_summaries;
      io::write_file_atomically(csv_file, io::convergence_csv(levels_));
    }
    io::write_file_atomically(summary_file, summary.dump() + "\n");
    return summary;
  }
} // namespace coshell::driver
