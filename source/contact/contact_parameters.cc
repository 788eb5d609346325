#include <coshell/contact/contact.h>

#include <stdexcept>

namespace coshell::contact
{
  using namespace dealii;

  namespace
  {
    /// Contact/Method and the barrier's and the penalty's own entries.
    void declare_method_entries(ParameterHandler &prm)
    {
      prm.declare_entry(
          "Method", "none", Patterns::Selection("none|barrier|penalty"),
          "none: no contact (nothing is built, no cost); barrier: the log "
          "barrier of incremental potential contact with every Newton step "
          "and obstacle move filtered by continuous collision detection, so "
          "no iterate ever interpenetrates; penalty: a smoothed penalty on "
          "the penetration (cheaper; lets in a penetration of order "
          "pressure / Penalty stiffness, reported).");
      prm.declare_entry("Activation distance", "0", Patterns::Double(0),
                        "Barrier: the gap (distance minus half the shell "
                        "thickness and the obstacle offset) below which the "
                        "barrier acts; the shell settles within it, so it "
                        "bounds the geometric error of contact. 0: a tenth of "
                        "the shell thickness. Unit: length (mm in the IOL "
                        "scenes).");
      prm.declare_entry(
          "Barrier stiffness", "0", Patterns::Double(0),
          "Barrier: kappa in the energy kappa * area * b(gap), b(g) = "
          "-(g - d)^2 ln(g / d) a squared length, so kappa is a pressure "
          "per length. 0: kappa = E / (h b''(d/2)), so "
          "that the barrier at half the activation distance d is as stiff as "
          "the shell across its half thickness. Doubled after a step whose "
          "smallest gap falls below Stiffening gap ratio * d. Unit: "
          "force/length^3 (N/mm^3 in mm-N-s scenes).");
      prm.declare_entry(
          "Barrier stiffness scale", "material",
          Patterns::Selection("material|load"),
          "Barrier, with Barrier stiffness = 0: what sets kappa. material: E / "
          "(h b''(d/2)), above, for contact pressures "
          "of the order of the shell's own stiffness (folding, pushing). "
          "load: q / |b'(d/2)|, q the mean dead load per area of the shell "
          "(force/length^2: the magnitudes of the vertex forces of gravity, "
          "pressure, "
          "point and edge forces, over the shell's area), so that the barrier "
          "carries the scene's own load at half the activation distance: for "
          "a shell resting on an obstacle or on itself under a light load, "
          "which the material scale would float at the barrier's edge, where "
          "its stiffness vanishes. Both are doubled as above.");
      prm.declare_entry("Stiffening gap ratio", "1e-3", Patterns::Double(0, 1),
                        "Barrier: see Barrier stiffness. Unit: "
                        "dimensionless (a fraction of the activation "
                        "distance).");
      prm.declare_entry("Penalty stiffness", "0", Patterns::Double(0),
                        "Penalty: contact pressure per penetration. 0: E / h. "
                        "Unit: force/length^3 (N/mm^3 in mm-N-s scenes).");
      prm.declare_entry("Penalty smoothing", "0", Patterns::Double(0),
                        "Penalty: the penetration over which the penalty "
                        "stiffness ramps up from zero (C2 start). 0: h / 100. "
                        "Unit: length (mm in the IOL scenes).");
      prm.declare_entry(
          "Penalty step filter", "0", Patterns::Double(0, 1),
          "Penalty: 0 (the default) lets a step carry a vertex through an "
          "obstacle's surface or the shell's own, where the penalty, which "
          "acts only on penetration, can no longer push it back; with "
          "f > 0 every Newton correction and obstacle move is filtered by "
          "continuous collision detection, as the barrier's are, to keep "
          "each pair f times its offset (half the thicknesses) apart, so a "
          "step may press into the half thickness but not through it "
          "(0 <= f < 1). Unit: dimensionless (a fraction of the offset).");
    }

    /// How the pairs' Hessians enter the tangent.
    void declare_tangent_entries(ParameterHandler &prm)
    {
      prm.declare_entry("Projected tangent", "true", Patterns::Bool(),
                        "Project each pair's Hessian onto the positive "
                        "semi-definite matrices (as IPC does) so that Newton "
                        "steps descend; false: the exact Hessian.");
      prm.declare_entry("Projected tangent on retry", "false", Patterns::Bool(),
                        "With Projected tangent = false: a step that failed is "
                        "retried with the projected Hessians (until a step "
                        "succeeds), whose Newton steps descend where the "
                        "exact ones, faster elsewhere, can stall against "
                        "the collision filter.");
      prm.declare_entry("Projected tangent on stall", "false", Patterns::Bool(),
                        "With Projected tangent = false: once Newton's "
                        "corrections in an attempt have climbed the energy "
                        "(du.r < 0, the exact Hessian indefinite along them) "
                        "Nonlinear solver/Climbs before convex tangent times, "
                        "the last is discarded and the rest of the attempt "
                        "uses the projected Hessians (Newton's steps then "
                        "descend). A retry starts with the exact ones again "
                        "unless Projected tangent on retry.");
    }

