#pragma once

#include <coshell/element/material.h>
#include <coshell/element/shell_element.h>

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace coshell::model
{
  /// Kinematics of the analysis. Only 'linear' exists so far; the
  /// co-rotational formulation will be a second value here.
  enum class Formulation
  {
    linear
  };

  /// prm subsections "Material" and "Element".
  struct ElementParameters
  {
    element::ShellMaterial       material;
    element::ShellElementOptions options;
    Formulation                  formulation = Formulation::linear;

    static void declare_parameters(dealii::ParameterHandler &prm);
    /// Throws std::invalid_argument naming the parameter for non-physical
    /// material values.
    void parse_parameters(dealii::ParameterHandler &prm);

    /// Short human-readable description, e.g. "cst+dkt".
    std::string element_name() const;
  };
} // namespace coshell::model
