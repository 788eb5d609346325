#include <coshell/driver/interactive.h>

#include <coshell/base/expressions.h>
#include <coshell/base/stopwatch.h>

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace coshell::driver
{
  using namespace dealii;

  InteractiveSession::InteractiveSession(std::istream &commands,
                                         std::ostream &replies)
      : commands_(commands), replies_(replies)
  {
  }

  void InteractiveSession::connect_driven_obstacles(
      contact::ContactParameters &contact)
  {
    // The driven obstacles share one input path.
    for (auto &obstacle : contact.obstacles)
      if (obstacle.input_direction.norm() > 0)
      {
        if (!input_)
          input_ = std::make_shared<contact::InputPath>();
        obstacle.input = input_;
      }
  }

  bool InteractiveSession::drives_obstacles() const
  {
    return input_ != nullptr;
  }

  bool InteractiveSession::ended() const
  {
    return ended_;
  }

  double InteractiveSession::reached() const
  {
    return reached_;
  }

  bool InteractiveSession::has_target() const
  {
    return target_.has_value();
  }

  void InteractiveSession::reply_done(double time)
  {
    replies_ << "done " << time << std::endl;
  }

  double InteractiveSession::advance(
      double                                     start,
      double                                     end,
      const std::function<void(double, double)> &integrate)
  {
    double now = start;
    while (now < end && !ended_)
    {
      read_ahead(now);
      if (ended_)
        break;
      const double to = std::min(*target_, end);
      if (to > now)
      {
        advance_from_    = now;
        advance_started_ = std::chrono::steady_clock::now();
        integrate(now, to);
        computing_s_ += base::seconds_since(advance_started_);
        simulated_s_ += to - now;
      }
      now = std::max(now, to);
      if (*target_ <= now)
      {
        reply_done(now);
        target_.reset();
      }
    }
    reached_ = now;
    return now;
  }

  // Also called before a static stage, which runs whole, so its decision
  // comes before it: a "quit" after a target at the end of the dynamic
  // stage before it ends the run there instead of after the static stage.
  void InteractiveSession::read_ahead(double now)
  {
    if (ended_ || target_)
      return;
    target_ = next_target(now);
    if (!target_)
    {
      ended_   = true;
      reached_ = now;
    }
  }

  // Interactive runs count only the time spent computing, not the time
  // spent waiting for the next target.
  double InteractiveSession::real_time_factor(double time) const
  {
    return (simulated_s_ + time - advance_from_) /
           std::max(computing_s_ + base::seconds_since(advance_started_), 1e-9);
  }

  namespace
  {
    /// A protocol line "t" or "t s": the target time and the input.
    struct Target
    {
      double                time;
      std::optional<double> input;
    };

    std::optional<Target> parse_target(const std::string &line)
    {
      std::istringstream       words(line);
      std::vector<std::string> parts{std::istream_iterator<std::string>(words),
                                     std::istream_iterator<std::string>()};
      if (parts.empty() || parts.size() > 2)
        return std::nullopt;
      // strtod reads "nan" and "inf" too: a target that is never reached
      // or an obstacle sent to infinity.
      const auto time = base::as_number(parts[0]);
      if (!time || !std::isfinite(*time))
        return std::nullopt;
      if (parts.size() == 1)
        return Target{*time, std::nullopt};
      const auto input = base::as_number(parts[1]);
      if (!input || !std::isfinite(*input))
        return std::nullopt;
      return Target{*time, *input};
    }
  } // namespace

  std::optional<double> InteractiveSession::next_target(double now)
  {
    std::string line;
    while (std::getline(commands_, line))
    {
      line = Utilities::trim(line);
      if (line.empty() || line[0] == '#')
        continue;
      if (line == "quit")
        return std::nullopt;
      const auto target = parse_target(line);
      if (!target)
        replies_ << "error cannot read '" << line
                 << "' as a finite time in s, or a time and an input"
                 << std::endl;
      else if (target->input && !input_)
        replies_ << "error '" << line
                 << "': no obstacle takes input (Contact/Obstacle k/Input "
                    "direction)"
                 << std::endl;
      else if (target->input && !(target->time > now))
        replies_ << "error '" << line << "': an input is for a time after "
                 << "the present, " << now << " s" << std::endl;
      else
      {
        if (target->input)
          input_->append(now, target->time, *target->input);
        return target->time;
      }
    }
    return std::nullopt;
  }

  void InteractiveSession::reply_step(const model::ShellProblem &problem,
                                      const contact::Contact    *contact,
                                      unsigned int               step,
                                      double                     time)
  {
    // Taken before the line is made: the replies' own work is not the
    // scene's.
    const double rtf   = real_time_factor(time);
    auto        &reply = replies_;
    reply << "step " << step << ' ' << time;
    if (contact)
      for (unsigned int o = 0; o < contact->obstacles().size(); ++o)
      {
        // A device renders the force along its own axis, with its sign:
        // the magnitude counts the force across the axis too, and cannot
        // tell a shell pushing the tool back from one dragging it along
        // (friction).
        const auto &force     = contact->obstacle_loads()[o].force;
        const auto &direction = contact->obstacles()[o].input_direction;
        reply << ' '
              << (direction.norm() > 0 ? force * direction / direction.norm()
                                       : force.norm());
      }
    const auto &model = problem.model();
    Point<3>    centroid;
    unsigned    n = 0;
    for (unsigned int v = 0; v < model.surface().n_vertices(); ++v)
      if (model.vertex_is_used(v))
      {
        centroid += model.surface().get_vertices()[v];
        for (unsigned int d = 0; d < 3; ++d)
          centroid[d] += problem.state().values()[model.vertex_dofs(v)[d]];
        ++n;
      }
    centroid /= double(n);
    reply << ' ' << centroid << ' ' << rtf << std::endl;
  }

  namespace
  {
    /// dr/ds of the driven obstacles' common input, condensed.
    Vector<double> input_load(const model::ShellProblem &problem,
                              const contact::Contact    &contact)
    {
      const auto    &obstacles = contact.obstacles();
      Vector<double> load(problem.model().n_dofs());
      for (unsigned int o = 0; o < obstacles.size(); ++o)
        if (const auto input = contact.input_coupling(o);
            input.coupling.size() > 0)
          load.add(obstacles[o].input_direction.norm(), input.coupling);
      problem.constraints().condense(load);
      return load;
    }
  } // namespace

  // The tangent K of the step, extended by the input s, holds the
  // obstacles' couplings: dr/ds = sum_o |d_o| c_o and, with the shell
  // held, dF_o/ds = -|d_o| a_o (contact::Contact::InputCoupling). The
  // shell's answer du/ds = K^-1 dr/ds adds c_o . du/ds: the Schur
  // complement of the shell in that extended tangent, which is what a
  // haptic loop's local model between two steps needs (Cavusoglu and
  // Tendick 2000; doc/user-guide/interactive.md).
  void InteractiveSession::reply_input_slopes(
      model::ShellProblem         &problem,
      contact::Contact            &contact,
      unsigned int                 step,
      double                       time,
      solvers::LinearSolver       &linear_solver,
      const std::function<void()> &factorize_exact_tangent)
  {
    // A linearized step's system is the step itself, and its factors
    // serve. Newton judges its last iterate without a tangent when it
    // expects convergence: its factors are then an iterate behind and
    // hold projected pair Hessians, and both move the slope it reports
    // (doc/validation/contact.md). So the state reached gets its exact tangent
    // (the couplings are assembled with it).
    Vector<double> response;
    contact.set_exact_tangent(true);
    try
    {
      factorize_exact_tangent();
      linear_solver.solve_with_factors(response, input_load(problem, contact));
    }
    catch (const std::exception &)
    {
      // The step has converged; only its slopes are missing (nan).
      response.reinit(problem.model().n_dofs());
      response = std::numeric_limits<double>::quiet_NaN();
    }
    contact.set_exact_tangent(false);
    const auto &obstacles = contact.obstacles();
    auto       &reply     = replies_;
    reply << "slope " << step << ' ' << input_->value(time);
    for (unsigned int o = 0; o < obstacles.size(); ++o)
      if (auto input = contact.input_coupling(o); input.coupling.size() > 0)
      {
        problem.constraints().condense(input.coupling);
        reply << ' '
              << input.coupling * response -
                     obstacles[o].input_direction.norm() * input.stiffness;
      }
    reply << std::endl;
  }
} // namespace coshell::driver
