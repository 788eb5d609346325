// Lumped follower pressure: the load turns with the surface, so it depends
// on the current positions and contributes a (non-symmetric) load stiffness.

#include <coshell/element/corotational.h>

namespace coshell::element
{
  Tensor<2, 3> skew(const Tensor<1, 3> &a)
  {
    Tensor<2, 3> s;
    s[0][1] = -a[2];
    s[0][2] = a[1];
    s[1][0] = a[2];
    s[1][2] = -a[0];
    s[2][0] = -a[1];
    s[2][1] = a[0];
    return s;
  }

  void follower_pressure(const SpatialTriangle &current,
                         double                 pressure_times_sign,
                         std::array<double, 9> &force,
                         FullMatrix<double>    *load_stiffness)
  {
    // Each vertex carries a third of p A n = p/2 (x1 - x0) x (x2 - x0).
    const Tensor<1, 3> edge_1 = current[1] - current[0];
    const Tensor<1, 3> edge_2 = current[2] - current[0];
    const double       scale  = pressure_times_sign / 6.0;
    const Tensor<1, 3> nodal  = scale * cross_product_3d(edge_1, edge_2);
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int c = 0; c < 3; ++c)
        force[3 * i + c] = nodal[c];
    if (load_stiffness == nullptr)
      return;

    // d(e1 x e2) = de1 x e2 + e1 x de2 = -skew(e2) de1 + skew(e1) de2, with
    // de1 = dx1 - dx0 and de2 = dx2 - dx0; the same for every vertex.
    const std::array<Tensor<2, 3>, 3> derivative = {
        {scale * skew(current[2] - current[1]), -scale * skew(edge_2),
         scale * skew(edge_1)}};
    load_stiffness->reinit(9, 9);
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        for (unsigned int a = 0; a < 3; ++a)
          for (unsigned int b = 0; b < 3; ++b)
            (*load_stiffness)(3 * i + a, 3 * j + b) = derivative[j][a][b];
  }
} // namespace coshell::element
