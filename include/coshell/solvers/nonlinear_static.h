#pragma once

#include <coshell/element/corotational.h>
#include <coshell/model/corotational_model.h>
#include <coshell/model/shell_state.h>
#include <coshell/solvers/linear_solver.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <functional>
#include <ostream>
#include <stdexcept>
#include <vector>

namespace coshell::solvers
{
  /// Thrown when a load step cannot be completed even after cutting it.
  class NewtonFailure : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  /// The external loading of a nonlinear run: load_factor * (dead_load +
  /// follower pressure on the current configuration).
  struct LoadPattern
  {
    dealii::Vector<double> dead_load; ///< unscaled, not condensed
    double                 follower_pressure = 0;
  };

  /// Static equilibrium path of the co-rotational model: Newton-Raphson
  /// under load control with step cutting and an optional line search, or
  /// Crisfield's cylindrical arc-length method (prm subsection "Nonlinear
  /// solver").
  class NonlinearStatic
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm);
    void        parse_parameters(dealii::ParameterHandler &prm);

    /// Called after every converged step with (step, load factor, Newton
    /// iterations, state).
    using StepObserver = std::function<void(
        unsigned int, double, unsigned int, const model::ShellState &)>;

    /// Follows the path from load factor 0 to 1 (load control: stopping
    /// exactly at every factor in 'stop_factors'; arc length: until the
    /// factor reaches 1 or the step limit). Writes every iteration to
    /// 'history' as CSV rows. Throws NewtonFailure.
    void run(const model::CorotationalModel          &model,
             model::ShellState                       &state,
             const LoadPattern                       &loads,
             const dealii::AffineConstraints<double> &constraints,
             const dealii::SparsityPattern           &sparsity,
             LinearSolver                            &linear_solver,
             const std::vector<double>               &stop_factors,
             const StepObserver                      &observer,
             std::ostream                            &log,
             std::ostream                            &history) const;

    element::CorotationalTangent tangent() const;
    const std::string           &method() const;

  private:
    std::string                  method_ = "load control";
    element::CorotationalTangent tangent_ =
        element::CorotationalTangent::consistent;
    unsigned int load_steps_           = 10;
    unsigned int max_step_cuts_        = 12;
    unsigned int max_iterations_       = 30;
    double       residual_tolerance_   = 1e-7;
    double       energy_tolerance_     = 1e-16;
    double       increment_tolerance_  = 1e-8;
    bool         line_search_          = false;
    unsigned int max_arc_length_steps_ = 200;
    double       max_load_factor_      = 1;

    struct Context;
    unsigned int newton(Context &context, double load_factor) const;
    double       line_search_scale(Context                      &context,
                                   double                        load_factor,
                                   const dealii::Vector<double> &correction) const;
    void         load_control(Context &context) const;
    void         arc_length(Context &context) const;
    unsigned int arc_length_step(Context &context, double arc) const;
  };
} // namespace coshell::solvers
