#pragma once

// Continuous collision detection: how far along linear trajectories two
// primitives may move and stay apart. Pure functions; no state.

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <array>

namespace coshell::contact
{
  using Points4       = std::array<dealii::Point<3>, 4>;
  using Displacements = std::array<dealii::Tensor<1, 3>, 4>;

  enum class PrimitivePair
  {
    point_triangle, ///< points: p, then the triangle a, b, c
    segment_segment ///< points: p0, p1, then q0, q1
  };

  /// Additive CCD (Li, Kaufman & Jiang 2021, "Codimensional incremental
  /// potential contact", section 5): the largest t in [0, 1] such that
  /// the primitives at x + t dx keep a distance above 'minimum_distance'
  /// (the thickness offsets) and their gap d - minimum_distance stays at
  /// least 'kept_fraction' of the starting gap. Conservative: it advances
  /// by steps that cannot close the gap, bounded by the largest relative
  /// displacement. Returns 0 if the primitives start within
  /// 'minimum_distance'. A walk that takes many steps (a pair sliding at
  /// a tiny gap, where those steps shrink with the gap) also strides as
  /// far as the plane separating the pair, held fixed, keeps the gap.
  double additive_ccd(PrimitivePair        pair,
                      const Points4       &x,
                      const Displacements &dx,
                      double               minimum_distance,
                      double               kept_fraction = 0.1);

  /// The distance of the pair (point-triangle or segment-segment).
  double primitive_distance(PrimitivePair pair, const Points4 &x);
} // namespace coshell::contact
