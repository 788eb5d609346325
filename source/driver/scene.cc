#include <coshell/driver/scene.h>

#include "energy_guard.h"
#include "staged_output.h"
#include <coshell/io/csv_file.h>
#include <coshell/io/expressions.h>
#include <coshell/io/results.h>
#include <coshell/model/external_loads.h>
#include <coshell/model/inertia.h>
#include <coshell/model/internal_force.h>
#include <coshell/model/prescribed_motions.h>
#include <coshell/model/rigid_body_modes.h>
#include <coshell/model/shell_model.h>
#include <coshell/model/shell_problem.h>
#include <coshell/model/shell_state.h>
#include <coshell/solvers/linear_static.h>
#include <coshell/solvers/modal_analysis.h>
#include <coshell/solvers/parallel_environment.h>

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
    void declare_modal_analysis_entries(ParameterHandler &prm)
    {
      prm.enter_subsection("Modal analysis");
      prm.declare_entry("Number of modes", "6", Patterns::Integer(1),
                        "Analysis/Type = modes: how many of the lowest natural "
                        "frequencies to compute. Unit: dimensionless (a "
                        "count).");
      prm.declare_entry("Shift", "0", Patterns::Double(),
                        "sigma of the shift-invert Lanczos iteration, in "
                        "omega^2 units: the modes nearest it are found. A "
                        "negative value lets an unsupported structure (with "
                        "rigid-body modes) be analysed. Unit: 1/time^2 "
                        "(1/s^2).");
      prm.leave_subsection();
    }

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
          "linearized step (doc/performance.md). Peaks between rows are "
          "not seen, and a run that fails keeps the rows up to its last "
          "multiple of n. Unit: dimensionless (a step count).");
      prm.leave_subsection();
    }
  } // namespace

  void Scene::declare_parameters(ParameterHandler &prm)
  {
    io::Constants::declare_parameters(prm);
    mesh::MeshParameters::declare_parameters(prm);
    model::ElementParameters::declare_parameters(prm);
    model::BoundaryConditions::declare_parameters(prm);
    model::Loads::declare_parameters(prm);
    model::QuantitiesOfInterest::declare_parameters(prm);
    solvers::LinearSolver::declare_parameters(prm);
    solvers::PathFollowing::declare_parameters(prm);
    model::CorrectionLimits::declare_parameters(prm);
    model::PrescribedMotions::declare_parameters(prm);
    model::InertiaParameters::declare_parameters(prm);
    contact::ContactParameters::declare_parameters(prm);
    declare_modal_analysis_entries(prm);
    solvers::TimeIntegration::declare_parameters(prm);
    Stages::declare_parameters(prm);
    declare_analysis_entries(prm);
    io::VtuOutput::declare_parameters(prm);
    declare_output_entries(prm);
    solvers::ThreadSettings::declare_parameters(prm);
  }

  void Scene::parse_parameters(ParameterHandler  &prm,
                               const std::string &prm_file)
  {
    prm_file_ = prm_file;
    // First: every expression parsed below may use the constants.
    io::Constants::parse_parameters(prm);
    mesh_.parse_parameters(
        prm, std::filesystem::path(prm_file).parent_path().string());
    element_.parse_parameters(prm);
    boundary_conditions_.parse_parameters(prm);
    loads_.parse_parameters(prm);
    quantities_.parse_parameters(prm);
    linear_solver_.parse_parameters(prm);
    path_following_.parse_parameters(prm);
    correction_limits_.parse_parameters(prm);
    prm.enter_subsection("Analysis");
    analysis_type_ = prm.get("Type");
    prm.leave_subsection();
    motions_.parse_parameters(prm);
    inertia_.parse_parameters(prm);
    contact_.parse_parameters(
        prm, std::filesystem::path(prm_file).parent_path().string());
    prm.enter_subsection("Modal analysis");
    n_modes_     = prm.get_integer("Number of modes");
    modal_shift_ = prm.get_double("Shift");
    prm.leave_subsection();
    time_integration_.parse_parameters(prm);
    Stage single;
    single.analysis = analysis_type_;
    single.duration =
        analysis_type_ == "dynamic" ? time_integration_.end_time() : 1.0;
    single.load_factor = Stages::default_load_factor(analysis_type_);
    single.motions     = motions_.defined();
    stages_.parse_parameters(prm, motions_.defined(), single);
    if (stages_.staged())
      analysis_type_ = "nonlinear static";
    check_analysis_choice();
    output_.parse_parameters(prm);
    prm.enter_subsection("Output");
    checkpoint_interval_        = prm.get_double("Checkpoint interval");
    steps_between_history_rows_ = prm.get_integer("Steps between history rows");
    prm.leave_subsection();
    solvers::ThreadSettings().parse_parameters(prm);
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
    if (solvers::distributed())
      mesh::partition(surface, solvers::n_ranks());
    model::ShellModel model(surface, element_, mesh_.normal_reference);
    linear_solver_.set_row_partition(model.locally_owned_dofs());
    require_mass(model.element_parameters().material.density);
    const double setup = seconds_since(start);
    log << "level " << level << ": " << surface.n_active_cells() << " cells, "
        << model.n_dofs() << " dofs, " << element_.formulation_name()
        << " formulation\n";

    io::LevelResult result =
        (this->*analyses().at(analysis_type_))(model, directory, log);
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

  AffineConstraints<double>
  Scene::support_constraints(const model::ShellModel &model) const
  {
    AffineConstraints<double> constraints;
    boundary_conditions_.make_constraints(model, constraints);
    constraints.close();
    return constraints;
  }

  io::LevelResult Scene::solve_linear(const model::ShellModel &model,
                                      const std::string       &directory,
                                      std::ostream            &log)
  {
    io::LevelResult                 result;
    auto                            phase = std::chrono::steady_clock::now();
    const AffineConstraints<double> constraints = support_constraints(model);
    solvers::LinearStatic           analysis(model, constraints,
                                             linear_solver_.distributed_rows());
    result.wall_time_s.setup = seconds_since(phase);

    phase = std::chrono::steady_clock::now();
    analysis.assemble(loads_, log);
    result.wall_time_s.assemble = seconds_since(phase);

    phase                           = std::chrono::steady_clock::now();
    const Vector<double> solution   = analysis.solve(linear_solver_);
    result.wall_time_s.solve        = seconds_since(phase);
    result.linear_solver_iterations = linear_solver_.last_iterations();
    if (linear_solver_.last_iterations() > 1)
      log << "  " << linear_solver_.method() << ": "
          << linear_solver_.last_iterations() << " iterations\n";

    phase      = std::chrono::steady_clock::now();
    result.qoi = quantities_.evaluate(model, solution);
    output_.write(model, solution, model.resultants(solution), directory);
    result.wall_time_s.output = seconds_since(phase);
    result.n_inactive_dofs    = analysis.n_inactive_dofs();
    return result;
  }

  namespace
  {
    std::string step_file_name(unsigned int       step,
                               const std::string &stem = "solution")
    {
      std::ostringstream name;
      name << stem << "-" << std::setw(5) << std::setfill('0') << step;
      return name.str();
    }

    void write_reference_points(const model::QuantitiesOfInterest &quantities,
                                const std::string                 &directory)
    {
      std::ostringstream csv;
      csv << "qoi,load_factor,value\n" << std::setprecision(io::csv_digits);
      for (const auto &[name, curve] : quantities.reference_curves())
        for (const auto &[factor, value] : curve)
          csv << name << ',' << factor << ',' << value << '\n';
      io::write_file_atomically(directory + "/reference_points.csv", csv.str());
    }

    std::vector<std::string>
    with_quantities(std::vector<std::string>             columns,
                    const std::map<std::string, double> &quantities,
                    const std::vector<std::string>      &after = {})
    {
      for (const auto &[name, value] : quantities)
        columns.push_back(name);
      columns.insert(columns.end(), after.begin(), after.end());
      return columns;
    }
  } // namespace

  const std::map<std::string, Scene::AnalysisRunner> &Scene::analyses()
  {
    static const std::map<std::string, AnalysisRunner> runners = {
        {"linear static", &Scene::solve_linear},
        {"nonlinear static", &Scene::run_stages},
        {"dynamic", &Scene::run_stages},
        {"modes", &Scene::solve_modes}};
    return runners;
  }

  bool Scene::has_dynamic_stage() const
  {
    for (const Stage &stage : stages_.list())
      if (stage.analysis == "dynamic")
        return true;
    return false;
  }

  void Scene::require_mass(double mean_density) const
  {
    if ((has_dynamic_stage() || analysis_type_ == "modes") &&
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
    if ((analysis_type_ == "linear static" || analysis_type_ == "modes") &&
        (stages_.staged() || !motions_.empty()))
      throw std::invalid_argument(
          "Analysis/Type = linear static runs no stages and no prescribed "
          "motions; set Analysis/Type = nonlinear static (or define the "
          "stages' Analysis type)");
    if (contact_.enabled() &&
        (analysis_type_ == "linear static" || analysis_type_ == "modes"))
      throw std::invalid_argument(
          "Contact is nonlinear: Contact/Method = barrier or penalty needs "
          "Analysis/Type = nonlinear static or dynamic (or stages)");
    if (contact_.enabled() && path_following_.arc_length())
      throw std::invalid_argument(
          "Contact works with load control, not with the arc-length method "
          "(Nonlinear solver/Method): its predictor is not filtered for "
          "collisions");
    if (analysis_type_ == "linear static" &&
        element_.formulation == model::Formulation::corotational)
      throw std::invalid_argument(
          "Analysis/Type = linear static solves the small-displacement "
          "problem once, but Element/Formulation = corotational asks for "
          "finite rotations; set Analysis/Type = nonlinear static");
  }

  namespace
  {
    /// The static contributions: internal force and external loads.
    std::vector<std::unique_ptr<model::Contribution>>
    static_contributions(const model::ShellModel     &model,
                         const model::Loads          &loads,
                         model::Formulation           kinematics,
                         element::CorotationalTangent tangent,
                         bool                         extrapolated_forces,
                         bool                         exact_after_failure,
                         std::ostream                &log)
    {
      std::vector<std::unique_ptr<model::Contribution>> contributions;
      contributions.push_back(std::make_unique<model::InternalForce>(
          model, kinematics, tangent, extrapolated_forces,
          exact_after_failure));
      contributions.push_back(std::make_unique<model::ExternalLoads>(
          model, loads, kinematics == model::Formulation::corotational, log));
      return contributions;
    }

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

  /// The lowest natural frequencies and mode shapes of the undeformed
  /// configuration: K x = omega^2 M x with the supports (modes.csv, one
  /// VTU per mode, omega_k in the quantities of interest).
  io::LevelResult Scene::solve_modes(const model::ShellModel &model,
                                     const std::string       &directory,
                                     std::ostream            &log)
  {
    if (solvers::distributed())
      throw std::invalid_argument("Analysis/Type = modes runs on one rank; "
                                  "start it without mpirun");
    io::LevelResult                 result;
    auto                            phase = std::chrono::steady_clock::now();
    const AffineConstraints<double> constraints = support_constraints(model);
    if (modal_shift_ == 0)
      model::check_supports(model, constraints);
    model::ShellState                                 state(model, false);
    std::vector<std::unique_ptr<model::Contribution>> inertia;
    inertia.push_back(std::make_unique<model::Inertia>(model, inertia_));
    model::ShellProblem  problem(model, state, constraints, std::move(inertia));
    SparseMatrix<double> stiffness(problem.sparsity());
    model.assemble_stiffness(constraints, stiffness);
    // Modes run on one rank (checked above): the mass is a deal.II matrix.
    solvers::TangentMatrix mass_tangent;
    problem.reinit_tangent(mass_tangent);
    problem.mass_matrix(mass_tangent);
    SparseMatrix<double> &mass = mass_tangent.serial();
    // Constrained rows: no mass, so their eigenvalues go to infinity.
    for (unsigned int i = 0; i < mass.m(); ++i)
      if (constraints.is_constrained(i))
        mass.diag_element(i) = 0;
    result.wall_time_s.assemble = seconds_since(phase);

    phase = std::chrono::steady_clock::now();
    std::vector<double>         eigenvalues;
    std::vector<Vector<double>> modes;
    solvers::lowest_modes(stiffness, mass, linear_solver_, modal_shift_,
                          n_modes_, eigenvalues, modes);
    result.wall_time_s.solve = seconds_since(phase);

    phase = std::chrono::steady_clock::now();
    std::ostringstream csv;
    csv << "mode,frequency_hz,omega_rad_s\n"
        << std::setprecision(io::csv_digits);
    for (unsigned int k = 0; k < modes.size(); ++k)
    {
      const double omega = std::sqrt(std::max(eigenvalues[k], 0.0));
      csv << k + 1 << ',' << omega / (2 * numbers::PI) << ',' << omega << '\n';
      result.qoi["omega_" + std::to_string(k + 1)] = omega;
      log << "  mode " << k + 1 << ": omega = " << omega
          << " rad/s, f = " << omega / (2 * numbers::PI) << " Hz\n";
      output_.write(model, modes[k], model.resultants(modes[k]), directory,
                    "mode-" + std::to_string(k + 1), k + 1);
    }
    std::filesystem::create_directories(directory);
    io::write_file_atomically(directory + "/modes.csv", csv.str());
    result.wall_time_s.output = seconds_since(phase);
    return result;
  }

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
    if (stage.analysis != "dynamic" && !contact_.enabled())
      model::check_supports(model, motions);
    return motions;
  }

  void Scene::write_step(const model::ShellModel &model,
                         const model::ShellState &state,
                         StagedOutput            &out,
                         const std::string       &directory,
                         unsigned int             step,
                         double                   time)
  {
    const model::InternalForce           internal(model, element_.formulation,
                                                  path_following_.tangent());
    std::vector<io::VtuOutput::DofField> fields;
    std::vector<std::string>             companions;
    Vector<double>                       contact_fields;
    if (out.contact && output_.writes_vtu())
    {
      contact_fields = out.contact->vertex_fields();
      fields.push_back({{"contact_force", "contact_force", "contact_force",
                         "contact_gap", "contact_pressure", "unused"},
                        &contact_fields});
      companions.push_back(step_file_name(step, "obstacles") + ".vtu");
      std::filesystem::create_directories(directory);
      out.contact->write_obstacles_vtu(directory + "/" + companions.back());
    }
    output_.write(model, state.values(), internal.resultants(state), directory,
                  step_file_name(step), time, fields, companions);
    out.last_written = step;
  }

  void
  Scene::record_contact(StagedOutput &out, unsigned int step, double time) const
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

  /// The quantities of interest of a dynamic step, with the largest
  /// strains if asked for ('internal' null: before the first step, zero).
  std::map<std::string, double>
  Scene::step_quantities(const model::ShellModel    &model,
                         const model::ShellState    &state,
                         const model::InternalForce *internal) const
  {
    auto values = quantities_.evaluate(model, state.values());
    if (quantities_.largest_strains())
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

  void
  Scene::write_history_row(const model::ShellProblem                  &problem,
                           const solvers::TimeIntegration::StepRecord &record,
                           unsigned int                                stage,
                           StagedOutput                               &out,
                           io::LevelResult                            &result,
                           std::optional<double> known_strain_energy) const
  {
    const auto  &state    = problem.state();
    const auto  *internal = problem.find<model::InternalForce>();
    const auto   kinetic  = problem.find<model::Inertia>()->measures(state);
    const double strain_energy = known_strain_energy
                                     ? *known_strain_energy
                                     : internal->strain_energy(state);
    result.qoi              = step_quantities(problem.model(), state, internal);
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
  void Scene::add_contact_work(const model::ShellProblem &problem,
                               const Vector<double>      &q,
                               StagedOutput              &out)
  {
    if (!out.contact)
      return;
    const Vector<double> &force = problem.force(model::ForceKind::contact);
    out.contact_work += 0.5 * ((force * q) + (out.contact_force * q));
    out.contact_force = force;
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
      run.result.qoi = step_quantities(model, state, internal);
    }
    else if (std::isnan(run.result.initial_total_energy))
      run.result.initial_total_energy =
          inertia->measures(state).kinetic_energy +
          internal->strain_energy(state);
    if (time_integration_.energy_growth_limit() > 0)
      run.guard.emplace(problem, out.contact, out.generalized_force,
                        out.contact_force,
                        time_integration_.energy_growth_limit());
  }

  void Scene::account_step_energies(DynamicStageRun &run)
  {
    auto           &out = run.out;
    Vector<double> &g = run.working_force, &q = run.increment;
    working_forces(run.problem, g);
    // Displacement since the previous save (global axes, also with SE3).
    run.problem.state().step_displacement(q);
    out.external_work += 0.5 * ((g * q) + (out.generalized_force * q));
    out.generalized_force = g;
    run.problem.find<model::Inertia>()->damping_force(run.problem.state(),
                                                      run.damping_force);
    out.dissipated_energy +=
        0.5 * ((run.damping_force * q) + (out.damping_force * q));
    // Friction's dissipation over the step (0 without friction).
    if (out.contact)
      out.dissipated_energy += out.contact->step_friction_dissipation();
    out.damping_force = run.damping_force;
    add_contact_work(run.problem, q, out);
  }

  void
  Scene::record_dynamic_step(DynamicStageRun                            &run,
                             const solvers::TimeIntegration::StepRecord &record)
  {
    auto              &out     = run.out;
    const auto        &problem = run.problem;
    const unsigned int step    = ++out.step;
    account_step_energies(run);
    // Output/Steps between history rows: the stage's last step has a row
    // too, written before a checkpoint of that step records the rows. An
    // interactive run that stops inside the stage writes its last step's
    // row when it stops (finish_dynamic_stage).
    if (step % steps_between_history_rows_ == 0 || run.ends_stage(record.time))
    {
      write_history_row(problem, record, run.stage.number, out, run.result,
                        run.guard
                            ? run.guard->accepted_strain_energy(record.time)
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
      reply_step(run.problem, out, record.time,
                 interactive_->real_time_factor(record.time));
  }

  void Scene::finish_dynamic_stage(DynamicStageRun &run, double reached)
  {
    auto &result = run.result;
    if (run.unwritten_row)
      write_history_row(run.problem, *run.unwritten_row, run.stage.number,
                        run.out, result);
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
    interactive_.emplace();
    interactive_->commands = &commands;
    interactive_->replies  = &replies;
    // The driven obstacles share one input path; the Contact made from
    // these parameters keeps a handle on it.
    for (auto &obstacle : contact_.obstacles)
      if (obstacle.input_direction.norm() > 0)
      {
        if (!interactive_->input)
          interactive_->input = std::make_shared<contact::InputPath>();
        obstacle.input = interactive_->input;
      }
    if (interactive_->input && checkpoint_interval_ > 0)
      throw std::invalid_argument(
          "Output/Checkpoint interval: a checkpoint would not hold the "
          "input of the obstacles with an Input direction, and a restart "
          "would put them back on their Translation; set it to 0 with "
          "--interactive");
  }

  // Also called before a static stage, which runs whole, so its decision
  // comes before it: a "quit" after a target at the end of the dynamic
  // stage before it ends the run there instead of after the static stage.
  void Scene::InteractiveSession::read_ahead(double now)
  {
    if (ended || target)
      return;
    target = next_target(now);
    if (!target)
    {
      ended   = true;
      reached = now;
    }
  }

  // Interactive runs count only the time spent computing, not the time
  // spent waiting for the next target.
  double Scene::InteractiveSession::real_time_factor(double time) const
  {
    return (simulated_s + time - advance_from) /
           std::max(computing_s + seconds_since(advance_started), 1e-9);
  }

  namespace
  {
    /// A protocol line "t" or "t s": the target time and the input.
    struct Target
    {
      double                time;
      std::optional<double> input;
    };

    std::optional<Target> parse_target(const std::string &line)
    {
      std::istringstream       words(line);
      std::vector<std::string> parts{std::istream_iterator<std::string>(words),
                                     std::istream_iterator<std::string>()};
      if (parts.empty() || parts.size() > 2)
        return std::nullopt;
      // strtod reads "nan" and "inf" too: a target that is never reached
      // or an obstacle sent to infinity.
      const auto time = io::as_number(parts[0]);
      if (!time || !std::isfinite(*time))
        return std::nullopt;
      if (parts.size() == 1)
        return Target{*time, std::nullopt};
      const auto input = io::as_number(parts[1]);
      if (!input || !std::isfinite(*input))
        return std::nullopt;
      return Target{*time, *input};
    }
  } // namespace

  std::optional<double> Scene::InteractiveSession::next_target(double now)
  {
    std::string line;
    while (std::getline(*commands, line))
    {
      line = Utilities::trim(line);
      if (line.empty() || line[0] == '#')
        continue;
      if (line == "quit")
        return std::nullopt;
      const auto target = parse_target(line);
      if (!target)
        *replies << "error cannot read '" << line
                 << "' as a finite time in s, or a time and an input"
                 << std::endl;
      else if (target->input && !input)
        *replies << "error '" << line
                 << "': no obstacle takes input (Contact/Obstacle k/Input "
                    "direction)"
                 << std::endl;
      else if (target->input && !(target->time > now))
        *replies << "error '" << line << "': an input is for a time after "
                 << "the present, " << now << " s" << std::endl;
      else
      {
        if (target->input)
          input->append(now, target->time, *target->input);
        return target->time;
      }
    }
    return std::nullopt;
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
    auto      &session = *interactive_;
    const auto advance = [&](double from, double to)
    {
      session.advance_from    = from;
      session.advance_started = std::chrono::steady_clock::now();
      time_integration_.run(problem, linear_solver_, path_following_.newton(),
                            from, to, step, on_step, on_iteration, log, &carry_,
                            check);
      session.computing_s += seconds_since(session.advance_started);
      session.simulated_s += to - from;
    };
    double now = start;
    while (now < end && !session.ended)
    {
      session.read_ahead(now);
      if (session.ended)
        break;
      const double to = std::min(*session.target, end);
      if (to > now)
        advance(now, to);
      now = std::max(now, to);
      if (*session.target <= now)
      {
        *session.replies << "done " << now << std::endl;
        session.target.reset();
      }
    }
    session.reached = now;
    return now;
  }

  void Scene::reply_step(model::ShellProblem &problem,
                         const StagedOutput  &out,
                         double               time,
                         double               real_time_factor)
  {
    auto &reply = *interactive_->replies;
    reply << "step " << out.step << ' ' << time;
    if (out.contact)
      for (unsigned int o = 0; o < out.contact->obstacles().size(); ++o)
      {
        // A device renders the force along its own axis, with its sign:
        // the magnitude counts the force across the axis too, and cannot
        // tell a shell pushing the tool back from one dragging it along
        // (friction).
        const auto &force     = out.contact->obstacle_loads()[o].force;
        const auto &direction = out.contact->obstacles()[o].input_direction;
        reply << ' '
              << (direction.norm() > 0 ? force * direction / direction.norm()
                                       : force.norm());
      }
    const auto &model = problem.model();
    Point<3>    centroid;
    unsigned    n = 0;
    for (unsigned int v = 0; v < model.surface().n_vertices(); ++v)
      if (model.vertex_is_used(v))
      {
        centroid += model.surface().get_vertices()[v];
        for (unsigned int d = 0; d < 3; ++d)
          centroid[d] += problem.state().values()[model.vertex_dofs(v)[d]];
        ++n;
      }
    centroid /= double(n);
    reply << ' ' << centroid << ' ' << real_time_factor << std::endl;
    if (interactive_->input && out.contact)
      reply_input_slopes(problem, *out.contact, out.step, time);
  }

  namespace
  {
    /// dr/ds of the driven obstacles' common input, condensed.
    Vector<double> input_load(const model::ShellProblem &problem,
                              const contact::Contact    &contact)
    {
      const auto    &obstacles = contact.obstacles();
      Vector<double> load(problem.model().n_dofs());
      for (unsigned int o = 0; o < obstacles.size(); ++o)
        if (const auto input = contact.input_coupling(o);
            input.coupling.size() > 0)
          load.add(obstacles[o].input_direction.norm(), input.coupling);
      problem.constraints().condense(load);
      return load;
    }
  } // namespace

  // The tangent K of the step, extended by the input s, holds the
  // obstacles' couplings: dr/ds = sum_o |d_o| c_o and, with the shell
  // held, dF_o/ds = -|d_o| a_o (contact::Contact::InputCoupling). The
  // shell's answer du/ds = K^-1 dr/ds adds c_o . du/ds: the Schur
  // complement of the shell in that extended tangent, which is what a
  // haptic loop's local model between two steps needs (Cavusoglu and
  // Tendick 2000; protocol in doc/user-guide/interactive.md).
  void Scene::reply_input_slopes(model::ShellProblem &problem,
                                 contact::Contact    &contact,
                                 unsigned int         step,
                                 double               time)
  {
    // A linearized step's system is the step itself, and its factors
    // serve. Newton judges its last iterate without a tangent when it
    // expects convergence: its factors are then an iterate behind and
    // hold projected pair Hessians, and both move the slope it reports
    // (doc/validation.md). So the state reached gets its exact tangent
    // (the couplings are assembled with it).
    Vector<double> response;
    contact.set_exact_tangent(true);
    try
    {
      if (!time_integration_.linearized())
        solvers::Newton(path_following_.newton(), linear_solver_)
            .factorize_tangent(problem);
      linear_solver_.solve_with_factors(response, input_load(problem, contact));
    }
    catch (const std::exception &)
    {
      // The step has converged; only its slopes are missing (nan).
      response.reinit(problem.model().n_dofs());
      response = std::numeric_limits<double>::quiet_NaN();
    }
    contact.set_exact_tangent(false);
    const auto &obstacles = contact.obstacles();
    auto       &reply     = *interactive_->replies;
    reply << "slope " << step << ' ' << interactive_->input->value(time);
    for (unsigned int o = 0; o < obstacles.size(); ++o)
      if (auto input = contact.input_coupling(o); input.coupling.size() > 0)
      {
        problem.constraints().condense(input.coupling);
        reply << ' '
              << input.coupling * response -
                     obstacles[o].input_direction.norm() * input.stiffness;
      }
    reply << std::endl;
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
    StagedOutput out(
        io::CsvFile(directory + "/load_displacement.csv",
                    with_quantities({"step", "load_factor", "iterations"},
                                    quantities_.evaluate(model, state.values()),
                                    {"stage", "time"})),
        io::CsvFile(directory + "/newton_history.csv",
                    {"step", "iteration", "load_factor", "relative_residual",
                     "correction_norm", "relative_energy"}));
    if (has_dynamic_stage())
    {
      out.time_history.emplace(
          directory + "/time_history.csv",
          with_quantities(
              {"step", "time", "dt", "iterations", "kinetic_energy",
               "strain_energy", "external_work", "dissipated_energy",
               "total_energy", "linear_momentum_x", "linear_momentum_y",
               "linear_momentum_z", "angular_momentum_x", "angular_momentum_y",
               "angular_momentum_z", "contact_work", "contact_energy"},
              step_quantities(model, state, nullptr), {"stage"}));
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
      if (interactive_ && stage.analysis != "dynamic")
        interactive_->read_ahead(start_time);
      if (interactive_ && interactive_->ended)
        break; // "quit": the stages after it do not start
      if (!skipped_by_restart(stage.number))
        run_stage(stage, model, state, start_time, out, result, directory, log);
      start_time += stage.duration;
    }
    if (interactive_ && interactive_->target) // past the scene's end
      *interactive_->replies << "done " << start_time << std::endl;
    finish_staged_outputs(model, state,
                          interactive_ && interactive_->ended
                              ? interactive_->reached
                              : start_time,
                          out, result, directory);
    return result;
  }

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

  void Scene::open_obstacle_force_files(StagedOutput      &out,
                                        const std::string &directory) const
  {
    const auto &obstacles = out.contact->obstacles();
    for (unsigned int o = 0; o < obstacles.size(); ++o)
      if (!obstacles[o].force_file.empty())
        out.obstacle_force_files.emplace_back(
            o, io::CsvFile(directory + "/" + obstacles[o].force_file,
                           {"time",
                            column_name(obstacles[o].name) + "_displacement",
                            "force_n"}));
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
    out.contact_forces.emplace(
        directory + "/contact_forces.csv",
        std::vector<std::string>{"step", "time", "obstacle", "fx", "fy", "fz",
                                 "mx", "my", "mz", "active_pairs",
                                 "min_distance", "work", "ux", "uy", "uz"});
    open_obstacle_force_files(out, directory);
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
                         [&](const Stage &earlier) {
                           return earlier.number < stage.number &&
                                  earlier.analysis == "dynamic";
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
    const bool dynamic       = stage.analysis == "dynamic";
    auto       contributions = static_contributions(
              model, loads_, element_.formulation, path_following_.tangent(),
              path_following_.extrapolated_geometric_stiffness(dynamic),
              path_following_.exact_tangent_after_failure(), log);
    if (dynamic)
      contributions.push_back(std::make_unique<model::Inertia>(
          model, inertia_, time_integration_.se3()));
    if (out.contact)
      contributions.push_back(
          std::make_unique<contact::ContactContribution>(*out.contact));
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
    summary["analysis"]    = stages_.staged() ? "staged" : analysis_type_;
    if (has_dynamic_stage())
      summary["time_integration"] = time_integration_.method();
    summary["element"]       = element_.element_name();
    summary["linear_solver"] = linear_solver_.method();
    summary["threads"]       = solvers::ThreadSettings::n_threads();
    summary["mpi_ranks"]     = solvers::n_ranks();
    // The design values this run used, Changes applied: a checker or a
    // study reads them here instead of assuming the prm's.
    io::Json::Object constants(io::expression_constants().begin(),
                               io::expression_constants().end());
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
