#pragma once

#include <coshell/base/constants.h>

#include <deal.II/base/function_parser.h>
#include <deal.II/base/numbers.h>
#include <deal.II/base/point.h>
#include <deal.II/base/utilities.h>
#include <deal.II/lac/vector.h>

#include <cstdlib>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

namespace coshell::base
{
  /// The value of 'text' if it is exactly one number (blanks around it
  /// allowed), else nothing.
  inline std::optional<double> as_number(const std::string &text)
  {
    const std::string trimmed = dealii::Utilities::trim(text);
    char             *end     = nullptr;
    const double      value   = std::strtod(trimmed.c_str(), &end);
    if (trimmed.empty() || end != trimmed.c_str() + trimmed.size())
      return std::nullopt;
    return value;
  }

  /// A muparser function with 'n_components' expressions separated by ';'
  /// in 'text', of the variables 'variables' (deal.II names, e.g. "x,y,z",
  /// or "x,t" with 'time_dependent'), with pi and the scene's Constants.
  /// Evaluated once here, so a bad expression fails at parse time. Throws
  /// std::invalid_argument
  /// "<where>: ..." naming the text and what was expected ('described', e.g.
  /// "t" or "x, y, z").
  template<int dim>
  std::unique_ptr<dealii::FunctionParser<dim>>
  parse_expressions(const std::string &text,
                    unsigned int       n_components,
                    const std::string &variables,
                    bool               time_dependent,
                    const std::string &described,
                    const std::string &where)
  {
    const auto expressions = dealii::Utilities::split_string_list(text, ';');
    const std::string expected = std::to_string(n_components) +
                                 " expression(s) of " + described +
                                 " separated by ';'";
    if (expressions.size() != n_components)
      throw std::invalid_argument(where + ": '" + text + "' must be " +
                                  expected);
    auto function = std::make_unique<dealii::FunctionParser<dim>>(n_components);
    try
    {
      function->initialize(variables, expressions, expression_constants(),
                           time_dependent);
      dealii::Vector<double> values(n_components);
      function->vector_value(dealii::Point<dim>(), values);
    }
    catch (...)
    {
      throw std::invalid_argument(where + ": cannot parse '" + text + "' as " +
                                  expected);
    }
    return function;
  }
} // namespace coshell::base
