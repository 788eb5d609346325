#include <coshell/base/constants.h>
#include <coshell/model/rigid_motion.h>

#include <deal.II/base/parameter_handler.h>

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace
{
  using coshell::base::Constants;

  /// Parses 'values' (and 'positive', 'changes') as a prm's Constants
  /// subsection.
  void parse_constants(const std::string &values,
                       const std::string &positive     = "",
                       const std::string &changes      = "",
                       const std::string &requirements = "")
  {
    dealii::ParameterHandler prm;
    Constants::declare_parameters(prm);
    prm.enter_subsection("Constants");
    prm.set("Values", values);
    prm.set("Positive", positive);
    prm.set("Changes", changes);
    prm.set("Requirements", requirements);
    prm.leave_subsection();
    Constants::parse_parameters(prm);
  }

  std::string message_of(const std::string &values,
                         const std::string &positive     = "",
                         const std::string &changes      = "",
                         const std::string &requirements = "")
  {
    try
    {
      parse_constants(values, positive, changes, requirements);
    }
    catch (const std::invalid_argument &error)
    {
      return error.what();
    }
    return "";
  }
} // namespace

// The injection's derived time: the expression sees the constants before
// it, and a comma inside max(...) does not end the entry.
TEST(Constants, ValuesMayBeExpressionsOfEarlierConstants)
{
  parse_constants("speed = 5, start = -6.9, tip = 15, out = 1.3, "
                  "push = out + (tip - start) / speed, "
                  "later = max(push, 2 * pi)");
  const auto &constants = coshell::base::expression_constants();
  EXPECT_DOUBLE_EQ(constants.at("push"), 1.3 + 21.9 / 5);
  EXPECT_DOUBLE_EQ(constants.at("later"), 2 * M_PI);
  EXPECT_DOUBLE_EQ(coshell::base::evaluate_constant_expression(
                       "push - out", constants, "Stage 2/Duration"),
                   21.9 / 5);
  const auto named =
      coshell::base::parse_named_values("a = tip, b = 0.45", "Gmsh parameters");
  ASSERT_EQ(named.size(), 2u);
  EXPECT_EQ(named[0].first, "a");
  EXPECT_DOUBLE_EQ(named[0].second, 15);
}

// A constant used before it is defined, a misspelt one and a division by
// a zero constant are refused, naming the entry; a positive constant is
// checked where it is defined, before a later one divides by it.
TEST(Constants, BadValuesAreRefusedByName)
{
  EXPECT_NE(message_of("push = out + 1, out = 1.3")
                .find("Constants/Values: push: cannot evaluate 'out + 1'"),
            std::string::npos);
  EXPECT_NE(message_of("speed = 0, push = 1 / speed")
                .find("Constants/Values: push: '1 / speed' is not finite"),
            std::string::npos);
  EXPECT_NE(message_of("speed = 0, push = 1 / speed", "speed")
                .find("Constants/Values: speed = 0 must be > 0"),
            std::string::npos);
  EXPECT_NE(message_of("speed 5").find("'speed 5' is not of the form "
                                       "'name = value'"),
            std::string::npos);
  EXPECT_NE(message_of("speed = 5", "sped")
                .find("Constants/Positive: 'sped' is not a constant"),
            std::string::npos);
  EXPECT_NE(message_of("pi = 3").find("pi is pi or given twice"),
            std::string::npos);
}

// A point or a direction (Rotation centre, Force direction, ...) takes
// constants too: the tuck's hinges follow its hinge_x and hinge_height.
TEST(Constants, ThreeValuesMayBeConstantExpressions)
{
  parse_constants("hinge_x = 3.8, hinge_height = 0.525");
  const auto centre = coshell::model::parse_three_values(
      "-hinge_x, 0, max(hinge_height, 0.2)", "Rotation centre");
  EXPECT_DOUBLE_EQ(centre[0], -3.8);
  EXPECT_DOUBLE_EQ(centre[1], 0);
  EXPECT_DOUBLE_EQ(centre[2], 0.525);
  const auto message = [](const std::string &text)
  {
    try
    {
      coshell::model::parse_three_values(text, "Obstacle 3/Rotation centre");
    }
    catch (const std::invalid_argument &error)
    {
      return std::string(error.what());
    }
    return std::string();
  };
  EXPECT_NE(message("1, 2").find("Obstacle 3/Rotation centre: '1, 2' is not "
                                 "three values 'a, b, c'"),
            std::string::npos);
  EXPECT_NE(message("-hinge, 0, 0")
                .find("Obstacle 3/Rotation centre: cannot evaluate '-hinge'"),
            std::string::npos);
}

// A change on the command line replaces one design value where it stands:
// what is derived from it after follows, what comes before does not.
TEST(Constants, ChangesReplaceValuesWhereTheyStand)
{
  const std::string values =
      "out = 1.3, speed = 5, push = out + 21.9 / speed, before = 2";
  parse_constants(values, "speed", "speed = 1.5, before = out * 2");
  const auto &constants = coshell::base::expression_constants();
  EXPECT_DOUBLE_EQ(constants.at("speed"), 1.5);
  EXPECT_DOUBLE_EQ(constants.at("push"), 1.3 + 21.9 / 1.5);
  EXPECT_DOUBLE_EQ(constants.at("before"), 2.6);
  EXPECT_EQ(message_of(values, "speed", "speed = 0"),
            "Constants/Changes: speed = 0 must be > 0 (it is listed in "
            "Constants/Positive)");
  EXPECT_EQ(message_of(values, "", "sped = 1.5"),
            "Constants/Changes: 'sped' is not a constant of "
            "Constants/Values");
  EXPECT_EQ(message_of(values, "", "speed = 1, speed = 2"),
            "Constants/Changes: speed is changed twice");
  EXPECT_EQ(message_of(values, "", "speed"),
            "Constants/Changes: 'speed' is not of the form 'name = value'");
  // A changed value may use only the constants before its place.
  EXPECT_NE(message_of(values, "", "out = push")
                .find("Constants/Changes: out: cannot evaluate 'push'"),
            std::string::npos);
}

// A requirement holds or refuses the scene with its message and the values
// of the constants it names (pi and constants it does not name left out);
// it sees the changed values; an entry without a message is refused.
TEST(Constants, RequirementsRefuseWithTheirMessage)
{
  const std::string values    = "radius = 0.9, area = pi * radius^2, other = 1";
  const std::string tip_range = "radius >= 0.7 && radius <= 1.75: the tip "
                                "must be 1.4 to 3.5 mm";
  EXPECT_EQ(message_of(values, "", "", tip_range + "; area > 2: wide enough"),
            "");
  EXPECT_EQ(message_of(values, "", "radius = 0.6", tip_range),
            "Constants/Requirements: the tip must be 1.4 to 3.5 mm ('radius "
            ">= 0.7 && radius <= 1.75' is false with radius = 0.6)");
  EXPECT_EQ(message_of(values, "", "", "area >= pi * other: wide enough"),
            "Constants/Requirements: wide enough ('area >= pi * other' is "
            "false with area = 2.54469, other = 1)");
  EXPECT_EQ(message_of(values, "", "", "radius > 1"),
            "Constants/Requirements: 'radius > 1' is not of the form "
            "'expression: message'");
  EXPECT_NE(message_of(values, "", "", "radious > 1: typo")
                .find("Constants/Requirements: cannot evaluate 'radious > 1'"),
            std::string::npos);
}
