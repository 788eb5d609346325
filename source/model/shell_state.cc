#include <coshell/element/corotational.h>
#include <coshell/model/shell_state.h>

#include <stdexcept>

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
            element::rotation_exp(vertex_block(increment, dofs, rx)) *
            rotations_[v];
        store_rotation_vector(v);
      }
    // The thickness stretches, numbered after the FESystem's DoFs, add.
    for (auto i = model_->n_fe_dofs(); i < values_.size(); ++i)
      values_[i] += increment[i];
  }

  Tensor<1, 3> ShellState::step_rotation(unsigned int v) const
  {
    return element::rotation_log(transpose(saved_rotations_[v]) *
                                 rotations_[v]);
  }

  void ShellState::step_displacement(Vector<double> &displacement) const
  {
    displacement = values_;
    displacement -= saved_values_;
    if (!finite_rotations_)
      return;
    for (unsigned int v = 0; v < rotations_.size(); ++v)
      if (model_->vertex_is_used(v))
      {
        const Tensor<1, 3> psi  = step_rotation(v);
        const VertexDofs  &dofs = model_->vertex_dofs(v);
        for (unsigned int d = 0; d < 3; ++d)
          displacement[dofs[rx + d]] = psi[d];
      }
  }

  void ShellState::step_increment(Vector<double> &increment) const
  {
    step_displacement(increment);
    if (!body_frame_translations_)
      return;
    // The SE(3) logarithm: q_u = V(psi)^-1 R_n^T (x - x_n), psi already in
    // the rotation slots (no second logarithm).
    for (unsigned int v = 0; v < rotations_.size(); ++v)
      if (model_->vertex_is_used(v))
      {
        const VertexDofs  &dofs = model_->vertex_dofs(v);
        const Tensor<1, 3> q_u  = element::so3_left_jacobian_inverse(
                                      vertex_block(increment, dofs, rx)) *
                                 (transpose(saved_rotations_[v]) *
                                  vertex_block(increment, dofs, ux));
        for (unsigned int d = 0; d < 3; ++d)
          increment[dofs[ux + d]] = q_u[d];
      }
  }

  void ShellState::step_displacement(const Vector<double> &increment,
                                     Vector<double>       &displacement) const
  {
    displacement = increment;
    if (!body_frame_translations_)
      return;
    // The SE(3) exponential: x - x_n = R_n V(psi) q_u.
    for (unsigned int v = 0; v < rotations_.size(); ++v)
      if (model_->vertex_is_used(v))
      {
        const VertexDofs  &dofs = model_->vertex_dofs(v);
        const Tensor<1, 3> dx =
            saved_rotations_[v] *
            (element::so3_left_jacobian(vertex_block(increment, dofs, rx)) *
             vertex_block(increment, dofs, ux));
        for (unsigned int d = 0; d < 3; ++d)
          displacement[dofs[ux + d]] = dx[d];
      }
  }

  void ShellState::set_step_increment(const Vector<double> &increment)
  {
    if (!body_frame_translations_)
    {
      set_step_displacement(increment);
      return;
    }
    Vector<double> displacement;
    step_displacement(increment, displacement);
    set_step_displacement(displacement);
  }

  void ShellState::set_step_displacement(const Vector<double> &displacement)
  {
    values_ = saved_values_;
    values_ += displacement;
    if (!finite_rotations_)
      return;
    for (unsigned int v = 0; v < rotations_.size(); ++v)
      if (model_->vertex_is_used(v))
      {
        rotations_[v] = saved_rotations_[v] *
                        element::rotation_exp(vertex_block(
                            displacement, model_->vertex_dofs(v), rx));
        store_rotation_vector(v);
      }
  }

  void ShellState::set_body_frame_translations(bool body_frame)
  {
    if (body_frame && !finite_rotations_)
      throw std::invalid_argument(
          "Time integration/Lie group = SE3 needs finite rotations "
          "(Element/Formulation = corotational)");
    body_frame_translations_ = body_frame;
  }

  bool ShellState::body_frame_translations() const
  {
    return body_frame_translations_;
  }

  Tensor<1, 3> ShellState::body_step_translation(unsigned int v) const
  {
    const VertexDofs &dofs = model_->vertex_dofs(v);
    return transpose(saved_rotations_[v]) *
           (vertex_block(values_, dofs, ux) -
            vertex_block(saved_values_, dofs, ux));
  }

  Tensor<2, 3> ShellState::step_translation_jacobian(unsigned int v) const
  {
    if (!body_frame_translations_)
      return identity();
    return element::so3_left_jacobian_inverse(step_rotation(v)) *
           transpose(saved_rotations_[v]);
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

  void ShellState::load(const Vector<double>            &values,
                        const std::vector<Tensor<2, 3>> &rotations,
                        const Vector<double>            &velocity,
                        const Vector<double>            &acceleration)
  {
    if (values.size() != values_.size() || velocity.size() != values_.size() ||
        acceleration.size() != values_.size() ||
        rotations.size() != rotations_.size())
      throw std::invalid_argument(
          "it holds " + std::to_string(values.size()) + " DoFs and " +
          std::to_string(rotations.size()) +
          " vertex rotations, the scene's "
          "mesh has " +
          std::to_string(values_.size()) + " and " +
          std::to_string(rotations_.size()) + " (another mesh or refinement)");
    values_       = values;
    rotations_    = rotations;
    velocity_     = velocity;
    acceleration_ = acceleration;
    save();
  }

  const std::vector<Tensor<2, 3>> &ShellState::rotations() const
  {
    return rotations_;
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
