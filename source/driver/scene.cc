#include <coshell/driver/scene.h>
#include <coshell/io/results.h>
#include <coshell/model/shell_model.h>
#include <coshell/solvers/linear_static.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#ifndef COSHELL_GIT_COMMIT
#define COSHELL_GIT_COMMIT "unknown"
#endif

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
    io::VtuOutput::declare_parameters(prm);
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
    output_.parse_parameters(prm);
  }

  const io::VtuOutput &Scene::output() const
  {
    return output_;
  }

  io::Json Scene::run_level(unsigned int       level,
                            const std::string &directory,
                            std::ostream      &log)
  {
    const auto      start = std::chrono::steady_clock::now();
    io::LevelResult result;
    mesh::Surface   surface;
    mesh_.build(surface, level);
    model::ShellModel         model(surface, element_, mesh_.normal_reference);
    AffineConstraints<double> constraints;
    boundary_conditions_.make_constraints(model, constraints);
    constraints.close();
    solvers::LinearStatic analysis(model, constraints);
    result.wall_time_s.setup = seconds_since(start);
    log << "level " << level << ": " << surface.n_active_cells() << " cells, "
        << model.n_dofs() << " dofs\n";

    auto phase = std::chrono::steady_clock::now();
    analysis.assemble(loads_, log);
    result.wall_time_s.assemble = seconds_since(phase);

    phase                         = std::chrono::steady_clock::now();
    const Vector<double> solution = analysis.solve(linear_solver_);
    result.wall_time_s.solve      = seconds_since(phase);

    phase            = std::chrono::steady_clock::now();
    result.qoi       = quantities_.evaluate(model, solution);
    result.reference = quantities_.references();
    output_.write(model, solution, model.resultants(solution), directory);
    result.wall_time_s.output = seconds_since(phase);
    result.wall_time_s.total  = seconds_since(start);

    result.level           = level;
    result.h               = longest_edge(surface);
    result.n_cells         = surface.n_active_cells();
    result.n_vertices      = surface.n_used_vertices();
    result.n_dofs          = model.n_dofs();
    result.n_inactive_dofs = analysis.n_inactive_dofs();
    for (const auto &[name, value] : result.qoi)
      log << "  " << name << " = " << value << '\n';
    for (const auto &[name, error] : result.relative_errors())
      log << "  relative error of " << name << " = " << error << '\n';
    levels_.push_back(result);
    return result.to_json();
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
    summary["commit"]        = COSHELL_GIT_COMMIT;
    summary["formulation"]   = "linear";
    summary["element"]       = element_.element_name();
    summary["linear_solver"] = linear_solver_.method();
    if (study)
    {
      summary["levels"] = level_summaries;
      io::write_file_atomically(csv_file, io::convergence_csv(levels_));
    }
    io::write_file_atomically(summary_file, summary.dump() + "\n");
    return summary;
  }
} // namespace coshell::driver
