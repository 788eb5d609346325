#include <coshell/base/expressions.h>
#include <coshell/model/element_parameters.h>

#include <cmath>

#include <deal.II/base/utilities.h>

#include <cstdlib>
#include <stdexcept>

namespace coshell::model
{
  using namespace dealii;

  namespace
  {
    void declare_material_entries(ParameterHandler &prm)
    {
      prm.enter_subsection("Material");
      prm.declare_entry("Young's modulus", "1", Patterns::Double(),
                        "Young's modulus E; > 0. Unit: force/length^2 (Pa "
                        "= N/m^2 in SI, MPa = N/mm^2 in mm-N-s-tonne "
                        "scenes).");
      prm.declare_entry("Poisson's ratio", "0.3", Patterns::Double(),
                        "Poisson's ratio nu, in (-1, 0.5). Unit: "
                        "dimensionless.");
      prm.declare_entry(
          "Thickness", "0.01", Patterns::Anything(),
          "Shell thickness h; > 0. "
          "A number, or a muparser expression of x, y, z (the reference "
          "centroid of each triangle) and region (its material id, the gmsh "
          "physical surface), constant over each triangle, e.g. "
          "if(region == 1, 0.8 - 0.5 * (x^2 + y^2) / 9, 0.45). Unit: length "
          "(m in SI, mm in the IOL scenes).");
      prm.declare_entry(
          "Density", "0", Patterns::Anything(),
          "Mass per unit volume, >= 0 (steel: 7850 kg/m^3 = 7.85e-9 "
          "t/mm^3); used by gravity loads and inertia. A number, or an "
          "expression of x, y, z and region as for Thickness. Unit: "
          "mass/length^3 (kg/m^3 in SI, tonne/mm^3 in mm-N-s-tonne "
          "scenes).");
      prm.leave_subsection();
    }

    void declare_element_entries(ParameterHandler &prm)
    {
      prm.enter_subsection("Element");
      prm.declare_entry("Formulation", "linear",
                        Patterns::Selection("linear|corotational"),
                        "Selects the kinematics. "
                        "linear: small displacements and rotations, one linear "
                        "solve. corotational: finite rotations (element-"
                        "independent co-rotational frame around the same "
                        "elements), solved by the Nonlinear solver.");
      prm.declare_entry(
          "Membrane element", "cst", Patterns::Selection("cst|andes|off"),
          "Selects the in-plane part of the flat shell triangle: cst (the "
          "constant-strain triangle plus the drilling penalty below), andes "
          "(Felippa's optimal ANDES triangle with genuine drilling stiffness, "
          "much better in in-plane bending; no penalty), or off (no membrane "
          "stiffness, as in the paper's Table 1 runs).");
      prm.declare_entry("Bending element", "dkt",
                        Patterns::Selection("dkt|przemieniecki|off"),
                        "Selects the plate-bending part: dkt, the Discrete "
                        "Kirchhoff Triangle; przemieniecki, the paper's "
                        "modified Przemieniecki incomplete cubic (x axis along "
                        "edge AB = vertex 0 -> 1); or off.");
      prm.declare_entry(
          "Drilling stiffness factor", "1e-3", Patterns::Double(0),
          "Penalty tying each nodal drilling "
          "rotation to the membrane's in-plane rotation, "
          "k = factor * E h A / 3 (doc/theory.md, section 4). Used by "
          "the cst membrane only. Unit: dimensionless.");
      prm.declare_entry(
          "ANDES curvature scaling", "10", Patterns::Double(0),
          "Constant c of the andes membrane's higher-order "
          "stiffness on a curved mesh: each triangle's K_h is multiplied by "
          "1 / (1 + c l^2 phi^2 / h^2), l^2 the mean squared edge length, h "
          "the thickness and phi the largest angle between the triangle's "
          "normal and the mean normals at its vertices. On a faceted curved "
          "surface the drilling terms charge part of the bending rotation at "
          "membrane stiffness and lock (91 % too stiff on the 4 x 4 pinched "
          "hemisphere); flat meshes keep factor 1. 0: Felippa's optimal "
          "element everywhere (doc/theory.md, section 14). Unit: "
          "dimensionless.");
      prm.declare_entry(
          "ANDES basic drilling scaling", "0.1", Patterns::Double(0),
          "Constant c_b of the same form for the Allman drilling "
          "weight alpha_b = 3/2 of the andes membrane's basic stiffness: "
          "alpha_b / (1 + c_b l^2 phi^2 / h^2) per triangle. 0: alpha_b = 3/2 "
          "everywhere (doc/theory.md, section 14). Unit: dimensionless.");
      prm.declare_entry(
          "Thickness stretch", "false", Patterns::Bool(),
          "Whether the thickness may change: each vertex gets one more "
          "unknown, its thickness stretch h/h0, and the membrane becomes the "
          "thick membrane, CalculiX's compressible neo-Hookean law on the "
          "in-plane stretch and the thickness stretch (doc/theory.md, "
          "section 21). Needs Formulation = corotational and Membrane "
          "element = cst, whose drilling penalty stays, and one MPI rank. "
          "Bending and the contact offsets follow the current thickness. "
          "Off: no unknown and no cost.");
      prm.declare_entry(
          "Face pressure", "0", Patterns::Double(),
          "Nominal pressure squeezing the shell through its thickness, force "
          "per reference area on both faces, times the load factor (a "
          "frictionless squeeze between plates). Needs Thickness stretch. "
          "Unit: MPa.");
      prm.leave_subsection();
    }
  } // namespace

