#include <coshell/driver/scene.h>
#include <coshell/io/results.h>
#include <coshell/model/corotational_model.h>
#include <coshell/model/rigid_body_modes.h>
#include <coshell/model/shell_model.h>
#include <coshell/model/shell_state.h>
#include <coshell/solvers/linear_static.h>
#include <coshell/solvers/parallel_environment.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#ifndef COSHELL_SOURCE_DIR
#define COSHELL_SOURCE_DIR "."
#endif

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

  void Scene::declare_parameters(ParameterHandler &prm)
  {
    mesh::MeshParameters::declare_parameters(prm);
    model::ElementParameters::declare_parameters(prm);
    model::BoundaryConditions::declare_parameters(prm);
    model::Loads::declare_parameters(prm);
    model::QuantitiesOfInterest::declare_parameters(prm);
    solvers::LinearSolver::declare_parameters(prm);
    solvers::NonlinearStatic::declare_parameters(prm);
    io::VtuOutput::declare_parameters(prm);
    solvers::ThreadSettings::declare_parameters(prm);
  }

  void Scene::parse_parameters(ParameterHandler  &prm,
                               const std::string &prm_file)
  {
    prm_file_ = prm_file;
    mesh_.parse_parameters(
        prm, std::filesystem::path(prm_file).parent_path().string());
    element_.parse_parameters(prm);
    boundary_conditions_.parse_parameters(prm);
    loads_.parse_parameters(prm);
    quantities_.parse_parameters(prm);
    linear_solver_.parse_parameters(prm);
    nonlinear_.parse_parameters(prm);
    output_.parse_parameters(prm);
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
    model::ShellModel         model(surface, element_, mesh_.normal_reference);
    AffineConstraints<double> constraints;
    boundary_conditions_.make_constraints(model, constraints);
    constraints.close();
    model::check_supports(model, constraints);
    const double setup = seconds_since(start);
    log << "level " << level << ": " << surface.n_active_cells() << " cells, "
        << model.n_dofs() << " dofs, " << element_.formulation_name()
        << " formulation\n";

    io::LevelResult result =
        element_.formulation == model::Formulation::linear
            ? solve_linear(model, constraints, directory, log)
            : solve_corotational(model, constraints, directory, log);
    result.wall_time_s.setup += setup;
    result.wall_time_s.total = seconds_since(start);
    result.level             = level;
    result.h                 = longest_edge(surface);
    result.n_cells           = surface.n_active_cells();
    result.n_vertices        = surface.n_used_vertices();
    result.n_dofs            = model.n_dofs();
    result.reference         = quantities_.references();
    for (const auto &[name, value] : result.qoi)
      log << "  " << name << " = " << value << '\n';
    for (const auto &[name, error] : result.relative_errors())
      log << "  relative error of " << name << " = " << error << '\n';
    levels_.push_back(result);
    return result.to_json();
  }

  io::LevelResult
  Scene::solve_linear(const model::ShellModel         &model,
                      const AffineConstraints<double> &constraints,
                      const std::string               &directory,
                      std::ostream                    &log)
  {
    io::LevelResult       result;
    auto                  phase = std::chrono::steady_clock::now();
    solvers::LinearStatic analysis(model, constraints);
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
    std::string step_file_name(unsigned int step)
    {
      std::ostringstream name;
      name << "solution-" << std::setw(5) << std::setfill('0') << step;
      return name.str();
    }

    void write_reference_points(const model::QuantitiesOfInterest &quantities,
                                const std::string                 &directory)
    {
      std::ostringstream csv;
      csv << "qoi,load_factor,value\n" << std::setprecision(12);
      for (const auto &[name, curve] : quantities.reference_curves())
        for (const auto &[factor, value] : curve)
          csv << name << ',' << factor << ',' << value << '\n';
      io::write_file_atomically(directory + "/reference_points.csv", csv.str());
    }
  } // namespace

  io::LevelResult
  Scene::solve_corotational(const model::ShellModel         &model,
                            const AffineConstraints<double> &constraints,
                            const std::string               &directory,
                            std::ostream                    &log)
  {
    io::LevelResult                result;
    auto                           phase = std::chrono::steady_clock::now();
    const model::CorotationalModel corotational(model);
    model::ShellState              state(model);
    SparsityPattern                sparsity;
    model.make_sparsity(constraints, sparsity);
    solvers::LoadPattern loads;
    loads.dead_load.reinit(model.n_dofs());
    loads_.assemble(model, loads.dead_load, log, true);
    loads.follower_pressure  = loads_.follower_pressure();
    result.wall_time_s.setup = seconds_since(phase);

    std::filesystem::create_directories(directory);
    const std::string curve_file   = directory + "/load_displacement.csv";
    const std::string history_file = directory + "/newton_history.csv";
    std::ofstream     curve(curve_file + ".partial");
    std::ofstream     history(history_file + ".partial");
    curve << "step,load_factor,iterations";
    for (const auto &[name, value] :
         quantities_.evaluate(model, state.values()))
      curve << ',' << name;
    curve << '\n' << std::setprecision(12);

    unsigned int last_written = 0;
    const auto   observer     = [&](unsigned int step, double load_factor,
                              unsigned int             iterations,
                              const model::ShellState &converged)
    {
      result.qoi = quantities_.evaluate(model, converged.values());
      curve << step << ',' << load_factor << ',' << iterations;
      for (const auto &[name, value] : result.qoi)
        curve << ',' << value;
      curve << std::endl;
      log << "  step " << step << ": load factor " << load_factor << ", "
          << iterations << " Newton iterations\n";
      result.load_steps = step;
      result.newton_iterations += iterations;
      if (output_.wants_step(step))
      {
        output_.write(model, converged.values(),
                      corotational.resultants(converged), directory,
                      step_file_name(step), load_factor);
        last_written = step;
      }
    };
    phase = std::chrono::steady_clock::now();
    nonlinear_.run(corotational, state, loads, constraints, sparsity,
                   linear_solver_, quantities_.reference_load_factors(),
                   observer, log, history);
    result.wall_time_s.solve = seconds_since(phase);

    phase = std::chrono::steady_clock::now();
    if (last_written != result.load_steps)
      output_.write(model, state.values(), corotational.resultants(state),
                    directory, step_file_name(result.load_steps), 1.0);
    curve.close();
    history.close();
    std::filesystem::rename(curve_file + ".partial", curve_file);
    std::filesystem::rename(history_file + ".partial", history_file);
    if (!quantities_.reference_curves().empty())
    {
      write_reference_points(quantities_, directory);
      plot_load_displacement(directory, log);
    }
    result.wall_time_s.output = seconds_since(phase);
    return result;
  }

  void Scene::plot_load_displacement(const std::string &directory,
                                     std::ostream      &log) const
  {
    const std::string command = "/usr/bin/python3 " COSHELL_SOURCE_DIR
                                "/scripts/plot_load_displacement.py '" +
                                directory + "' > /dev/null 2>&1";
    if (std::system(command.c_str()) != 0)
      log << "  note: could not plot load_displacement.png (needs "
             "/usr/bin/python3 with matplotlib)\n";
  }

  io::Json Scene::run(const std::string &output_directory, std::ostream &log)
  {
    std::filesystem::create_directories(output_directory);
    const std::string summary_file = output_directory + "/summary.json";
    const std::string csv_file     = output_directory + "/convergence.csv";
    // A failed run must not leave an earlier run's results looking current.
    std::filesystem::remove(summary_file);
    std::filesystem::remove(csv_file);

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
    summary["prm_file"]      = prm_file_;
    summary["commit"]        = git_commit;
    summary["formulation"]   = element_.formulation_name();
    summary["element"]       = element_.element_name();
    summary["linear_solver"] = linear_solver_.method();
    summary["threads"]       = solvers::ThreadSettings::n_threads();
    if (study)
    {
      summary["levels"] = level_summaries;
      io::write_file_atomically(csv_file, io::convergence_csv(levels_));
    }
    io::write_file_atomically(summary_file, summary.dump() + "\n");
    return summary;
  }
} // namespace coshell::driver
