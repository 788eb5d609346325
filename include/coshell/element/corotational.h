#pragma once

// Element-independent co-rotational (EICR) formulation of the flat shell
// triangle (Rankin & Nour-Omid 1988; Felippa & Haugen 2005): the linear
// flat-shell stiffness K_l of shell_element.h acts on deformational DOFs
// measured in a frame that follows the element, so that rigid motions of
// any size cost nothing while the strains stay small.

#include <coshell/element/shell_element.h>

#include <deal.II/base/tensor.h>
#include <deal.II/lac/full_matrix.h>

#include <array>

namespace coshell::element
{
  /// Which tangent the co-rotational element returns. Both variants return
  /// the same internal force (the gradient of the energy), so Newton
  /// converges to the same solution; only the tangent differs.
  enum class CorotationalTangent
  {
    consistent, ///< exact derivative of the force (non-symmetric in general)
    symmetric,  ///< the symmetric part of the consistent tangent
    paper       ///< T K_l T^T: no geometric stiffness, no projector
  };

  /// Nodal rotation matrices: R_i maps the node's initial triad to its
  /// current one (R_i = I initially).
  using NodalRotations = std::array<dealii::Tensor<2, 3>, 3>;

  /// What the co-rotational element keeps of its initial configuration.
  struct CorotationalReference
  {
    /// E0 = make_element_frame(initial): e1 along edge 0->1.
    ElementFrame frame;
    /// Initial in-plane vertex coordinates about the centroid.
    std::array<Point<2>, 3> coordinates;
    /// [X1 - X0, X2 - X0]^-1 of those coordinates (row-major): maps current
    /// edges to the in-plane deformation gradient.
    std::array<std::array<double, 2>, 2> inverse_edges;
  };

  /// The deformational DOFs d of one configuration and their Jacobian
  /// J = dd/dp (row-major): enough to extrapolate d linearly to a nearby
  /// configuration, d + J dp.
  struct CorotationalLinearization
  {
    ShellDisplacements                                     dofs{};
    std::array<std::array<double, shell_dofs>, shell_dofs> jacobian{};
  };

  class CorotationalShell
  {
  public:
    /// Caches the initial element frame E0 (make_element_frame, e1 along
    /// edge 0->1), the initial in-plane vertex coordinates about the
    /// centroid, and K_l = shell_stiffness_local of the initial triangle.
    CorotationalShell(const SpatialTriangle     &initial,
                      const ShellMaterial       &material,
                      const ShellElementOptions &options);

    /// Deformational DoFs in the co-rotated frame: per node (u, v, w,
    /// theta_x, theta_y, theta_z) along its axes, w = 0. Zero for any rigid
    /// motion of the initial state.
    ShellDisplacements
    deformational_dofs(const SpatialTriangle &current,
                       const NodalRotations  &rotations) const;

    /// 1/2 d^T K_l d.
    double energy(const SpatialTriangle &current,
                  const NodalRotations  &rotations) const;

    /// Internal force f = dE/dp in global axes, index 6*vertex + component
    /// (u_x, u_y, u_z, theta_x, theta_y, theta_z), for the perturbation p:
    /// x_i += du_i, R_i <- exp(skew(dtheta_i)) R_i. If tangent != nullptr it
    /// is resized to 18x18 and set to K_ab = d f_a / d p_b under that same
    /// update (consistent) or to T K_l T^T with T = diag(E, ..., E) built
    /// from the current frame E (paper).
    ///
    /// For the consistent and symmetric tangents: if 'geometric_dofs' is
    /// given, the terms of the tangent that are linear in the local force
    /// g = K_l d (the geometric stiffness and the rotation-update term) use
    /// K_l times those DOFs instead of the current d; the force does not
    /// change. If 'linearization' is given, it receives d and J here.
    void
    internal_force(const SpatialTriangle     &current,
                   const NodalRotations      &rotations,
                   CorotationalTangent        tangent_type,
                   ShellDisplacements        &force,
                   FullMatrix<double>        *tangent,
                   const ShellDisplacements  *geometric_dofs = nullptr,
                   CorotationalLinearization *linearization  = nullptr) const;

    /// Membrane forces and bending moments of the deformational DoFs, on
    /// the initial shape; the global tensors use the current frame axes.
    ShellResultants resultants(const SpatialTriangle &current,
                               const NodalRotations  &rotations) const;

    /// The linear stiffness K_l in the initial element frame.
    const FullMatrix<double> &local_stiffness() const
    {
      return stiffness;
    }

  private:
    CorotationalReference reference;
    FullMatrix<double>    stiffness;
    ResultantRecovery     recovery;
  };

  /// Lumped follower pressure on the current triangle: each vertex gets
  /// p/6 (x1-x0) x (x2-x0), i.e. p times the area-weighted normal / 3
  /// (pressure_times_sign = -p flips the normal). Returns the 9
  /// translational forces (index 3*vertex + component) and, if requested,
  /// the 9x9 non-symmetric load stiffness dF/dx.
  void follower_pressure(const SpatialTriangle &current,
                         double                 pressure_times_sign,
                         std::array<double, 9> &force,
                         FullMatrix<double>    *load_stiffness);

  /// The matrix of v -> a x v.
  dealii::Tensor<2, 3> skew(const dealii::Tensor<1, 3> &a);

  /// Rotation matrix exp(skew(theta)) (Rodrigues), accurate for all angles.
  dealii::Tensor<2, 3> rotation_exp(const dealii::Tensor<1, 3> &theta);
  /// Rotation vector of R with angle in [0, pi] (quaternion via Shepperd's
  /// method, angle via atan2), accurate near 0 and near pi.
  dealii::Tensor<1, 3> rotation_log(const dealii::Tensor<2, 3> &rotation);

  /// The left Jacobian of SO(3), V(theta) = sum_k skew(theta)^k / (k+1)!:
  /// the translation part of the SE(3) exponential, exp(u, theta) =
  /// (V(theta) u, exp(skew(theta))). Accurate for all angles below 2 pi.
  dealii::Tensor<2, 3> so3_left_jacobian(const dealii::Tensor<1, 3> &theta);
  /// Its inverse (the translation part of the SE(3) logarithm).
  dealii::Tensor<2, 3>
  so3_left_jacobian_inverse(const dealii::Tensor<1, 3> &theta);
} // namespace coshell::element
