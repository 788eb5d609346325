#include <coshell/element/corotational.h>
#include <coshell/model/shell_state.h>

namespace coshell::model
{
  using namespace dealii;

  namespace
  {
    Tensor<2, 3> identity()
    {
      Tensor<2, 3> one;
      for (unsigned int d = 0; d < 3; ++d)
        one[d][d] = 1;
      return one;
    }
  } // namespace

  ShellState::ShellState(const ShellModel &model)
      : model_(&model), values_(model.n_dofs()),
        rotations_(model.surface().n_vertices(), identity())
  {
    save();
  }

  void ShellState::apply_increment(const Vector<double> &increment)
  {
    for (unsigned int v = 0; v < rotations_.size(); ++v)
      if (model_->vertex_is_used(v))
      {
        const VertexDofs &dofs = model_->vertex_dofs(v);
        Tensor<1, 3>      spin;
        for (unsigned int d = 0; d < 3; ++d)
        {
          values_[dofs[ux + d]] += increment[dofs[ux + d]];
          spin[d] = increment[dofs[rx + d]];
        }
        rotations_[v] = element::rotation_exp(spin) * rotations_[v];
        const Tensor<1, 3> rotation_vector =
            element::rotation_log(rotations_[v]);
        for (unsigned int d = 0; d < 3; ++d)
          values_[dofs[rx + d]] = rotation_vector[d];
      }
  }

  const Vector<double> &ShellState::values() const
  {
    return values_;
  }

  const Tensor<2, 3> &ShellState::rotation(unsigned int vertex) const
  {
    return rotations_[vertex];
  }

  void ShellState::save()
  {
    saved_values_    = values_;
    saved_rotations_ = rotations_;
  }

  void ShellState::restore()
  {
    values_    = saved_values_;
    rotations_ = saved_rotations_;
  }
} // namespace coshell::model
