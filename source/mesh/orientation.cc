#include <coshell/mesh/mesh.h>

#include <deal.II/base/exceptions.h>

#include <array>
#include <queue>

namespace coshell::mesh
{
  using namespace dealii;

  namespace
  {
    using CellIterator = Surface::active_cell_iterator;

    Tensor<1, 3> area_normal(const CellIterator &cell)
    {
      return 0.5 * cross_product_3d(cell->vertex(1) - cell->vertex(0),
                                    cell->vertex(2) - cell->vertex(0));
    }

    /// True when the cell's vertex cycle runs from vertex index 'from' to
    /// 'to' along one of its edges.
    bool
    runs_along(const CellIterator &cell, unsigned int from, unsigned int to)
    {
      for (unsigned int v = 0; v < 3; ++v)
        if (cell->vertex_index(v) == from &&
            cell->vertex_index((v + 1) % 3) == to)
          return true;
      return false;
    }

    /// Breadth-first walk over one connected patch, returning its cells.
    std::vector<CellIterator> orient_patch(const CellIterator &seed,
                                           std::vector<int>   &sign)
    {
      std::vector<CellIterator> patch{seed};
      std::queue<CellIterator>  front;
      sign[seed->active_cell_index()] = 1;
      front.push(seed);
      while (!front.empty())
      {
        const CellIterator cell = front.front();
        front.pop();
        for (unsigned int f = 0; f < cell->n_faces(); ++f)
        {
          if (cell->at_boundary(f))
            continue;
          const CellIterator neighbor = cell->neighbor(f);
          if (sign[neighbor->active_cell_index()] != 0)
            continue;
          const unsigned int p = cell->face(f)->vertex_index(0);
          const unsigned int q = cell->face(f)->vertex_index(1);
          // Consistent neighbours run along a shared edge in opposite
          // directions.
          const bool same_direction =
              runs_along(cell, p, q) == runs_along(neighbor, p, q);
          sign[neighbor->active_cell_index()] =
              same_direction ? -sign[cell->active_cell_index()]
                             : sign[cell->active_cell_index()];
          patch.push_back(neighbor);
          front.push(neighbor);
        }
      }
      return patch;
    }
  } // namespace

  std::vector<int> orient_normals(const Surface      &surface,
                                  const Tensor<1, 3> &reference)
  {
    std::vector<int> sign(surface.n_active_cells(), 0);
    for (const auto &seed : surface.active_cell_iterators())
    {
      if (sign[seed->active_cell_index()] != 0)
        continue;
      const std::vector<CellIterator> patch     = orient_patch(seed, sign);
      double                          alignment = 0;
      for (const auto &cell : patch)
        alignment +=
            sign[cell->active_cell_index()] * (area_normal(cell) * reference);
      if (alignment < 0)
        for (const auto &cell : patch)
          sign[cell->active_cell_index()] *= -1;
    }
    return sign;
  }
} // namespace coshell::mesh
