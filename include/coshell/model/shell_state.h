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
  ///
  /// With body-frame translations (Time integration/Lie group = SE3) each
  /// vertex is an element (x, R) of SE(3): step increments are the SE(3)
  /// logarithm of (x_n, R_n)^-1 (x, R), and the translation slots of the
  /// rates hold the velocity and acceleration in the node's frame,
  /// v = R^T dx/dt. Newton's corrections stay spatial either way.
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

    /// Displacements since the last save(): translations x - x_saved in
    /// global axes, rotations as in step_increment(). Equal to the step
    /// increment unless translations are body-frame.
    void step_displacement(dealii::Vector<double> &displacement) const;
    /// The displacement a step increment would give (no state change).
    void step_displacement(const dealii::Vector<double> &increment,
                           dealii::Vector<double>       &displacement) const;
    /// Sets the configuration to the saved one plus a displacement of the
    /// form step_displacement() returns.
    void set_step_displacement(const dealii::Vector<double> &displacement);

    /// SE(3) step increments and body-frame translational rates (see the
    /// class documentation); needs finite rotations.
    void set_body_frame_translations(bool body_frame);
    bool body_frame_translations() const;
    /// d(step increment's translation)/d(x) of a vertex at fixed rotation:
    /// V(psi)^-1 R_saved^T (the identity without body-frame translations).
    dealii::Tensor<2, 3> step_translation_jacobian(unsigned int vertex) const;
    /// R_saved^T (x - x_saved) of a vertex.
    dealii::Tensor<1, 3> body_step_translation(unsigned int vertex) const;

    /// DoF values: translations and rotation vectors.
    const dealii::Vector<double> &values() const;
    /// Rotation matrix of a (used) vertex (finite rotations).
    const dealii::Tensor<2, 3> &rotation(unsigned int vertex) const;
    bool                        finite_rotations() const;

    dealii::Vector<double>       &velocity();
    const dealii::Vector<double> &velocity() const;
    dealii::Vector<double>       &acceleration();
    const dealii::Vector<double> &acceleration() const;

    /// Sets configuration and rates (a restart) and saves them. Throws
    /// std::invalid_argument when the sizes are not this mesh's.
    void load(const dealii::Vector<double>            &values,
              const std::vector<dealii::Tensor<2, 3>> &rotations,
              const dealii::Vector<double>            &velocity,
              const dealii::Vector<double>            &acceleration);
    const std::vector<dealii::Tensor<2, 3>> &rotations() const;

    /// Keeps a copy of configuration and rates to go back to when a step
    /// fails, and to measure step increments from.
    void save();
    void restore();

    const ShellModel &model() const;

  private:
    const ShellModel                 *model_;
    bool                              finite_rotations_;
    bool                              body_frame_translations_ = false;
    dealii::Vector<double>            values_, saved_values_;
    std::vector<dealii::Tensor<2, 3>> rotations_, saved_rotations_;
    dealii::Vector<double>            velocity_, saved_velocity_;
    dealii::Vector<double>            acceleration_, saved_acceleration_;

    void store_rotation_vector(unsigned int vertex);
    /// log(R_saved^T R) of a vertex.
    dealii::Tensor<1, 3> step_rotation(unsigned int vertex) const;
  };
} // namespace coshell::model
