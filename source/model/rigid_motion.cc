#include <coshell/base/constants.h>
#include <coshell/base/expressions.h>
#include <coshell/element/corotational.h>
#include <coshell/model/rigid_motion.h>

#include <deal.II/base/utilities.h>

#include <stdexcept>

namespace coshell::model
{
  using namespace dealii;

  Tensor<1, 3> parse_three_values(const std::string &text,
                                  const std::string &where)
  {
    const std::vector<double> values = base::parse_constant_list(text, where);
    if (values.size() != 3)
      throw std::invalid_argument(where + ": '" + text +
                                  "' is not three values 'a, b, c'");
    return Tensor<1, 3>({values[0], values[1], values[2]});
  }

  void RigidMotion::declare_entries(ParameterHandler &prm)
  {
    prm.declare_entry("Translation", "0; 0; 0", Patterns::Anything(),
                      "d(t): three muparser expressions of the time t (s) "
                      "separated by ';'. Unit: length (mm in the IOL "
                      "scenes).");
    prm.declare_entry("Rotation axis", "0, 0, 1", Patterns::Anything(),
                      "Axis of the rigid rotation (normalized here; each "
                      "component a number or an expression of the scene's "
                      "Constants). Unit: dimensionless.");
    prm.declare_entry("Rotation angle", "0", Patterns::Anything(),
                      "angle(t): muparser expression of t (s) (pi is "
                      "defined). Unit: rad.");
    prm.declare_entry("Rotation centre", "0, 0, 0", Patterns::Anything(),
                      "A point on the rotation axis; each coordinate a "
                      "number or an expression of the scene's Constants. "
                      "Unit: length (mm in the IOL scenes).");
  }

  void RigidMotion::parse_entries(ParameterHandler  &prm,
                                  const std::string &where)
  {
    translation = base::parse_expressions<1>(prm.get("Translation"), 3, "x,t",
                                             true, "t", where + "/Translation");
    angle = base::parse_expressions<1>(prm.get("Rotation angle"), 1, "x,t",
                                       true, "t", where + "/Rotation angle");
    axis =
        parse_three_values(prm.get("Rotation axis"), where + "/Rotation axis");
    if (axis.norm() == 0)
      throw std::invalid_argument(where + "/Rotation axis: must not be zero");
    axis /= axis.norm();
    centre = Point<3>(parse_three_values(prm.get("Rotation centre"),
                                         where + "/Rotation centre"));
  }

  Tensor<1, 3> RigidMotion::rotation_vector(double time) const
  {
    angle->set_time(time);
    return angle->value(Point<1>()) * axis;
  }

  Tensor<1, 3> RigidMotion::displacement(double time) const
  {
    translation->set_time(time);
    Vector<double> d(3);
    translation->vector_value(Point<1>(), d);
    return Tensor<1, 3>({d[0], d[1], d[2]});
  }

  RigidMotion::Pose RigidMotion::pose(double time) const
  {
    const Tensor<2, 3> R = element::rotation_exp(rotation_vector(time));
    return {R, centre - R * centre + displacement(time)};
  }
} // namespace coshell::model
