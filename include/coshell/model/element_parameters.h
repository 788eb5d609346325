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
    /// E and nu; thickness and density when "Thickness" and "Density" are
    /// numbers. When either is an expression, ShellModel evaluates it per
    /// triangle and holds the area-weighted means here.
    element::ShellMaterial material;
    /// "Thickness" and "Density" when they are muparser expressions of
    /// x, y, z (the triangle's reference centroid) and region (its
    /// material id); empty when they are numbers (then in 'material').
    std::string                  thickness_expression;
    std::string                  density_expression;
    element::ShellElementOptions options;
    Formulation                  formulation = Formulation::linear;
    /// c of the ANDES higher-order scaling 1 / (1 + c l^2 phi^2 / h^2),
    /// applied per triangle by ShellModel (dimensionless; 0: none).
    double andes_curvature_scaling = 10.0;
    /// The same for the Allman drilling weight alpha_b of the basic part.
    double andes_basic_drilling_scaling = 0.1;
    /// Whether each vertex has a thickness stretch unknown and the
    /// membrane is the thick membrane (then options.membrane_in_plane is
    /// false: the CST keeps only its drilling penalty).
    bool thickness_stretch = false;
    /// Nominal face pressure in MPa (force per reference area), times the
    /// load factor; only with thickness_stretch.
    double face_pressure = 0;

    static void declare_parameters(dealii::ParameterHandler &prm);
    /// Throws std::invalid_argument naming the parameter for non-physical
    /// material values.
    void parse_parameters(dealii::ParameterHandler &prm);

    /// Whether thickness and density are single numbers (no expression).
    bool uniform_properties() const;

    std::string formulation_name() const;

    /// Short human-readable description, e.g. "cst+dkt".
    std::string element_name() const;

  private:
    /// Throws naming the parameter when Thickness stretch or Face pressure
    /// do not fit the rest of the subsection; with the stretch, leaves the
    /// CST its drilling penalty only (options.membrane_in_plane = false).
    void check_thickness_stretch();
  };
} // namespace coshell::model
