#pragma once

// The --interactive protocol (doc/user-guide/interactive.md): dynamic
// stages advance to the target times read from standard input, and every
// step writes one line (and, with driven obstacles, a slope line) to
// standard output.

#include <coshell/contact/contact.h>
#include <coshell/model/shell_problem.h>
#include <coshell/solvers/linear_solver.h>

#include <chrono>
#include <functional>
#include <istream>
#include <memory>
#include <optional>
#include <ostream>

namespace coshell::driver
{
  /// An --interactive session, which spans the scene's dynamic stages: a
  /// target past a stage's end carries on into the next dynamic stage,
  /// and "quit" or the end of the input ends the run.
  class InteractiveSession
  {
  public:
    InteractiveSession(std::istream &commands, std::ostream &replies);

    /// Gives every obstacle with an Input direction the session's input
    /// path (the Contact made from these parameters keeps a handle on
    /// it).
    void connect_driven_obstacles(contact::ContactParameters &contact);
    /// Whether some obstacle follows the input.
    bool drives_obstacles() const;

    /// At 'now': the next target, if none is pending; "quit" or the end
    /// of the input ends the session there.
    void read_ahead(double now);
    /// "quit" or the end of the input was read: no later stage runs.
    bool ended() const;
    /// The simulated time (s) reached so far.
    double reached() const;
    /// A target time was read and is not reached yet.
    bool has_target() const;

    /// Integrates ('integrate(from, to)') from 'start' to each target
    /// read until 'end', "quit" or the end of the input (a target past
    /// 'end' is kept for the next stage), answering "done" at each
    /// target reached; returns the time reached.
    double advance(double                                     start,
                   double                                     end,
                   const std::function<void(double, double)> &integrate);
    /// The protocol's "done" line.
    void reply_done(double time);
    /// The protocol's line for one step: time, the force on each obstacle
    /// (N, magnitude, or the signed component along an Input direction),
    /// the shell's centroid and the real-time factor so far.
    void reply_step(const model::ShellProblem &problem,
                    const contact::Contact    *contact,
                    unsigned int               step,
                    double                     time);
    /// The slope line: the input s at 'time' and, per driven obstacle,
    /// dF/ds of its force along its direction, as the tangent of the
    /// state reached answers a change of s. 'factorize_exact_tangent'
    /// leaves the linear solver holding the factors of the state's exact
    /// tangent (a linearized step's own factors serve as they are).
    void
    reply_input_slopes(model::ShellProblem         &problem,
                       contact::Contact            &contact,
                       unsigned int                 step,
                       double                       time,
                       solvers::LinearSolver       &linear_solver,
                       const std::function<void()> &factorize_exact_tangent);

  private:
    std::istream &commands_;
    std::ostream &replies_;
    /// The input of the obstacles with an Input direction (none: no
    /// obstacle takes input).
    std::shared_ptr<contact::InputPath> input_;
    /// The target time (s) read and not reached yet.
    std::optional<double> target_;
    bool                  ended_   = false;
    double                reached_ = 0;
    /// Simulated and wall time (s) of the integrations finished so far,
    /// the start of the current one and its wall clock.
    double                                simulated_s_ = 0, computing_s_ = 0;
    double                                advance_from_ = 0;
    std::chrono::steady_clock::time_point advance_started_;

    /// Simulated over computing time of the session up to 'time' of the
    /// current integration; waiting for input is not counted.
    double real_time_factor(double time) const;
    /// The next target time, its input (if any) appended to the path
    /// from 'now'; nothing at "quit" or the end of the input. Blank and
    /// '#' lines are skipped; a line that is not a target is answered
    /// with an error line.
    std::optional<double> next_target(double now);
  };
} // namespace coshell::driver
