#pragma once

// The analyses of a scene that run no stages: one linear static solve,
// and the natural modes. Scene::run_level chooses one by its
// AnalysisType; the staged analyses (nonlinear static, dynamic) are the
// Scene's own stage loop.

#include <coshell/io/results.h>
#include <coshell/io/vtu_output.h>
#include <coshell/model/boundary_conditions.h>
#include <coshell/model/inertia.h>
#include <coshell/model/loads.h>
#include <coshell/model/quantities.h>
#include <coshell/model/shell_model.h>
#include <coshell/solvers/linear_solver.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/lac/affine_constraints.h>

#include <ostream>
#include <string>

namespace coshell::driver
{
  /// The supports of Boundary conditions, closed.
  dealii::AffineConstraints<double>
  support_constraints(const model::BoundaryConditions &boundary_conditions,
                      const model::ShellModel         &model);

  /// Analysis/Type = linear static: K u = f once, the quantities of
  /// interest and the VTU of the solution.
  class LinearStaticAnalysis
  {
  public:
    LinearStaticAnalysis(const model::BoundaryConditions   &supports,
                         const model::Loads                &loads,
                         const model::QuantitiesOfInterest &quantities,
                         solvers::LinearSolver             &linear_solver,
                         io::VtuOutput                     &output);

    io::LevelResult run(const model::ShellModel &model,
                        const std::string       &directory,
                        std::ostream            &log) const;

  private:
    const model::BoundaryConditions   &supports_;
    const model::Loads                &loads_;
    const model::QuantitiesOfInterest &quantities_;
    solvers::LinearSolver             &linear_solver_;
    io::VtuOutput                     &output_;
  };

  /// Analysis/Type = modes: the lowest natural frequencies and mode shapes
  /// of the undeformed configuration, K x = omega^2 M x with the supports
  /// (modes.csv, one VTU per mode, omega_k in the quantities of interest).
  /// Its settings are prm subsection "Modal analysis".
  class ModalAnalysis
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm);
    void        parse_parameters(dealii::ParameterHandler &prm);

    io::LevelResult run(const model::ShellModel         &model,
                        const model::BoundaryConditions &supports,
                        const model::InertiaParameters  &inertia,
                        solvers::LinearSolver           &linear_solver,
                        io::VtuOutput                   &output,
                        const std::string               &directory,
                        std::ostream                    &log) const;

  private:
    unsigned int n_modes_ = 6;
    double       shift_   = 0;
  };
} // namespace coshell::driver