    /// Which pairs are kept, and friction's smoothing.
    void declare_pair_entries(ParameterHandler &prm)
    {
      prm.declare_entry(
          "Pairs", "all", Patterns::Selection("all|local minima"),
          "all: every shell vertex-obstacle triangle and obstacle vertex-shell "
          "triangle pair within reach, one per pair of closest features (as "
          "IPC): the energy is continuous, but a vertex over a flat face also "
          "feels the neighbouring triangles' edges, a lateral force of order "
          "1e-4 of the normal one. local minima: only pairs whose distance is "
          "a local minimum over the surface (a frictionless plane then pushes "
          "exactly along its normal), exact for flat and convex obstacles but "
          "discontinuous where a vertex passes a concave edge.");
      prm.declare_entry(
          "Stiction velocity", "1e-3", Patterns::Double(0),
          "Friction: the tangential speed below which "
          "Coulomb friction is smoothed to a viscous law (IPC's epsilon_v): "
          "a sticking contact creeps at a fraction of it. In statics the "
          "pseudo-time of a step stands for its duration. Unit: "
          "length/time (mm/s in the IOL scenes).");
      prm.declare_entry(
          "Stiction displacement", "0", Patterns::Double(0),
          "Friction: the least tangential slip over which "
          "friction is smoothed in a step, whatever the step's duration: "
          "the smoothing length is the larger of this and Stiction velocity "
          "times the step. With 0 (the default) it is IPC's v dt alone, "
          "which a step cut shrinks with the step, stiffening friction "
          "where Newton already struggles. A floor weakens friction on "
          "slow slip: a vertex slipping at speed v is resisted by about "
          "v dt / (this) of Coulomb's force while v dt is below it, so "
          "the force depends on the time step (doc/validation/contact.md, "
          "doc/performance/iol.md). Unit: length (mm in the IOL scenes).");
      prm.declare_entry(
          "Edge-edge pairs", "true", Patterns::Bool(),
          "Also keep shell edges from obstacle edges (and, with Self "
          "contact, from shell edges), with the same friction, so that "
          "an obstacle edge cannot cut through a shell edge between their "
          "vertices; nearly parallel edges fade out smoothly (IPC's "
          "mollifier). false: vertex-triangle pairs only (cheaper; an "
          "edge crossing between vertices is then not seen).");
    }

    /// The shell against itself.
    void declare_self_contact_entries(ParameterHandler &prm)
    {
      prm.declare_entry(
          "Self contact", "false", Patterns::Bool(),
          "Also keep the shell from itself: shell vertices against shell "
          "triangles, at least the mean of their half thicknesses apart, by "
          "the same barrier or penalty and step filter, and friction with "
          "Self contact friction coefficient.");
      prm.declare_entry("Self contact friction coefficient", "0",
                        Patterns::Double(),
                        "Coulomb friction coefficient mu of the shell against "
                        "itself (>= 0; 0: frictionless, and no cost). Unit: "
                        "dimensionless.");
      prm.declare_entry(
          "Self contact exclusion", "2", Patterns::Double(1),
          "Self contact ignores a vertex-triangle pair of the same connected "
          "piece of shell whose distance in the reference configuration is "
          "below this multiple of the distance it must keep (>= 1): "
          "neighbours on a thick shell are closer than its thickness "
          "and are held apart by the elements, not by contact. Unit: "
          "dimensionless.");
    }
  } // namespace

  void ContactParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Contact");
    declare_method_entries(prm);
    declare_tangent_entries(prm);
    declare_pair_entries(prm);
    declare_self_contact_entries(prm);
    ObstacleParameters::declare_parameters(prm);
    prm.leave_subsection();
  }

  void ContactParameters::parse_parameters(ParameterHandler  &prm,
                                           const std::string &prm_directory)
  {
    prm.enter_subsection("Contact");
    const std::string name      = prm.get("Method");
    method                      = name == "barrier"   ? Method::barrier
                                  : name == "penalty" ? Method::penalty
                                                      : Method::none;
    activation_distance         = prm.get_double("Activation distance");
    barrier_stiffness           = prm.get_double("Barrier stiffness");
    barrier_stiffness_from_load = prm.get("Barrier stiffness scale") == "load";
    stiffening_gap_ratio        = prm.get_double("Stiffening gap ratio");
    penalty_stiffness           = prm.get_double("Penalty stiffness");
    penalty_smoothing           = prm.get_double("Penalty smoothing");
    penalty_step_filter         = prm.get_double("Penalty step filter");
    project_tangent             = prm.get_bool("Projected tangent");
    project_tangent_on_retry    = prm.get_bool("Projected tangent on retry");
    project_tangent_on_stall    = prm.get_bool("Projected tangent on stall");
    stiction_velocity           = prm.get_double("Stiction velocity");
    stiction_displacement       = prm.get_double("Stiction displacement");
    local_minima_only           = prm.get("Pairs") == "local minima";
    self_contact                = prm.get_bool("Self contact");
    edge_edge_pairs             = prm.get_bool("Edge-edge pairs");
    self_exclusion              = prm.get_double("Self contact exclusion");
    self_friction_coefficient =
        prm.get_double("Self contact friction coefficient");
    if (!(self_friction_coefficient >= 0))
    {
      const std::string value = prm.get("Self contact friction coefficient");
      prm.leave_subsection();
      throw std::runtime_error("Contact/Self contact friction coefficient: " +
                               value + " is negative; it must be >= 0");
    }
    if (penalty_step_filter >= 1)
    {
      const std::string value = prm.get("Penalty step filter");
      prm.leave_subsection();
      // At 1 the filter would stop every pair before the penalty acts,
      // and a pushing obstacle could never advance.
      throw std::runtime_error("Contact/Penalty step filter: " + value +
                               " must be below 1 (0 turns the filter off)");
    }
    try
    {
      // Off costs nothing: the obstacle meshes are not even read.
      if (enabled())
        obstacles = ObstacleParameters::parse_parameters(prm, prm_directory);
    }
    catch (...)
    {
      prm.leave_subsection();
      throw;
    }
    prm.leave_subsection();
    if (enabled() && obstacles.empty() && !self_contact)
      throw std::runtime_error("Contact/Method is " + name +
                               " but no obstacle has a Mesh file and Self "
                               "contact is off");
  }
} // namespace coshell::contact
