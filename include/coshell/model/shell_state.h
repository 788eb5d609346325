#pragma once

#include <coshell/model/shell_model.h>

#include <deal.II/base/tensor.h>
#include <deal.II/lac/vector.h>

#include <vector>

namespace coshell::model
{
  /// Configuration of a shell undergoing finite rotations. Rotations do not
  /// add, so each vertex keeps its rotation matrix here, outside the
  /// solution vector; the vector holds the translations and, for output and
  /// quantities of interest, the rotation vectors log(R) in the rotation
  /// slots.
  class ShellState
  {
  public:
    explicit ShellState(const ShellModel &model);

    /// Translations add; rotations update multiplicatively,
    /// R <- exp(skew(d_theta)) R (spatial spin increments).
    void apply_increment(const dealii::Vector<double> &increment);

    /// DoF values: translations and rotation vectors.
    const dealii::Vector<double> &values() const;
    /// Rotation matrix of a (used) vertex.
    const dealii::Tensor<2, 3> &rotation(unsigned int vertex) const;

    /// Keeps a copy to go back to when a load step fails.
    void save();
    void restore();

  private:
    const ShellModel                 *model_;
    dealii::Vector<double>            values_, saved_values_;
    std::vector<dealii::Tensor<2, 3>> rotations_, saved_rotations_;
  };
} // namespace coshell::model
