#pragma once

#include <coshell/model/shell_model.h>

#include <deal.II/base/tensor.h>
#include <deal.II/lac/vector.h>

#include <vector>

namespace coshell::model
{
  /// Configuration of the shell and, in dynamics, its rates. With finite
  /// rotations, rotations do not add, so each vertex keeps its rotation
  /// matrix here, outside the solution vector; the vector holds the
  /// translations and, for output and quantities of interest, the rotation
  /// vectors log(R) in the rotation slots. With small rotations (linear
  /// kinematics) everything adds.
  ///
  /// Rates use the DoF layout: translation slots hold the velocity and
  /// acceleration in global axes, rotation slots the angular velocity and
  /// acceleration in the node's material frame (Omega with
  /// dR/dt = R skew(Omega)), as the Lie-group integrators want them.
  class ShellState
  {
  public:
    explicit ShellState(const ShellModel &model, bool finite_rotations = true);

    /// Translations add; rotations update multiplicatively,
    /// R <- exp(skew(d_theta)) R (spatial spin increments), or add.
    void apply_increment(const dealii::Vector<double> &increment);

    /// The increment since the last save(), in the tangent space:
    /// translations u - u_saved, rotations log(R_saved^T R) (material).
    void step_increment(dealii::Vector<double> &increment) const;
    /// Sets the configuration to the saved one plus a step increment of
    /// the form step_increment() returns.
    void set_step_increment(const dealii::Vector<double> &increment);

    /// DoF values: translations and rotation vectors.
    const dealii::Vector<double> &values() const;
    /// Rotation matrix of a (used) vertex (finite rotations).
    const dealii::Tensor<2, 3> &rotation(unsigned int vertex) const;
    bool                        finite_rotations() const;

    dealii::Vector<double>       &velocity();
    const dealii::Vector<double> &velocity() const;
    dealii::Vector<double>       &acceleration();
    const dealii::Vector<double> &acceleration() const;

    /// Keeps a copy of configuration and rates to go back to when a step
    /// fails, and to measure step increments from.
    void save();
    void restore();

    const ShellModel &model() const;

  private:
    const ShellModel                 *model_;
    bool                              finite_rotations_;
    dealii::Vector<double>            values_, saved_values_;
    std::vector<dealii::Tensor<2, 3>> rotations_, saved_rotations_;
    dealii::Vector<double>            velocity_, saved_velocity_;
    dealii::Vector<double>            acceleration_, saved_acceleration_;

    void store_rotation_vector(unsigned int vertex);
  };
} // namespace coshell::model
