// What a device that drives an obstacle needs besides the force, and what
// a linearized step needs to report the load at its end: how the load
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
      slopes.followed = true;
  }

  void Contact::reset_force_slopes()
  {
    for (ForceSlopes &slopes : force_slopes_)
    {
      slopes.entries.clear();
      slopes.stiffness = 0;
    }
  }

  bool Contact::follows_force(const Pair &pair) const
  {
    return !pair.self && force_slopes_[pair.obstacle].followed;
  }

  // A friction pair: its reaction on the obstacle is minus the sum of its
  // forces on the shell points, whose derivative the block holds with a
  // minus sign (rows of axis i % 3), and it acts at a fixed point.
  void
  Contact::add_force_slopes(const Pair                                 &pair,
                            const std::vector<types::global_dof_index> &dofs,
                            const FullMatrix<double> &shell_block,
                            const Tensor<1, 3>       &application)
  {
    ForceSlopes &slopes = force_slopes_[pair.obstacle];
    for (unsigned int j = 0; j < dofs.size(); ++j)
    {
      ForceSlopes::Entry entry{dofs[j], {}, {}};
      for (unsigned int i = 0; i < dofs.size(); ++i)
      {
        entry.force[i % 3] += shell_block(i, j);
        slopes.stiffness[i % 3][j % 3] += shell_block(i, j);
      }
      entry.moment = cross_product_3d(application, entry.force);
      slopes.entries.push_back(entry);
    }
  }

  // A contact pair: the force on obstacle point k is -g_k (its energy's
  // gradient there), so its derivative is the Hessian's row of k, and the
  // moment's is the point's arm across it (the obstacle does not move
  // within the evaluation).
  void
  Contact::add_force_slopes(const Pair                                 &pair,
                            const std::vector<types::global_dof_index> &dofs,
                            const PairEnergy                           &energy,
                            const std::array<Point<3>, 4>              &points)
  {
    ForceSlopes       &slopes = force_slopes_[pair.obstacle];
    const unsigned int first  = shell_coordinates(pair).first;
    for (unsigned int j = 0; j < dofs.size(); ++j)
    {
      ForceSlopes::Entry entry{dofs[j], {}, {}};
      for (unsigned int k = 0; k < 4; ++k)
        if (on_obstacle(pair, k))
        {
          Tensor<1, 3> force;
          for (unsigned int c = 0; c < 3; ++c)
            force[c] = -energy.hessian[3 * k + c][first + j];
          entry.force += force;
          entry.moment += cross_product_3d(points[k], force);
        }
      for (unsigned int i = 0; i < dofs.size(); ++i)
        slopes.stiffness[i % 3][j % 3] += energy.hessian[first + i][first + j];
      slopes.entries.push_back(entry);
    }
  }

  Vector<double> Contact::load_gradient(unsigned int obstacle,
                                        unsigned int axis,
                                        bool         moment) const
  {
    const ForceSlopes &slopes = force_slopes_[obstacle];
    Vector<double>     gradient(slopes.followed ? model_.n_dofs() : 0);
    for (const ForceSlopes::Entry &entry : slopes.entries)
      gradient[entry.dof] += (moment ? entry.moment : entry.force)[axis];
    return gradient;
  }

  // The blocks are symmetric (a contact energy's Hessian, lagged
  // friction's), so dF.e/du is also H_ss e, the shell's answer to the
  // obstacle's move along e.
  Contact::InputCoupling Contact::input_coupling(unsigned int obstacle) const
  {
    const ForceSlopes &slopes = force_slopes_[obstacle];
    InputCoupling      input;
    if (!parameters_.obstacles[obstacle].input || !slopes.followed)
      return input;
    const Tensor<1, 3> &direction =
        parameters_.obstacles[obstacle].input_direction;
    const Tensor<1, 3> e = direction / direction.norm();
    input.coupling.reinit(model_.n_dofs());
    for (const ForceSlopes::Entry &entry : slopes.entries)
      input.coupling[entry.dof] += entry.force * e;
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
      for (const ForceSlopes::Entry &entry : force_slopes_[o].entries)
      {
        loads_[o].force += entry.force * correction[entry.dof];
        loads_[o].moment += entry.moment * correction[entry.dof];
      }
  }
} // namespace coshell::contact
