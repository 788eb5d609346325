#pragma once

#include <coshell/element/bending.h>
#include <coshell/element/membrane.h>

#include <optional>

namespace coshell::element
{
  enum class MembraneElement
  {
    cst,  ///< constant-strain triangle + drilling penalty
    andes ///< optimal ANDES triangle, genuine drilling stiffness (no penalty)
  };

  /// What the flat shell element is made of. An unset optional switches
  /// that part off (the paper computed Table 1 with bending only).
  struct ShellElementOptions
  {
    std::optional<MembraneElement> membrane = MembraneElement::cst;
    std::optional<BendingElement>  bending  = BendingElement::dkt;
    /// Dimensionless size of the drilling penalty (see add_drilling_penalty);
    /// used by the CST only.
    double drilling_factor = 1e-3;
    /// false: the CST keeps only its drilling penalty, because the
    /// in-plane stiffness comes from the thick membrane (ThickMembrane),
    /// whose law also governs the thickness. Used by the CST only.
    bool membrane_in_plane = true;
    /// Multipliers of the ANDES membrane's higher-order stiffness and of
    /// its basic drilling weight: 1 is Felippa's optimal element.
    /// ShellModel lowers them on the facets of a curved mesh, where the
    /// drilling terms lock (doc/theory.md, section 14).
    AndesScales andes_scales;
  };

  /// Number of DOFs of the flat shell triangle: 3 vertices x (u_x, u_y,
  /// u_z, theta_x, theta_y, theta_z) in global axes, index = 6*vertex +
  /// component, which is deal.II's cell-local order for
  /// FESystem(FE_SimplexP<2,3>(1), 6).
  constexpr unsigned int shell_dofs = 18;
  using ShellDisplacements          = std::array<double, shell_dofs>;

  /// Linear flat-shell stiffness in the element frame: 18 DOFs, per node
  /// (u, v, w, theta_x, theta_y, theta_z) along the frame axes, built on
  /// frame.planar (the frame's origin and axes are not used).
  FullMatrix<double> shell_stiffness_local(const ElementFrame        &frame,
                                           const ShellMaterial       &material,
                                           const ShellElementOptions &options);

  /// T^T K_local T for an 18x18 element matrix whose 3-blocks (per node,
  /// translations then rotations) are in the frame with axes e_a (rows of
  /// R, u_local = R u_global).
  FullMatrix<double> rotate_to_global(const FullMatrix<double>          &local,
                                      const std::array<Tensor<1, 3>, 3> &axes);
  /// The same into 'global' (sized 18x18 if it is not), without allocating:
  /// the co-rotational element's paper tangent does this once per cell and
  /// evaluation.
  void rotate_to_global(const FullMatrix<double>          &local,
                        const std::array<Tensor<1, 3>, 3> &axes,
                        FullMatrix<double>                &global);

  /// Linear flat-shell stiffness in global axes: membrane and bending
  /// assembled in the element frame (make_element_frame) and rotated with
  /// K = T^T K_local T.
  FullMatrix<double> shell_stiffness(const SpatialTriangle     &triangle,
                                     const ShellMaterial       &material,
                                     const ShellElementOptions &options);

  /// Stress resultants of one element, in its frame and rotated to global
  /// axes as symmetric 3x3 tensors (N = sum N_ab e_a (x) e_b, same for M).
  struct ShellResultants
  {
    MembraneForces       membrane_local{};
    BendingMoments       bending_local{};
    dealii::Tensor<2, 3> membrane_global;
    dealii::Tensor<2, 3> bending_global;
  };

  ShellResultants shell_resultants(const SpatialTriangle     &triangle,
                                   const ShellMaterial       &material,
                                   const ShellElementOptions &options,
                                   const ShellDisplacements  &dofs);

  /// The resultants of shell_resultants() as a linear map of the 18
  /// element-frame DOFs, built once for a fixed planar shape: the
  /// co-rotational element measures them on its initial shape at every
  /// step, where rebuilding the DKT's and ANDES's strain matrices each
  /// time cost more than the rest of the step's bookkeeping.
  class ResultantRecovery
  {
  public:
    ResultantRecovery(const PlanarTriangle      &planar,
                      const ShellMaterial       &material,
                      const ShellElementOptions &options);
    /// From element-frame DOFs; the global tensors use 'axes' (e1, e2, e3).
    ShellResultants resultants(const std::array<Tensor<1, 3>, 3> &axes,
                               const ShellDisplacements          &local) const;

  private:
    /// Rows N_xx, N_yy, N_xy, M_xx, M_yy, M_xy.
    std::array<std::array<double, shell_dofs>, 6> map_{};
  };

  /// Rotates 18 global DOFs into the element frame (per node: local
  /// translations then local rotations).
  ShellDisplacements to_element_frame(const ElementFrame       &frame,
                                      const ShellDisplacements &global_dofs);
} // namespace coshell::element
