#include <coshell/io/constants.h>
#include <coshell/io/expressions.h>

#include <deal.II/base/numbers.h>
#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cctype>
#include <optional>
#include <stdexcept>

namespace coshell::io
{
  using namespace dealii;

  namespace
  {
    std::map<std::string, double> &scene_constants()
    {
      static std::map<std::string, double> constants{{"pi", numbers::PI}};
      return constants;
    }

    /// The scene's constants with pi; throws naming the entry.
    std::map<std::string, double> parse_values(const std::string &text)
    {
      std::map<std::string, double> values{{"pi", numbers::PI}};
      for (const auto &[name, value] :
           parse_named_numbers(text, "Constants/Values"))
        if (!values.emplace(name, value).second)
          throw std::invalid_argument("Constants/Values: " + name +
                                      " is pi or given twice");
      return values;
    }
  } // namespace

  std::vector<std::pair<std::string, double>>
  parse_named_numbers(const std::string &text, const std::string &where)
  {
    std::vector<std::pair<std::string, double>> named_numbers;
    for (const auto &entry : Utilities::split_string_list(text, ','))
    {
      const auto parts = Utilities::split_string_list(entry, '=');
      const auto name  = parts.empty() ? std::string() : parts[0];
      const bool named =
          !name.empty() && !std::isdigit(static_cast<unsigned char>(name[0])) &&
          std::all_of(name.begin(), name.end(),
                      [](char c) {
                        return std::isalnum(static_cast<unsigned char>(c)) ||
                               c == '_';
                      });
      const auto value =
          parts.size() == 2 ? as_number(parts[1]) : std::optional<double>();
      if (!named || !value)
        throw std::invalid_argument(where + ": '" + entry +
                                    "' is not of the form 'name = number'");
      named_numbers.emplace_back(name, *value);
    }
    return named_numbers;
  }

  void Constants::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Constants");
    prm.declare_entry("Values", "", Patterns::Anything(),
                      "Named constants as 'name = number' entries separated "
                      "by ',', usable in every expression of the prm; each "
                      "in the unit the prm's header gives it (e.g. "
                      "'plunger_speed = 5' in mm/s).");
    prm.declare_entry("Positive", "", Patterns::Anything(),
                      "Names of constants (separated by ',') that must be "
                      "> 0: a scene that needs a forward speed or a "
                      "positive size refuses anything else before it runs.");
    prm.leave_subsection();
  }

  void Constants::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Constants");
    const auto values   = parse_values(prm.get("Values"));
    const auto positive = Utilities::split_string_list(prm.get("Positive"));
    prm.leave_subsection();
    for (const std::string &name : positive)
    {
      const auto found = values.find(name);
      if (found == values.end())
        throw std::invalid_argument("Constants/Positive: '" + name +
                                    "' is not a constant of Constants/Values");
      if (!(found->second > 0))
        throw std::invalid_argument(
            "Constants/Values: " + name + " = " +
            Utilities::to_string(found->second) +
            " must be > 0 (it is listed in Constants/Positive)");
    }
    scene_constants() = values;
  }

  const std::map<std::string, double> &expression_constants()
  {
    return scene_constants();
  }
} // namespace coshell::io
