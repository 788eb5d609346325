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

    Tensor<1, 3>
    block(const Vector<double> &v, const VertexDofs &dofs, unsigned int first)
    {
      Tensor<1, 3> x;
      for (unsigned int d = 0; d < 3; ++d)
        x[d] = v[dofs[first + d]];
      return x;
    }
  } // namespace

  ShellState::ShellState(const ShellModel &model, bool finite_rotations)
      : model_(&model), finite_rotations_(finite_rotations),
        values_(model.n_dofs()),
        rotations_(model.surface().n_vertices(), identity()),
        velocity_(model.n_dofs()), acceleration_(model.n_dofs())
  {
    save();
  }

  void ShellState::store_rotation_vector(unsigned int v)
  {
    const VertexDofs  &dofs            = model_->vertex_dofs(v);
    const Tensor<1, 3> rotation_vector = element::rotation_log(rotations_[v]);
    for (unsigned int d = 0; d < 3; ++d)
      values_[dofs[rx + d]] = rotation_vector[d];
  }

  void ShellState::apply_increment(const Vector<double> &increment)
  {
    if (!finite_rotations_)
    {
      values_ += increment;
      return;
    }
    for (unsigned int v = 0; v < rotations_.size(); ++v)
      if (model_->vertex_is_used(v))
      {
        const VertexDofs &dofs = model_->vertex_dofs(v);
        for (unsigned int d = 0; d < 3; ++d)
          values_[dofs[ux + d]] += increment[dofs[ux + d]];
        rotations_[v] =
            element::rotation_exp(block(increment, dofs, rx)) * rotations_[v];
        store_rotation_vector(v);
      }
  }

  void ShellState::step_increment(Vector<double> &increment) const
  {
    increment = values_;
    increment -= saved_values_;
    if (!finite_rotations_)
      return;
    for (unsigned int v = 0; v < rotations_.size(); ++v)
      if (model_->vertex_is_used(v))
      {
        const Tensor<1, 3> psi = element::rotation_log(
            transpose(saved_rotations_[v]) * rotations_[v]);
        const VertexDofs &dofs = model_->vertex_dofs(v);
        for (unsigned int d = 0; d < 3; ++d)
          increment[dofs[rx + d]] = psi[d];
      }
  }

  void ShellState::set_step_increment(const Vector<double> &increment)
  {
    values_ = saved_values_;
    values_ += increment;
    if (!finite_rotations_)
      return;
    for (unsigned int v = 0; v < rotations_.size(); ++v)
      if (model_->vertex_is_used(v))
      {
        rotations_[v] =
            saved_rotations_[v] *
            element::rotation_exp(block(increment, model_->vertex_dofs(v), rx));
        store_rotation_vector(v);
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

  bool ShellState::finite_rotations() const
  {
    return finite_rotations_;
  }

  Vector<double> &ShellState::velocity()
  {
    return velocity_;
  }

  const Vector<double> &ShellState::velocity() const
  {
    return velocity_;
  }

  Vector<double> &ShellState::acceleration()
  {
    return acceleration_;
  }

  const Vector<double> &ShellState::acceleration() const
  {
    return acceleration_;
  }

  const ShellModel &ShellState::model() const
  {
    return *model_;
  }

  void ShellState::save()
  {
    saved_values_       = values_;
    saved_rotations_    = rotations_;
    saved_velocity_     = velocity_;
    saved_acceleration_ = acceleration_;
  }

  void ShellState::restore()
  {
    values_       = saved_values_;
    rotations_    = saved_rotations_;
    velocity_     = saved_velocity_;
    acceleration_ = saved_acceleration_;
  }
} // namespace coshell::model
