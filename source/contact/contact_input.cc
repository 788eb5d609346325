// What a device that drives an obstacle needs besides the force, and what
// a linearized step needs to report the force at its end: how the force
// changes with the shell and with the obstacle. The contact and friction
// energies of a pair depend on differences of its points' positions only,
// so translating the obstacle by e changes them as translating the pair's
// shell points by -e does: the exact Hessian's shell block H_ss gives the
// obstacle's slopes too (H_so e = -H_ss e, e^T H_oo e = e^T H_ss e), and no
// obstacle block is formed. The tangent's block may be projected to
// positive semi-definite; that projection breaks the identity, so the
// exact block is used here.

#include <coshell/contact/contact.h>

#include <stdexcept>

namespace coshell::contact
{
  using namespace dealii;

  void Contact::follow_force_slopes()
  {
    for (ForceSlopes &slopes : force_slopes_)
      for (Vector<double> &gradient : slopes.gradients)
        gradient.reinit(model_.n_dofs());
  }

  void Contact::reset_force_slopes()
  {
    for (ForceSlopes &slopes : force_slopes_)
    {
      for (Vector<double> &gradient : slopes.gradients)
        gradient = 0;
      slopes.stiffness = 0;
    }
  }

  bool Contact::follows_force(const Pair &pair) const
  {
    return !pair.self && force_slopes_[pair.obstacle].gradients[0].size() > 0;
  }

  void
  Contact::add_force_slopes(const Pair                                 &pair,
                            const std::vector<types::global_dof_index> &dofs,
                            const FullMatrix<double> &shell_block)
  {
    ForceSlopes &slopes = force_slopes_[pair.obstacle];
    // The DoFs are the translations x, y, z of the pair's shell points,
    // so row i is axis i % 3: dF_k/du_j sums the rows of axis k. The block
    // is symmetric (a contact energy's Hessian, lagged friction's), so
    // gradients[k] is also H_ss e_k, the shell's answer to the obstacle's
    // move along axis k, which the input coupling uses.
    for (unsigned int i = 0; i < dofs.size(); ++i)
      for (unsigned int j = 0; j < dofs.size(); ++j)
      {
        slopes.gradients[i % 3][dofs[j]] += shell_block(i, j);
        slopes.stiffness[i % 3][j % 3] += shell_block(i, j);
      }
  }

  void
  Contact::add_force_slopes(const Pair                                 &pair,
                            const std::vector<types::global_dof_index> &dofs,
                            const PairEnergy                           &energy)
  {
    const unsigned int first = shell_coordinates(pair).first;
    FullMatrix<double> shell_block(dofs.size(), dofs.size());
    for (unsigned int i = 0; i < dofs.size(); ++i)
      for (unsigned int j = 0; j < dofs.size(); ++j)
        shell_block(i, j) = energy.hessian[first + i][first + j];
    add_force_slopes(pair, dofs, shell_block);
  }

  Contact::InputCoupling Contact::input_coupling(unsigned int obstacle) const
  {
    const ForceSlopes &slopes = force_slopes_[obstacle];
    InputCoupling      input;
    if (!parameters_.obstacles[obstacle].input ||
        slopes.gradients[0].size() == 0)
      return input;
    const Tensor<1, 3> &direction =
        parameters_.obstacles[obstacle].input_direction;
    const Tensor<1, 3> e = direction / direction.norm();
    input.coupling.reinit(model_.n_dofs());
    for (unsigned int k = 0; k < 3; ++k)
      input.coupling.add(e[k], slopes.gradients[k]);
    input.stiffness = e * (slopes.stiffness * e);
    return input;
  }

  void Contact::extrapolate_loads(const Vector<double> &correction)
  {
    if (!slopes_at_last_evaluation_)
      throw std::logic_error("Contact::extrapolate_loads: the last "
                             "evaluation assembled no tangent, so the force "
                             "slopes are not of its state");
    for (unsigned int o = 0; o < loads_.size(); ++o)
      if (force_slopes_[o].gradients[0].size() > 0)
        for (unsigned int k = 0; k < 3; ++k)
          loads_[o].force[k] += force_slopes_[o].gradients[k] * correction;
  }
} // namespace coshell::contact
