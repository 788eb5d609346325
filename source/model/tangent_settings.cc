#include <coshell/model/tangent_settings.h>

namespace coshell::model
{
  using namespace dealii;

  void TangentSettings::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Nonlinear solver");
    prm.declare_entry("Tangent", "consistent",
                      Patterns::Selection("consistent|symmetric|paper"),
                      "consistent: exact derivative of the co-rotational "
                      "internal force (quadratic convergence, non-symmetric: "
                      "UMFPACK); symmetric: its symmetric part (exact at "
                      "equilibrium; Cholesky with Linear solver/Method = "
                      "cholmod, which falls back to UMFPACK where the "
                      "matrix is not positive definite); paper: the "
                      "approximation R K R^T of Comas et al. 2010.");
    prm.declare_entry(
        "Geometric stiffness", "auto",
        Patterns::Selection("auto|current forces|extrapolated forces"),
        "Which local forces of each co-rotational element drive the "
        "terms of the tangent that are linear in them (the geometric "
        "stiffness and the rotation-update term). current forces: those "
        "of the current iterate, the exact derivative of the residual. "
        "extrapolated forces: K_l (d + J dp), the local forces of the "
        "previous iterate carried along that iterate's linearization to "
        "the current one, as in the mixed-integration-point Newton of "
        "Magisano, Leonetti & Garcea (2017): the same solution, the same "
        "residual, far fewer iterations on thin shells, where a "
        "correction's spurious membrane forces spoil the next tangent. "
        "auto: extrapolated forces in static analyses until a step fails, "
        "then current forces for the rest of the stage; current forces in "
        "dynamic ones (doc/performance.md).");
    prm.leave_subsection();
  }

  void TangentSettings::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Nonlinear solver");
    const std::string tangent = prm.get("Tangent");
    tangent_ = tangent == "paper" ? element::CorotationalTangent::paper
               : tangent == "symmetric"
                   ? element::CorotationalTangent::symmetric
                   : element::CorotationalTangent::consistent;
    geometric_stiffness_ = prm.get("Geometric stiffness");
    prm.leave_subsection();
  }

  element::CorotationalTangent TangentSettings::tangent() const
  {
    return tangent_;
  }

  bool TangentSettings::extrapolated_geometric_stiffness(bool dynamic) const
  {
    if (geometric_stiffness_ == "auto")
      return !dynamic;
    return geometric_stiffness_ == "extrapolated forces";
  }

  bool TangentSettings::exact_tangent_after_failure() const
  {
    return geometric_stiffness_ == "auto";
  }
} // namespace coshell::model