  void ElementParameters::declare_parameters(ParameterHandler &prm)
  {
    declare_material_entries(prm);
    declare_element_entries(prm);
  }

  bool ElementParameters::uniform_properties() const
  {
    return thickness_expression.empty() && density_expression.empty();
  }

  void ElementParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Material");
    material.youngs_modulus = prm.get_double("Young's modulus");
    material.poisson_ratio  = prm.get_double("Poisson's ratio");
    // Expressions are evaluated and checked per triangle by ShellModel;
    // stand-in values let E and nu be checked here already.
    const std::string thickness = prm.get("Thickness");
    const std::string density   = prm.get("Density");
    prm.leave_subsection();
    material.thickness   = base::as_number(thickness).value_or(1.0);
    material.density     = base::as_number(density).value_or(0.0);
    thickness_expression = base::as_number(thickness) ? "" : thickness;
    density_expression   = base::as_number(density) ? "" : density;
    try
    {
      material.validate();
    }
    catch (const std::invalid_argument &error)
    {
      throw std::invalid_argument(std::string("subsection Material: ") +
                                  error.what());
    }

    prm.enter_subsection("Element");
    formulation                = prm.get("Formulation") == "corotational"
                                     ? Formulation::corotational
                                     : Formulation::linear;
    const std::string membrane = prm.get("Membrane element");
    if (membrane == "off")
      options.membrane = std::nullopt;
    else
      options.membrane = membrane == "cst" ? element::MembraneElement::cst
                                           : element::MembraneElement::andes;
    const std::string bending = prm.get("Bending element");
    if (bending == "off")
      options.bending = std::nullopt;
    else
      options.bending = bending == "dkt"
                            ? element::BendingElement::dkt
                            : element::BendingElement::przemieniecki;
    options.drilling_factor = prm.get_double("Drilling stiffness factor");
    andes_curvature_scaling = prm.get_double("ANDES curvature scaling");
    andes_basic_drilling_scaling =
        prm.get_double("ANDES basic drilling scaling");
    thickness_stretch = prm.get_bool("Thickness stretch");
    face_pressure     = prm.get_double("Face pressure");
    prm.leave_subsection();
    check_thickness_stretch();
    if (!options.membrane && !options.bending)
      throw std::invalid_argument("subsection Element: Membrane element and "
                                  "Bending element are both off; nothing "
                                  "would resist any load");
  }

  void ElementParameters::check_thickness_stretch()
  {
    if (!thickness_stretch)
    {
      if (face_pressure != 0)
        throw std::invalid_argument(
            "subsection Element: Face pressure needs Thickness stretch = "
            "true (a shell of fixed thickness has no through-thickness "
            "unknown to push)");
      return;
    }
    if (formulation != Formulation::corotational)
      throw std::invalid_argument(
          "subsection Element: Thickness stretch needs Formulation = "
          "corotational (the thick membrane is nonlinear)");
    if (options.membrane != element::MembraneElement::cst)
      throw std::invalid_argument(
          "subsection Element: Thickness stretch needs Membrane element = "
          "cst (the thick membrane replaces the CST's in-plane part)");
    if (!std::isfinite(face_pressure))
      throw std::invalid_argument(
          "subsection Element: Face pressure must be finite");
    options.membrane_in_plane = false;
  }

  std::string ElementParameters::formulation_name() const
  {
    return formulation == Formulation::linear ? "linear" : "corotational";
  }

  std::string ElementParameters::element_name() const
  {
    std::string membrane = "nomembrane";
    if (options.membrane)
      membrane =
          *options.membrane == element::MembraneElement::cst ? "cst" : "andes";
    std::string bending = "nobending";
    if (options.bending)
      bending = *options.bending == element::BendingElement::dkt
                    ? "dkt"
                    : "przemieniecki";
    return membrane + "+" + bending + (thickness_stretch ? "+stretch" : "");
  }
} // namespace coshell::model
