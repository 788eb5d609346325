#include <coshell/base/constants.h>
#include <coshell/base/expressions.h>

#include <deal.II/base/numbers.h>
#include <deal.II/base/utilities.h>

#include <deal.II/base/function_parser.h>
#include <deal.II/base/point.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <iomanip>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace coshell::base
{
  using namespace dealii;

  namespace
  {
    std::map<std::string, double> &scene_constants()
    {
      static std::map<std::string, double> constants{{"pi", numbers::PI}};
      return constants;
    }

    bool is_name(const std::string &name)
    {
      return !name.empty() &&
             !std::isdigit(static_cast<unsigned char>(name[0])) &&
             std::all_of(name.begin(), name.end(),
                         [](char c) {
                           return std::isalnum(static_cast<unsigned char>(c)) ||
                                  c == '_';
                         });
    }

    /// The entries of 'text' between the commas outside parentheses, so
    /// that an expression's max(a, b) stays one entry.
    std::vector<std::string> split_entries(const std::string &text)
    {
      std::vector<std::string> entries(1);
      int                      depth = 0;
      for (const char c : text)
      {
        depth += (c == '(') - (c == ')');
        if (c == ',' && depth == 0)
          entries.emplace_back();
        else
          entries.back() += c;
      }
      if (Utilities::trim(text).empty())
        return {};
      return entries;
    }

    /// "name = value, ..." -> the names and the values' texts in order.
    std::vector<std::pair<std::string, std::string>>
    split_named_entries(const std::string &text, const std::string &where)
    {
      std::vector<std::pair<std::string, std::string>> named;
      for (const std::string &entry : split_entries(text))
      {
        const auto equals = entry.find('=');
        const auto name =
            Utilities::trim(entry.substr(0, std::min(equals, entry.size())));
        const auto value = equals == std::string::npos
                               ? std::string()
                               : Utilities::trim(entry.substr(equals + 1));
        if (!is_name(name) || value.empty())
          throw std::invalid_argument(where + ": '" + Utilities::trim(entry) +
                                      "' is not of the form 'name = value'");
        named.emplace_back(name, value);
      }
      return named;
    }

    /// A constant's text and the entry it came from, for messages.
    struct Definition
    {
      std::string name, expression, where;
    };

    /// The entries of Values, each of those named in 'changes' given the
    /// changed text in its place: the constants after it that derive from
    /// it follow the change. Throws naming a change of no constant of
    /// Values, or one changed twice.
    std::vector<Definition> apply_changes(const std::string &values,
                                          const std::string &changes)
    {
      std::vector<Definition> definitions;
      for (auto &[name, expression] :
           split_named_entries(values, "Constants/Values"))
        definitions.push_back({name, expression, "Constants/Values"});
      const std::string        where = "Constants/Changes";
      std::vector<std::string> changed;
      for (auto &[name, expression] : split_named_entries(changes, where))
      {
        const auto definition =
            std::find_if(definitions.begin(), definitions.end(),
                         [&](const Definition &d) { return d.name == name; });
        if (definition == definitions.end())
          throw std::invalid_argument(where + ": '" + name +
                                      "' is not a constant of "
                                      "Constants/Values");
        if (std::find(changed.begin(), changed.end(), name) != changed.end())
          throw std::invalid_argument(where + ": " + name +
                                      " is changed twice");
        changed.push_back(name);
        *definition = {name, expression, where};
      }
      return definitions;
    }

    /// 'value' to 6 significant digits: a derived constant's rounding
    /// (1.7 - 1.75 = -0.050000000000000044) is no part of the message.
    std::string short_number(double value)
    {
      std::ostringstream text;
      text << std::setprecision(6) << value;
      return text.str();
    }

    /// The scene's constants with pi, each value a number or an expression
    /// of those before it; a constant listed in 'positive' must be > 0 where
    /// it is defined, so that the message names it rather than a later
    /// constant divided by it. Throws naming the entry.
    std::map<std::string, double>
    parse_values(const std::vector<Definition>  &definitions,
                 const std::vector<std::string> &positive)
    {
      std::map<std::string, double> values{{"pi", numbers::PI}};
      for (const auto &[name, expression, where] : definitions)
      {
        const double value = evaluate_constant_expression(expression, values,
                                                          where + ": " + name);
        if (!values.emplace(name, value).second)
          throw std::invalid_argument(where + ": " + name +
                                      " is pi or given twice");
        if (std::find(positive.begin(), positive.end(), name) !=
                positive.end() &&
            !(value > 0))
          throw std::invalid_argument(
              where + ": " + name + " = " + short_number(value) +
              " must be > 0 (it is listed in Constants/Positive)");
      }
      for (const std::string &name : positive)
        if (values.find(name) == values.end())
          throw std::invalid_argument(
              "Constants/Positive: '" + name +
              "' is not a constant of Constants/Values");
      return values;
    }

    /// The names of the scene's constants that 'expression' mentions, as
    /// "name = value" for a message.
    std::string named_values(const std::string                   &expression,
                             const std::map<std::string, double> &values)
    {
      std::string listed, word;
      const auto  flush = [&]()
      {
        const auto value = values.find(word);
        if (value != values.end() && value->first != "pi" &&
            listed.find(word + " = ") == std::string::npos)
          listed += (listed.empty() ? "" : ", ") + word + " = " +
                    short_number(value->second);
        word.clear();
      };
      for (const char c : expression + ' ')
        if (std::isalnum(static_cast<unsigned char>(c)) || c == '_')
          word += c;
        else
          flush();
      return listed;
    }

    /// Each entry of 'requirements' ("expression: message", entries
    /// separated by ';', the message after the last ':') must evaluate to
    /// a non-zero value with the scene's constants. Throws with the
    /// message, the expression and the values of the constants it names:
    /// a design value out of the range the scene was built for is
    /// refused before anything is meshed.
    void check_requirements(const std::string                   &requirements,
                            const std::map<std::string, double> &values)
    {
      const std::string where = "Constants/Requirements";
      for (const std::string &entry :
           Utilities::split_string_list(requirements, ';'))
      {
        const auto colon = entry.rfind(':');
        if (colon == std::string::npos || colon == 0 ||
            Utilities::trim(entry.substr(colon + 1)).empty())
          throw std::invalid_argument(where + ": '" + entry +
                                      "' is not of the form 'expression: "
                                      "message'");
        const std::string expression = Utilities::trim(entry.substr(0, colon));
        if (evaluate_constant_expression(expression, values, where) == 0)
          throw std::invalid_argument(where + ": " +
                                      Utilities::trim(entry.substr(colon + 1)) +
                                      " ('" + expression + "' is false with " +
                                      named_values(expression, values) + ")");
      }
    }
  } // namespace

  double
  evaluate_constant_expression(const std::string                   &text,
                               const std::map<std::string, double> &constants,
                               const std::string                   &where)
  {
    if (const auto number = as_number(text))
      return *number;
    // One variable no constant can be named like, as muparser needs one.
    FunctionParser<1> parser(1);
    double            value = 0;
    try
    {
      parser.initialize("coshell_unused_variable_",
                        std::vector<std::string>{text}, constants);
      value = parser.value(Point<1>());
    }
    catch (...)
    {
      throw std::invalid_argument(
          where + ": cannot evaluate '" + Utilities::trim(text) +
          "' (a number, or an expression of pi and the constants defined "
          "before it)");
    }
    if (!std::isfinite(value))
      throw std::invalid_argument(where + ": '" + Utilities::trim(text) +
                                  "' is not finite");
    return value;
  }

  std::vector<std::pair<std::string, double>>
  parse_named_values(const std::string &text, const std::string &where)
  {
    std::vector<std::pair<std::string, double>> named_values;
    for (const auto &[name, expression] : split_named_entries(text, where))
      named_values.emplace_back(
          name, evaluate_constant_expression(expression, expression_constants(),
                                             where + ": " + name));
    return named_values;
  }

  std::vector<double> parse_constant_list(const std::string &text,
                                          const std::string &where)
  {
    std::vector<double> values;
    for (const std::string &entry : split_entries(text))
      values.push_back(evaluate_constant_expression(
          Utilities::trim(entry), expression_constants(), where));
    return values;
  }

  void Constants::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Constants");
    prm.declare_entry("Values", "", Patterns::Anything(),
                      "Named constants as 'name = value' entries separated "
                      "by ',', usable in every expression of the prm; each "
                      "in the unit the prm's header gives it (e.g. "
                      "'plunger_speed = 5' in mm/s). A value is a number or "
                      "an expression of pi and the constants before it "
                      "(e.g. 'push_time = rod_out_time + 21.9 / "
                      "plunger_speed'), so that derived times follow the "
                      "design values they come from. Unit: each constant's "
                      "own, as the prm's header states it.");
    prm.declare_entry(
        "Changes", "", Patterns::Anything(),
        "'name = value' entries, as in Values, that replace the values of "
        "constants of Values where they stand, so that the constants "
        "derived from them follow. Meant "
        "for the command line: --set \"Constants/Changes=plunger_speed = "
        "1.5\" changes one design value without restating the others. A "
        "name that is not a constant of Values is refused. Unit: each "
        "constant's own, as in Values.");
    prm.declare_entry("Positive", "", Patterns::Anything(),
                      "Names of constants (separated by ',') that must be "
                      "> 0: a scene that needs a forward speed or a "
                      "positive size refuses anything else before it runs.");
    prm.declare_entry(
        "Requirements", "", Patterns::Anything(),
        "Conditions on the constants, as 'expression: message' entries "
        "separated by ';' (the message follows the entry's last ':'), "
        "checked after Values and Changes: an expression of the constants "
        "that is 0 (false) refuses the scene with its message and the "
        "values of the constants it names, e.g. 'nozzle_radius >= 0.7 && "
        "nozzle_radius <= 1.75: the tip must be 1.4 to 3.5 mm'. Unit: none "
        "(each expression in its constants' units).");
    prm.leave_subsection();
  }

  void Constants::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Constants");
    const auto definitions =
        apply_changes(prm.get("Values"), prm.get("Changes"));
    const auto positive = Utilities::split_string_list(prm.get("Positive"));
    const std::string requirements = prm.get("Requirements");
    prm.leave_subsection();
    scene_constants() = parse_values(definitions, positive);
    check_requirements(requirements, scene_constants());
  }

  const std::map<std::string, double> &expression_constants()
  {
    return scene_constants();
  }
} // namespace coshell::base
