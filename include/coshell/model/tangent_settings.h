#pragma once

#include <coshell/element/corotational.h>

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace coshell::model
{
  /// Which tangent the co-rotational internal force returns, and which
  /// local forces drive its geometric terms: the entries "Tangent" and
  /// "Geometric stiffness" of prm subsection "Nonlinear solver" (the
  /// subsection also holds the path following's and Newton's settings,
  /// which know no element).
  class TangentSettings
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm);
    void        parse_parameters(dealii::ParameterHandler &prm);

    element::CorotationalTangent tangent() const;
    /// Whether the co-rotational tangent's geometric terms use the local
    /// forces extrapolated from the previous Newton iterate (see
    /// "Geometric stiffness"), in a dynamic analysis or a static one.
    bool extrapolated_geometric_stiffness(bool dynamic) const;
    /// Whether a failed step returns the rest of its stage to the exact
    /// tangent (Geometric stiffness = auto).
    bool exact_tangent_after_failure() const;

  private:
    element::CorotationalTangent tangent_ =
        element::CorotationalTangent::consistent;
    std::string geometric_stiffness_ = "auto";
  };
} // namespace coshell::model
