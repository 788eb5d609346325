#pragma once

#include <coshell/base/tangent_matrix.h>

#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <limits>
#include <string>

namespace coshell::base
{
  /// What a Newton solver needs of a nonlinear system r(x) = 0 whose
  /// unknowns may live on a manifold (rotations): residual and tangent at
  /// the current iterate, a way to move the iterate, and a force scale to
  /// judge |r| against. The solver knows nothing else of the physics.
  class NonlinearProblem
  {
  public:
    virtual ~NonlinearProblem() = default;

    /// Pattern of the tangent. It may change only in begin_solve().
    virtual const dealii::SparsityPattern &sparsity() const = 0;

    /// Sizes 'tangent' for the current pattern: complete on one rank; a
    /// problem that distributes its tangent over the ranks gives each rank
    /// its rows.
    virtual void reinit_tangent(TangentMatrix &tangent) const
    {
      tangent.reinit(sparsity());
    }

    /// Called by Newton before it sizes the tangent of a solve: a problem
    /// whose couplings grow (self contact) updates sparsity() here.
    virtual void begin_solve() {}

    /// Residual r (out-of-balance force, condensed with the constraints)
    /// at the current iterate and, if 'tangent' is given, K = -dr/dx for
    /// the increment that apply_increment() takes. While a prescribed
    /// increment of constrained unknowns is pending, the residual contains
    /// its effect on the free ones (inhomogeneous constraints).
    /// 'tangent' comes from reinit_tangent() of the same solve.
    virtual void evaluate(dealii::Vector<double> &residual,
                          TangentMatrix          *tangent) = 0;

    /// The potential whose negative gradient the residual is, at the
    /// iterate of the last evaluate() (call it after evaluate(), at the
    /// same iterate): the energy a line search on the potential compares.
    /// Its unit is that of force times length. A quiet NaN when the problem
    /// has no potential (a follower load, body-frame translations): a
    /// solver then judges a step by the residual alone.
    virtual double energy()
    {
      return std::numeric_limits<double>::quiet_NaN();
    }

    /// The size of the forces at the last evaluate(), against which |r| is
    /// measured. It must not vanish when the external load does (a
    /// displacement-driven stage), e.g. the largest of the internal,
    /// external and inertia force norms.
    virtual double force_scale() const = 0;

    /// True while constrained unknowns have not reached their prescribed
    /// values: Newton must not stop then, whatever the residual.
    virtual bool prescribed_increment_pending() const
    {
      return false;
    }

    /// True when the last evaluation had to leave a prescribed move short
    /// (an obstacle held back by the shell). Unlike a constrained unknown's
    /// increment, which the next correction realizes, no correction
    /// carries it out: a step that ends so is jammed.
    virtual bool prescribed_move_blocked() const
    {
      return false;
    }

    /// Completes a correction solved on the free unknowns: sets the
    /// constrained entries (slaves and prescribed increments).
    virtual void distribute(dealii::Vector<double> &correction) const = 0;

    /// x <- x (+) correction (multiplicative on rotations).
    virtual void apply_increment(const dealii::Vector<double> &correction) = 0;

    /// Largest fraction in (0, 1] of 'correction' that may be applied (a
    /// collision-free step filter, for instance). Newton scales the whole
    /// correction, rotations included, by it.
    virtual double
    admissible_fraction(const dealii::Vector<double> & /*correction*/) const
    {
      return 1.0;
    }

    /// A step of one correction (the linearized implicit Euler) ends
    /// without an evaluation at its end: what the problem reports of its
    /// last evaluation (the forces on obstacles) is carried along the
    /// applied 'correction' by its linearization.
    virtual void
    extrapolate_reports(const dealii::Vector<double> & /*correction*/)
    {
    }

    /// Keeps a copy of the current iterate; restore() goes back to it.
    virtual void save()    = 0;
    virtual void restore() = 0;

    /// Around an evaluation at a trial iterate that will be undone (the
    /// line search): end_trial() puts back what that evaluation changed
    /// besides the iterate, e.g. obstacles moved against the trial shape.
    /// The caller undoes the trial increment itself; an implementation
    /// may also put the iterate back exactly (no round-off).
    virtual void begin_trial() {}
    virtual void end_trial() {}
    /// Instead of end_trial() (the caller does not undo the increment):
    /// the trial iterate and what its evaluation changed become the
    /// current ones, as if the increment had been applied and evaluated.
    virtual void keep_trial() {}

    /// Whether the tangent is symmetric (lets a Cholesky solver be used).
    virtual bool symmetric_tangent() const = 0;

    /// Called by Newton when a correction climbs the energy (du.r < 0: the
    /// tangent is indefinite along it), once NewtonParameters::
    /// climbs_before_convex_tangent corrections of the solve have. A problem
    /// whose tangent is exact but may be indefinite (contact pair Hessians) can
    /// switch to a positive semi-definite one for the rest of the step and
    /// return true; Newton then discards the correction and evaluates again.
    virtual bool use_convex_tangent()
    {
      return false;
    }

    /// Where a failed solve left the problem, in words for the failure
    /// message (e.g. "; the shell is pinched between ..."); "" if there is
    /// nothing to add.
    virtual std::string failure_context() const
    {
      return "";
    }
  };
} // namespace coshell::base

namespace coshell::base
{
  /// A NonlinearProblem that evolves: along a load path (statics) or in
  /// time (dynamics). Path following and time integrators drive it through
  /// this interface and know nothing else of it.
  class EvolutionProblem : public NonlinearProblem
  {
  public:
    /// Statics: the path parameter s in [0, 1] of the current stage, which
    /// fixes the time and the load factor.
    virtual void set_path_parameter(double s) = 0;
    /// d r / d s at the current iterate, condensed (the arc-length
    /// method's load direction).
    virtual void path_direction(dealii::Vector<double> &direction) = 0;

    /// Dynamics: the time the residual is evaluated at, s.
    virtual void set_time(double time) = 0;
    /// The step increment since save(), in the tangent space (rotations as
    /// material rotation vectors), and the way to set it.
    virtual void step_increment(dealii::Vector<double> &increment) const = 0;
    virtual void
    set_step_increment(const dealii::Vector<double> &increment) = 0;
    /// The displacement from the saved configuration that a step increment
    /// gives, in the layout admissible_fraction() reads (translations in
    /// global axes), and the way to set one. They equal the step increment
    /// unless translations are integrated in body frames (SE(3)), where a
    /// step moves a vertex along a helix, not a straight line.
    virtual void step_displacement(const dealii::Vector<double> &increment,
                                   dealii::Vector<double> &displacement) const
    {
      displacement = increment;
    }
    virtual void
    set_step_displacement(const dealii::Vector<double> &displacement)
    {
      set_step_increment(displacement);
    }
    /// Rates (velocity, acceleration) in the layout of step increments.
    virtual dealii::Vector<double> &velocity()     = 0;
    virtual dealii::Vector<double> &acceleration() = 0;
    /// How the integrator's rates depend on the increment: d(acceleration)
    /// / d(increment) and d(velocity) / d(increment).
    virtual void set_rate_coefficients(double acceleration_coefficient,
                                       double velocity_coefficient) = 0;
    /// The mass matrix (inertia tangent with unit acceleration
    /// coefficient), condensed, to find a consistent initial acceleration;
    /// 'mass' comes from reinit_tangent() (distributed like the tangent).
    virtual void mass_matrix(TangentMatrix &mass) = 0;
  };
} // namespace coshell::base
