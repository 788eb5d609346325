#pragma once

#include <coshell/element/material.h>
#include <coshell/element/shell_element.h>

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace coshell::model
{
  /// Kinematics of the analysis: small displacements, or finite
  /// rotations through the element-independent co-rotational frame.
  enum class Formulation
  {
    linear,
    corotational
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

    std::string formulation_name() const;

    /// Short human-readable description, e.g. "cst+dkt".
    std::string element_name() const;
  };
} // namespace coshell::model
