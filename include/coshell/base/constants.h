#pragma once

#include <deal.II/base/parameter_handler.h>

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace coshell::base
{
  /// The named constants of a scene (prm subsection "Constants"), usable in
  /// every expression of the prm (motions, thickness, density, stage load
  /// factors, vertex transformation) besides pi: a scene states its design
  /// values (a plunger's speed, a sag) once, with their units, and the
  /// ones that must be positive are checked before anything is built.
  class Constants
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm);
    /// Parses the constants, with "Changes" applied to "Values", and makes
    /// them those of every expression parsed afterwards. Throws
    /// std::invalid_argument naming the entry and the constant: a
    /// malformed entry, an unknown name in "Positive" or "Changes", a
    /// constant changed twice, a value that must be positive and is not,
    /// an entry of "Requirements" that is false (with its message).
    static void parse_parameters(dealii::ParameterHandler &prm);
  };

  /// "name = value, name = value" -> the pairs in order, each value a
  /// number or an expression of pi and the scene's Constants (commas inside
  /// parentheses belong to the expression). Throws std::invalid_argument
  /// "<where>: '<entry>' is not of the form 'name = value'" (a name is
  /// letters, digits and '_', not starting with a digit), or naming the
  /// value that cannot be evaluated.
  std::vector<std::pair<std::string, double>>
  parse_named_values(const std::string &text, const std::string &where);

  /// "a, b, ..." -> the values in order, each a number or an expression
  /// of pi and the scene's Constants (commas inside parentheses belong to
  /// the expression). Throws std::invalid_argument naming 'where' and the
  /// value that cannot be evaluated.
  std::vector<double> parse_constant_list(const std::string &text,
                                          const std::string &where);

  /// 'text' as a number, or as a muparser expression of the given
  /// constants. Throws std::invalid_argument "<where>: cannot evaluate
  /// '<text>' ..." or "... is not finite".
  double
  evaluate_constant_expression(const std::string                   &text,
                               const std::map<std::string, double> &constants,
                               const std::string                   &where);

  /// The constants every expression sees (pi and those of the scene).
  const std::map<std::string, double> &expression_constants();
} // namespace coshell::base
