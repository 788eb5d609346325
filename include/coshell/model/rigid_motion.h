#pragma once

#include <deal.II/base/function_parser.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <memory>
#include <string>

namespace coshell::model
{
  /// A rigid motion given as functions of time t: x(t) = c + R(t) (X - c)
  /// + d(t), with R(t) the rotation by angle(t) about a fixed axis through
  /// the centre c. Shared by prescribed motions of shell vertices and by
  /// the motion of rigid obstacles.
  struct RigidMotion
  {
    /// d(t): 3 components; angle(t): 1 component (muparser of t).
    std::shared_ptr<dealii::FunctionParser<1>> translation, angle;
    dealii::Tensor<1, 3>                       axis;
    dealii::Point<3>                           centre;

    /// Declares "Translation", "Rotation axis", "Rotation angle" and
    /// "Rotation centre" in the current subsection.
    static void declare_entries(dealii::ParameterHandler &prm);
    /// Parses them; throws std::invalid_argument "<where>/<entry>: ...".
    void parse_entries(dealii::ParameterHandler &prm, const std::string &where);

    /// Rotation vector angle(t) * axis at time t, rad.
    dealii::Tensor<1, 3> rotation_vector(double time) const;
    /// d(t).
    dealii::Tensor<1, 3> displacement(double time) const;
    /// The rigid motion at time t: R(t) and the image of a point.
    struct Pose
    {
      dealii::Tensor<2, 3> rotation;
      dealii::Tensor<1, 3> translation; ///< x = rotation * X + translation
      dealii::Point<3>     operator()(const dealii::Point<3> &X) const
      {
        return dealii::Point<3>(rotation * X + translation);
      }
    };
    Pose pose(double time) const;
  };

  /// "a, b, c" -> a vector, each value a number or an expression of the
  /// scene's Constants; throws std::invalid_argument naming 'where'.
  dealii::Tensor<1, 3> parse_three_values(const std::string &text,
                                          const std::string &where);
} // namespace coshell::model
