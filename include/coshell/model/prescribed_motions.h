#pragma once

#include <coshell/model/rigid_motion.h>
#include <coshell/model/shell_problem.h>

#include <deal.II/base/function_parser.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/lac/affine_constraints.h>

#include <memory>
#include <string>
#include <vector>

namespace coshell::model
{
  /// A rigid motion of a set of vertices, given as functions of time t:
  /// x(t) = c + R(t) (X - c) + d(t) and nodal rotation R(t), with R(t) the
  /// rotation by angle(t) about a fixed axis through the centre c. Each of
  /// the listed components is prescribed: translations one by one, the
  /// rotation as a whole (all three components or none). With linear
  /// kinematics the motion is linearized: u = theta(t) x (X - c) + d(t).
  struct PrescribedMotion
  {
    /// "boundary N" or "point x y z"; used to name the motion in messages.
    std::string      where;
    int              boundary_id = -1;
    dealii::Point<3> point;
    bool             translations[3] = {false, false, false};
    bool             rotation        = false;
    RigidMotion      motion;
  };

  /// prm subsection "Prescribed motions", with "Motion 1" ... "Motion 8".
  class PrescribedMotions
  {
  public:
    static constexpr unsigned int max_motions = 8;

    static void declare_parameters(dealii::ParameterHandler &prm);
    /// Throws std::invalid_argument naming the motion and entry.
    void parse_parameters(dealii::ParameterHandler &prm);

    /// Numbers (1-based) of the motions defined in the prm.
    std::vector<unsigned int> defined() const;
    bool                      empty() const;

    /// Adds a homogeneous line for every DoF the listed motions prescribe
    /// (throws naming the motion if its boundary id is not in the mesh).
    void make_constraints(const ShellModel                  &model,
                          const std::vector<unsigned int>   &active,
                          dealii::AffineConstraints<double> &constraints) const;

    /// The increments the listed motions still need at a time.
    PrescribedIncrementFunction
    increments(const ShellModel                &model,
               const std::vector<unsigned int> &active) const;

  private:
    std::vector<PrescribedMotion> motions_; ///< index = number - 1
  };
} // namespace coshell::model
