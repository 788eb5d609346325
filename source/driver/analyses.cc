#include <coshell/driver/analyses.h>
#include <coshell/driver/linear_static.h>

#include <coshell/base/csv_file.h>
#include <coshell/base/parallel_environment.h>
#include <coshell/base/stopwatch.h>
#include <coshell/base/tangent_matrix.h>
#include <coshell/io/json.h>
#include <coshell/model/rigid_body_modes.h>
#include <coshell/model/shell_problem.h>
#include <coshell/model/shell_state.h>
#include <coshell/solvers/modal_analysis.h>

#include <deal.II/base/numbers.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace coshell::driver
{
  using namespace dealii;

  AffineConstraints<double>
  support_constraints(const model::BoundaryConditions &boundary_conditions,
                      const model::ShellModel         &model)
  {
    AffineConstraints<double> constraints;
    boundary_conditions.make_constraints(model, constraints);
    constraints.close();
    return constraints;
  }

  LinearStaticAnalysis::LinearStaticAnalysis(
      const model::BoundaryConditions   &supports,
      const model::Loads                &loads,
      const model::QuantitiesOfInterest &quantities,
      solvers::LinearSolver             &linear_solver,
      io::VtuOutput                     &output)
      : supports_(supports), loads_(loads), quantities_(quantities),
        linear_solver_(linear_solver), output_(output)
  {
  }

  io::LevelResult LinearStaticAnalysis::run(const model::ShellModel &model,
                                            const std::string       &directory,
                                            std::ostream            &log) const
  {
    io::LevelResult                 result;
    auto                            phase = std::chrono::steady_clock::now();
    const AffineConstraints<double> constraints =
        support_constraints(supports_, model);
    LinearStatic analysis(model, constraints,
                          linear_solver_.distributed_rows());
    result.wall_time_s.setup = base::seconds_since(phase);

    phase = std::chrono::steady_clock::now();
    analysis.assemble(loads_, log);
    result.wall_time_s.assemble = base::seconds_since(phase);

    phase                           = std::chrono::steady_clock::now();
    const Vector<double> solution   = analysis.solve(linear_solver_);
    result.wall_time_s.solve        = base::seconds_since(phase);
    result.linear_solver_iterations = linear_solver_.last_iterations();
    if (linear_solver_.last_iterations() > 1)
      log << "  " << linear_solver_.method() << ": "
          << linear_solver_.last_iterations() << " iterations\n";

    phase      = std::chrono::steady_clock::now();
    result.qoi = quantities_.evaluate(model, solution);
    output_.write(model, solution, model.resultants(solution), directory);
    result.wall_time_s.output = base::seconds_since(phase);
    result.n_inactive_dofs    = analysis.n_inactive_dofs();
    return result;
  }

  namespace
  {
    /// The shift that makes K - shift M of a shell with free rigid-body
    /// motions positive definite: a millionth of the smallest ratio
    /// K_ii / M_ii of a free DoF, a bound on the scale of the lowest
    /// elastic omega^2 from the stiffest a single DoF can be. So small a
    /// shift keeps the elastic modes apart in the shift-inverted spectrum
    /// (Lanczos converges on them as without a shift); the factorization's
    /// condition grows by the million, which a direct solver bears.
    double free_body_shift(const SparseMatrix<double> &stiffness,
                           const SparseMatrix<double> &mass)
    {
      double smallest = std::numeric_limits<double>::max();
      for (unsigned int i = 0; i < stiffness.m(); ++i)
        if (mass.diag_element(i) > 0 && stiffness.diag_element(i) > 0)
          smallest = std::min(smallest,
                              stiffness.diag_element(i) / mass.diag_element(i));
      return -1e-6 * smallest;
    }
  } // namespace

  void ModalAnalysis::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Modal analysis");
    prm.declare_entry("Number of modes", "6", Patterns::Integer(1),
                      "Analysis/Type = modes: how many of the lowest elastic "
                      "natural frequencies to compute. A shell whose "
                      "supports leave rigid-body motions free (free-free) "
                      "gets those too, as its first modes at omega near 0. "
                      "Unit: dimensionless (a count).");
    prm.declare_entry("Shift", "0", Patterns::Double(),
                      "sigma of the shift-invert Lanczos iteration, in "
                      "omega^2 units: the modes nearest it are found. 0: "
                      "automatic, 0 for a supported shell and, for one "
                      "with free rigid-body motions, a small negative "
                      "shift (a millionth of the smallest stiffness-to-"
                      "mass ratio of a DoF) that makes K - sigma M "
                      "definite. Unit: 1/time^2 (1/s^2).");
    prm.leave_subsection();
  }

  void ModalAnalysis::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Modal analysis");
    n_modes_ = prm.get_integer("Number of modes");
    shift_   = prm.get_double("Shift");
    prm.leave_subsection();
  }

  io::LevelResult
  ModalAnalysis::run(const model::ShellModel         &model,
                     const model::BoundaryConditions &supports,
                     const model::InertiaParameters  &inertia_parameters,
                     solvers::LinearSolver           &linear_solver,
                     io::VtuOutput                   &output,
                     const std::string               &directory,
                     std::ostream                    &log) const
  {
    if (base::distributed())
      throw std::invalid_argument("Analysis/Type = modes runs on one rank; "
                                  "start it without mpirun");
    io::LevelResult                 result;
    auto                            phase = std::chrono::steady_clock::now();
    const AffineConstraints<double> constraints =
        support_constraints(supports, model);
    const unsigned int n_rigid =
        model::n_free_rigid_motions(model, constraints);
    model::ShellState                                 state(model, false);
    std::vector<std::unique_ptr<model::Contribution>> inertia;
    inertia.push_back(
        std::make_unique<model::Inertia>(model, inertia_parameters));
    model::ShellProblem  problem(model, state, constraints, std::move(inertia));
    SparseMatrix<double> stiffness(problem.sparsity());
    model.assemble_stiffness(constraints, stiffness);
    // Modes run on one rank (checked above): the mass is a deal.II matrix.
    base::TangentMatrix mass_tangent;
    problem.reinit_tangent(mass_tangent);
    problem.mass_matrix(mass_tangent);
    SparseMatrix<double> &mass = mass_tangent.serial();
    // Constrained rows: no mass, so their eigenvalues go to infinity.
    for (unsigned int i = 0; i < mass.m(); ++i)
      if (constraints.is_constrained(i))
        mass.diag_element(i) = 0;
    result.wall_time_s.assemble = base::seconds_since(phase);

    phase = std::chrono::steady_clock::now();
    const double shift =
        shift_ != 0 || n_rigid == 0 ? shift_ : free_body_shift(stiffness, mass);
    if (n_rigid > 0 && shift <= 0)
      log << "  " << n_rigid << " rigid-body motion(s) free: modes 1 to "
          << n_rigid << " are rigid (omega near 0), shift " << shift
          << " 1/s^2\n";
    std::vector<double>         eigenvalues;
    std::vector<Vector<double>> modes;
    solvers::lowest_modes(stiffness, mass, linear_solver, shift,
                          n_modes_ + n_rigid, eigenvalues, modes);
    result.wall_time_s.solve = base::seconds_since(phase);

    phase = std::chrono::steady_clock::now();
    std::ostringstream csv;
    csv << "mode,frequency_hz,omega_rad_s,rigid_body\n"
        << std::setprecision(base::csv_digits);
    for (unsigned int k = 0; k < modes.size(); ++k)
    {
      const double omega = std::sqrt(std::max(eigenvalues[k], 0.0));
      // Below a shift at or under 0 the rigid modes come first.
      const bool rigid = k < n_rigid && shift <= 0;
      csv << k + 1 << ',' << omega / (2 * numbers::PI) << ',' << omega << ','
          << rigid << '\n';
      result.qoi["omega_" + std::to_string(k + 1)] = omega;
      log << "  mode " << k + 1 << ": omega = " << omega
          << " rad/s, f = " << omega / (2 * numbers::PI) << " Hz"
          << (rigid ? " (rigid-body motion)" : "") << '\n';
      output.write(model, modes[k], model.resultants(modes[k]), directory,
                   "mode-" + std::to_string(k + 1), k + 1);
    }
    std::filesystem::create_directories(directory);
    io::write_file_atomically(directory + "/modes.csv", csv.str());
    result.wall_time_s.output = base::seconds_since(phase);
    return result;
  }
} // namespace coshell::driver
