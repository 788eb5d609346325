// What a device that drives an obstacle needs besides the force: how the
// force changes with the device's input. The contact and friction energies
// of a pair depend on differences of its points' positions only, so
// translating the obstacle by e changes them as translating the pair's
// shell points by -e does: the exact Hessian's shell block H_ss gives the
// obstacle's couplings too (H_so e = -H_ss e, e^T H_oo e = e^T H_ss e), and
// no obstacle block is formed. The tangent's block may be projected to
// positive semi-definite; that projection breaks the identity, so the
// exact block is used here.

#include <coshell/contact/contact.h>

namespace coshell::contact
{
  using namespace dealii;

  void Contact::reset_input_couplings()
  {
    for (InputCoupling &input : input_couplings_)
    {
      input.coupling  = 0;
      input.stiffness = 0;
    }
  }

  bool Contact::drives_input(const Pair &pair) const
  {
    return !pair.self && input_couplings_[pair.obstacle].coupling.size() > 0;
  }

  void
  Contact::add_input_coupling(const Pair                                 &pair,
                              const std::vector<types::global_dof_index> &dofs,
                              const FullMatrix<double> &shell_block)
  {
    InputCoupling      &input = input_couplings_[pair.obstacle];
    const Tensor<1, 3> &direction =
        parameters_.obstacles[pair.obstacle].input_direction;
    const Tensor<1, 3> e = direction / direction.norm();
    // The DoFs are the translations x, y, z of the pair's shell points.
    for (unsigned int i = 0; i < dofs.size(); ++i)
    {
      double row = 0;
      for (unsigned int j = 0; j < dofs.size(); ++j)
        row += shell_block(i, j) * e[j % 3];
      input.coupling[dofs[i]] += row;
      input.stiffness += e[i % 3] * row;
    }
  }

  void
  Contact::add_input_coupling(const Pair                                 &pair,
                              const std::vector<types::global_dof_index> &dofs,
                              const PairEnergy &energy)
  {
    const unsigned int first = shell_coordinates(pair).first;
    FullMatrix<double> shell_block(dofs.size(), dofs.size());
    for (unsigned int i = 0; i < dofs.size(); ++i)
      for (unsigned int j = 0; j < dofs.size(); ++j)
        shell_block(i, j) = energy.hessian[first + i][first + j];
    add_input_coupling(pair, dofs, shell_block);
  }
} // namespace coshell::contact
