// Contact state for checkpoint and restart (Output/Checkpoint interval).

#include <coshell/contact/contact.h>

#include <limits>
#include <stdexcept>

namespace coshell::contact
{
  using namespace dealii;

  namespace
  {
    constexpr unsigned int normal_force_size = 13;

    const std::vector<double> &
    array(const std::map<std::string, std::vector<double>> &arrays,
          const std::string                                &name,
          std::size_t                                       size)
    {
      const auto found = arrays.find(name);
      if (found == arrays.end() || (size != 0 && found->second.size() != size))
        throw std::invalid_argument(
            "its contact state '" + name +
            "' is missing or of another size (another scene?)");
      return found->second;
    }
  } // namespace

  std::map<std::string, std::vector<double>> Contact::checkpoint_arrays() const
  {
    std::map<std::string, std::vector<double>> arrays;
    // save() doubles kappa when the barrier got too stiff a spring.
    const bool stiffen        = pair_potential_->stiffens(smallest_gap_);
    arrays["contact_scalars"] = {stiffen ? 2 * kappa_ : kappa_, target_time_};
    arrays["contact_obstacle_work"]      = obstacle_work();
    arrays["contact_obstacle_potential"] = potential_per_obstacle_;
    for (unsigned int o = 0; o < current_.size(); ++o)
    {
      const std::string number = std::to_string(o);
      auto &positions          = arrays["contact_obstacle_positions_" + number];
      for (const Point<3> &p : current_[o])
        positions.insert(positions.end(), {p[0], p[1], p[2]});
      const Vector<double> force = model_.to_vertex_order(shell_force_[o]);
      arrays["contact_shell_force_" + number].assign(force.begin(),
                                                     force.end());
    }
    auto &lagged = arrays["contact_lagged_normal_forces"];
    for (const NormalForce &n : normal_forces_)
      lagged.insert(lagged.end(),
                    {double(n.pair.shell_vertex_side), double(n.pair.obstacle),
                     double(n.pair.shell), double(n.pair.other), n.pair.area,
                     double(n.pair.self), double(n.pair.edge_edge), n.force,
                     n.closest[0], n.closest[1], n.normal[0], n.normal[1],
                     n.normal[2]});
    return arrays;
  }

  void Contact::restore_checkpoint_arrays(
      const std::map<std::string, std::vector<double>> &arrays,
      const model::ShellState                          &state,
      double                                            time)
  {
    const auto &scalars = array(arrays, "contact_scalars", 2);
    kappa_              = scalars[0];
    obstacle_work_ = array(arrays, "contact_obstacle_work", current_.size());
    potential_per_obstacle_ =
        array(arrays, "contact_obstacle_potential", current_.size());
    saved_potential_per_obstacle_ = potential_per_obstacle_;
    for (unsigned int o = 0; o < current_.size(); ++o)
    {
      const std::string number = std::to_string(o);
      const auto       &positions =
          array(arrays, "contact_obstacle_positions_" + number,
                3 * target_[o].size());
      for (unsigned int i = 0; i < current_[o].size(); ++i)
        current_[o][i] = Point<3>(positions[3 * i], positions[3 * i + 1],
                                  positions[3 * i + 2]);
      const auto &force = array(arrays, "contact_shell_force_" + number, 0);
      shell_force_[o] =
          model_.from_vertex_order(Vector<double>(force.begin(), force.end()));
      obstacle_moved(o);
    }
    saved_shell_force_ = shell_force_;
    saved_             = current_;
    target_time_       = -std::numeric_limits<double>::max();
    set_target_time(scalars[1]);
    saved_time_        = time;
    const auto &lagged = array(arrays, "contact_lagged_normal_forces", 0);
    lagged_normal_forces_.clear();
    for (std::size_t k = 0; k + normal_force_size <= lagged.size();
         k += normal_force_size)
    {
      const double *n = &lagged[k];
      lagged_normal_forces_.push_back(
          {{n[0] != 0, unsigned(n[1]), unsigned(n[2]), unsigned(n[3]), n[4],
            n[5] != 0, n[6] != 0},
           n[7],
           {n[8], n[9]},
           Tensor<1, 3>({n[10], n[11], n[12]})});
    }
    positions_       = shell_positions(state);
    saved_positions_ = positions_;
    update_stretches(state);
    forget_gaps();
    projecting_this_step_ = false;
  }
} // namespace coshell::contact
