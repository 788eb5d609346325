#include <coshell/base/expressions.h>
#include <coshell/model/cell_loop.h>
#include <coshell/model/shell_model.h>
#include <coshell/model/subdomain_dofs.h>

#include <deal.II/dofs/dof_renumbering.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <algorithm>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace coshell::model
{
  using namespace dealii;

  namespace
  {
    Point<3> centroid(const element::SpatialTriangle &corners)
    {
      Point<3> sum;
      for (const auto &corner : corners)
        sum += corner;
      return sum / 3.0;
    }

    const std::array<std::string, dofs_per_vertex> component_names = {
        {"ux", "uy", "uz", "rx", "ry", "rz"}};
  } // namespace

  Component parse_component(const std::string &name)
  {
    for (unsigned int c = 0; c < dofs_per_vertex; ++c)
      if (name == component_names[c])
        return static_cast<Component>(c);
    throw std::invalid_argument("unknown component '" + name +
                                "' (expected ux, uy, uz, rx, ry or rz)");
  }

  ShellModel::ShellModel(const mesh::Surface     &surface,
                         const ElementParameters &element,
                         const Tensor<1, 3>      &normal_reference)
      : surface_(surface), element_(element),
        fe_(FE_SimplexP<2, 3>(1), dofs_per_vertex), dof_handler_(surface),
        normal_sign_(mesh::orient_normals(surface, normal_reference))
  {
    // The kernels number DoFs as 6*vertex + component; make sure deal.II
    // agrees so that element matrices scatter without permutation.
    for (unsigned int i = 0; i < fe_.n_dofs_per_cell(); ++i)
      if (fe_.system_to_component_index(i) !=
          std::make_pair(i % dofs_per_vertex, i / dofs_per_vertex))
        throw std::logic_error("unexpected cell-local DoF order in FESystem");
    dof_handler_.distribute_dofs(fe_);
    number_dofs_by_rank();
    number_vertex_dofs();
    number_thickness_dofs();
    assign_cell_materials();
    assign_cell_options();
  }

  std::vector<double> ShellModel::cell_values_of(const std::string &text,
                                                 const std::string &name,
                                                 double uniform) const
  {
    if (text.empty())
      return std::vector<double>(surface_.n_active_cells(), uniform);
    // "region" is the parser's time variable, set to the material id.
    const auto function = base::parse_expressions<3>(
        text, 1, "x,y,z,region", true, "x, y, z, region", "Material/" + name);
    std::vector<double> values(surface_.n_active_cells());
    for (const auto &cell : dof_handler_.active_cell_iterators())
    {
      function->set_time(cell->material_id());
      values[cell->active_cell_index()] =
          function->value(centroid(triangle(cell)));
    }
    return values;
  }

  void ShellModel::assign_cell_materials()
  {
    const auto thickness =
        cell_values_of(element_.thickness_expression, "Thickness",
                       element_.material.thickness);
    const auto density = cell_values_of(element_.density_expression, "Density",
                                        element_.material.density);
    cell_materials_.assign(surface_.n_active_cells(), element_.material);
    vertex_thickness_.assign(surface_.n_vertices(), 0);
    std::vector<double> vertex_area(surface_.n_vertices(), 0);
    double              area = 0, thickness_sum = 0, density_sum = 0;
    for (const auto &cell : dof_handler_.active_cell_iterators())
    {
      const unsigned int index    = cell->active_cell_index();
      auto              &material = cell_materials_[index];
      material.thickness          = thickness[index];
      material.density            = density[index];
      const auto corners          = triangle(cell);
      try
      {
        material.validate();
      }
      catch (const std::invalid_argument &error)
      {
        std::ostringstream where;
        where << "Material: at triangle " << index << " (centroid "
              << centroid(corners) << ", region " << int(cell->material_id())
              << "): ";
        throw std::invalid_argument(where.str() + error.what());
      }
      const double a = element::area(corners);
      area += a;
      thickness_sum += a * material.thickness;
      density_sum += a * material.density;
      for (unsigned int v = 0; v < 3; ++v)
      {
        vertex_thickness_[cell->vertex_index(v)] += a * material.thickness;
        vertex_area[cell->vertex_index(v)] += a;
      }
    }
    for (unsigned int v = 0; v < vertex_area.size(); ++v)
      if (vertex_area[v] > 0)
        vertex_thickness_[v] /= vertex_area[v];
    if (!element_.uniform_properties())
    {
      element_.material.thickness = thickness_sum / area;
      element_.material.density   = density_sum / area;
    }
  }

  const element::ShellMaterial &
  ShellModel::material(const CellIterator &cell) const
  {
    return cell_materials_[cell->active_cell_index()];
  }

  // On a faceted curved surface a facet's normal is off its vertices' mean
  // normals by phi, so part of the bending rotation reads as drilling, and
  // the ANDES drilling terms (the higher-order stiffness K_h and the Allman
  // weight alpha_b of K_b) charge it at membrane stiffness, E h: relative
  // to bending that is (l phi / h)^2, which locks coarse curved meshes.
  // Each term is divided by 1 + c (l phi / h)^2 with its own c; flat meshes
  // keep Felippa's element (factors 1).
  void ShellModel::assign_cell_options()
  {
    cell_options_.assign(surface_.n_active_cells(), element_.options);
    const double c_higher = element_.andes_curvature_scaling;
    const double c_basic  = element_.andes_basic_drilling_scaling;
    if ((c_higher == 0 && c_basic == 0) ||
        element_.options.membrane != element::MembraneElement::andes)
      return;
    // Area-weighted mean of the oriented cell normals at each vertex.
    std::vector<Tensor<1, 3>> vertex_normal(surface_.n_vertices());
    for (const auto &cell : dof_handler_.active_cell_iterators())
      for (unsigned int v = 0; v < 3; ++v)
        vertex_normal[cell->vertex_index(v)] +=
            element::area(triangle(cell)) * unit_normal(cell);
    for (const auto &cell : dof_handler_.active_cell_iterators())
    {
      const Tensor<1, 3> normal = unit_normal(cell);
      double             phi_sq = 0, edge_sq = 0;
      const auto         corners = triangle(cell);
      for (unsigned int v = 0; v < 3; ++v)
      {
        const Tensor<1, 3> &mean = vertex_normal[cell->vertex_index(v)];
        const double        cosine =
            std::min(1.0, std::abs(normal * mean) / mean.norm());
        phi_sq = std::max(phi_sq, 2.0 * (1.0 - cosine)); // ~ phi^2
        edge_sq += (corners[(v + 1) % 3] - corners[v]).norm_square() / 3.0;
      }
      const double h       = material(cell).thickness;
      const double locking = edge_sq * phi_sq / (h * h);
      auto &scales = cell_options_[cell->active_cell_index()].andes_scales;
      scales.higher_order   = 1.0 / (1.0 + c_higher * locking);
      scales.basic_drilling = 1.0 / (1.0 + c_basic * locking);
    }
  }

  const element::ShellElementOptions &
  ShellModel::element_options(const CellIterator &cell) const
  {
    return cell_options_[cell->active_cell_index()];
  }

  double ShellModel::vertex_thickness(unsigned int v) const
  {
    return vertex_thickness_[v];
  }

  std::pair<double, double> ShellModel::thickness_range() const
  {
    std::pair<double, double> range{std::numeric_limits<double>::max(), 0};
    for (const auto &material : cell_materials_)
    {
      range.first  = std::min(range.first, material.thickness);
      range.second = std::max(range.second, material.thickness);
    }
    return range;
  }

  double ShellModel::mass() const
  {
    double sum = 0;
    for (const auto &cell : dof_handler_.active_cell_iterators())
    {
      const auto &cell_material = material(cell);
      sum += cell_material.density * cell_material.thickness *
             element::area(triangle(cell));
    }
    return sum;
  }

  void ShellModel::number_dofs_by_rank()
  {
    locally_owned_dofs_ = complete_index_set(dof_handler_.n_dofs());
    if (!base::distributed())
      return;
    DoFRenumbering::subdomain_wise(dof_handler_);
    const auto owned = DoFTools::locally_owned_dofs_per_subdomain(dof_handler_);
    if (owned.size() != base::n_ranks())
      throw std::logic_error("the mesh is not partitioned into one part per "
                             "MPI rank");
    locally_owned_dofs_ = owned[base::this_rank()];
    if (!locally_owned_dofs_.is_contiguous())
      throw std::logic_error("the DoFs of one rank are not contiguous");
  }

  const IndexSet &ShellModel::locally_owned_dofs() const
  {
    return locally_owned_dofs_;
  }

  void ShellModel::throw_not_a_vertex(unsigned int v) const
  {
    throw std::out_of_range("vertex " + std::to_string(v) +
                            " is not a vertex of the mesh (it has " +
                            std::to_string(vertex_dofs_.size()) + ")");
  }

  void ShellModel::number_vertex_dofs()
  {
    const global_dof_index invalid = numbers::invalid_dof_index;
    VertexDofs             unused;
    unused.fill(invalid);
    vertex_dofs_.assign(surface_.n_vertices(), unused);
    for (const auto &cell : dof_handler_.active_cell_iterators())
      for (unsigned int v = 0; v < cell->n_vertices(); ++v)
        for (unsigned int c = 0; c < dofs_per_vertex; ++c)
          vertex_dofs_[cell->vertex_index(v)][c] = cell->vertex_dof_index(v, c);
  }

  void ShellModel::number_thickness_dofs()
  {
    if (!element_.thickness_stretch)
      return;
    if (base::distributed())
      throw std::invalid_argument(
          "Element/Thickness stretch runs on one MPI rank only (its DoFs "
          "come after every rank's range)");
    thickness_dofs_.assign(surface_.n_vertices(), numbers::invalid_dof_index);
    global_dof_index next = dof_handler_.n_dofs();
    for (unsigned int v = 0; v < surface_.n_vertices(); ++v)
      if (vertex_is_used(v))
        thickness_dofs_[v] = next++;
    locally_owned_dofs_ = complete_index_set(next);
  }

  void ShellModel::add_thickness_sparsity(
      const AffineConstraints<double> &constraints,
      DynamicSparsityPattern          &dsp) const
  {
    std::vector<global_dof_index> dofs(element::shell_dofs);
    for (const auto &cell : dof_handler_.active_cell_iterators())
    {
      cell->get_dof_indices(dofs);
      dofs.resize(element::shell_dofs);
      for (unsigned int v = 0; v < 3; ++v)
        dofs.push_back(thickness_dofs_[cell->vertex_index(v)]);
      constraints.add_entries_local_to_global(dofs, dsp, false);
    }
  }

  global_dof_index ShellModel::n_fe_dofs() const
  {
    return dof_handler_.n_dofs();
  }

  double ShellModel::current_thickness(const CellIterator   &cell,
                                       const Vector<double> &values) const
  {
    const double reference = material(cell).thickness;
    if (!has_thickness_stretch())
      return reference;
    double mean_stretch = 0;
    for (unsigned int v = 0; v < 3; ++v)
      mean_stretch += thickness_stretch(cell->vertex_index(v), values) / 3.0;
    return reference * mean_stretch;
  }

  Vector<double> ShellModel::fe_part(const Vector<double> &v) const
  {
    if (!has_thickness_stretch() || v.size() == 0)
      return v;
    return Vector<double>(v.begin(), v.begin() + n_fe_dofs());
  }

  const DoFHandler<2, 3> &ShellModel::dof_handler() const
  {
    return dof_handler_;
  }

  const mesh::Surface &ShellModel::surface() const
  {
    return surface_;
  }

  const ElementParameters &ShellModel::element_parameters() const
  {
    return element_;
  }

  global_dof_index ShellModel::n_dofs() const
  {
    return locally_owned_dofs_.size();
  }

  bool ShellModel::vertex_is_used(unsigned int v) const
  {
    return vertex_dofs_.at(v)[0] != numbers::invalid_dof_index;
  }

  Vector<double> ShellModel::to_vertex_order(const Vector<double> &dofs) const
  {
    if (dofs.size() == 0)
      return {};
    const unsigned int n_vertices = vertex_dofs_.size();
    Vector<double>     by_vertex((dofs_per_vertex + thickness_fields()) *
                                 n_vertices);
    for (unsigned int v = 0; v < n_vertices; ++v)
      if (vertex_is_used(v))
      {
        for (unsigned int c = 0; c < dofs_per_vertex; ++c)
          by_vertex[dofs_per_vertex * v + c] = dofs[vertex_dofs_[v][c]];
        if (has_thickness_stretch())
          by_vertex[dofs_per_vertex * n_vertices + v] =
              dofs[thickness_dofs_[v]];
      }
    return by_vertex;
  }

  Vector<double>
  ShellModel::from_vertex_order(const Vector<double> &by_vertex) const
  {
    if (by_vertex.size() == 0)
      return {};
    const unsigned int n_vertices = vertex_dofs_.size();
    const unsigned int per_vertex = dofs_per_vertex + thickness_fields();
    if (by_vertex.size() != per_vertex * n_vertices)
      throw std::invalid_argument(
          "it holds " + std::to_string(by_vertex.size() / per_vertex) +
          " vertices, the scene's mesh has " + std::to_string(n_vertices) +
          " (another mesh or refinement, or Element/Thickness stretch "
          "switched)");
    Vector<double> dofs(n_dofs());
    for (unsigned int v = 0; v < n_vertices; ++v)
      if (vertex_is_used(v))
      {
        for (unsigned int c = 0; c < dofs_per_vertex; ++c)
          dofs[vertex_dofs_[v][c]] = by_vertex[dofs_per_vertex * v + c];
        if (has_thickness_stretch())
          dofs[thickness_dofs_[v]] =
              by_vertex[dofs_per_vertex * n_vertices + v];
      }
    return dofs;
  }

  unsigned int ShellModel::nearest_vertex(const Point<3> &point) const
  {
    unsigned int best          = numbers::invalid_unsigned_int;
    double       best_distance = std::numeric_limits<double>::max();
    const auto  &vertices      = surface_.get_vertices();
    for (unsigned int v = 0; v < vertices.size(); ++v)
      if (vertex_is_used(v) && vertices[v].distance(point) < best_distance)
      {
        best          = v;
        best_distance = vertices[v].distance(point);
      }
    return best;
  }

  element::SpatialTriangle ShellModel::triangle(const CellIterator &cell) const
  {
    return {{cell->vertex(0), cell->vertex(1), cell->vertex(2)}};
  }

  Tensor<1, 3> ShellModel::unit_normal(const CellIterator &cell) const
  {
    const Tensor<1, 3> n = cross_product_3d(cell->vertex(1) - cell->vertex(0),
                                            cell->vertex(2) - cell->vertex(0));
    return normal_sign_[cell->active_cell_index()] * n / n.norm();
  }

  int ShellModel::normal_sign(const CellIterator &cell) const
  {
    return normal_sign_[cell->active_cell_index()];
  }

  void ShellModel::orient_moments(const CellIterator       &cell,
                                  element::ShellResultants &resultants) const
  {
    // Moments are measured with z along the oriented normal, which may be
    // opposite to the element frame's e3.
    if (normal_sign(cell) > 0)
      return;
    resultants.bending_global *= -1;
    for (double &m : resultants.bending_local)
      m = -m;
  }

  void ShellModel::make_sparsity(
      const AffineConstraints<double>                &constraints,
      SparsityPattern                                &pattern,
      const std::vector<std::array<unsigned int, 2>> &coupled) const
  {
    DynamicSparsityPattern dsp(n_dofs());
    if (has_thickness_stretch())
      add_thickness_sparsity(constraints, dsp);
    else
      DoFTools::make_sparsity_pattern(dof_handler_, dsp, constraints, false);
    for (const auto &[v, w] : coupled)
    {
      const auto coupled_dofs = [this](unsigned int vertex)
      {
        std::vector<global_dof_index> dofs(vertex_dofs_[vertex].begin(),
                                           vertex_dofs_[vertex].begin() + 3);
        if (has_thickness_stretch())
          dofs.push_back(thickness_dofs_[vertex]);
        return dofs;
      };
      for (const auto i : coupled_dofs(v))
        for (const auto j : coupled_dofs(w))
        {
          dsp.add(i, j);
          dsp.add(j, i);
        }
    }
    pattern.copy_from(dsp);
  }

  template<typename Matrix>
  void
  ShellModel::assemble_owned_cells(const AffineConstraints<double> &constraints,
                                   Matrix &matrix) const
  {
    matrix = 0;
    for_each_cell(
        dof_handler_,
        [this](const CellIterator &cell, CellContribution &contribution)
        {
          contribution.matrix = element::shell_stiffness(
              triangle(cell), material(cell), element_options(cell));
        },
        [&](const CellContribution &contribution)
        {
          constraints.distribute_local_to_global(contribution.matrix,
                                                 contribution.dofs, matrix);
        },
        CellRange::owned);
  }

  void
  ShellModel::assemble_stiffness(const AffineConstraints<double> &constraints,
                                 SparseMatrix<double>            &matrix) const
  {
    assemble_owned_cells(constraints, matrix);
    base::sum_over_ranks(matrix);
  }

  void
  ShellModel::assemble_stiffness(const AffineConstraints<double> &constraints,
                                 TrilinosWrappers::SparseMatrix  &matrix) const
  {
    assemble_owned_cells(constraints, matrix);
    matrix.compress(VectorOperation::add);
  }

  void ShellModel::make_distributed_sparsity(
      const AffineConstraints<double>                &constraints,
      const IndexSet                                 &owned_rows,
      TrilinosWrappers::SparsityPattern              &pattern,
      const std::vector<std::array<unsigned int, 2>> &coupled) const
  {
    const auto rank             = base::this_rank();
    IndexSet   rows_of_my_cells = dofs_of_subdomain_cells(dof_handler_, rank);
    // Constraints tie a DoF of my cells to others: their rows are written.
    std::vector<types::global_dof_index> constrained_to;
    for (const auto &line : constraints.get_lines())
      if (rows_of_my_cells.is_element(line.index))
        for (const auto &entry : line.entries)
          constrained_to.push_back(entry.first);
    std::sort(constrained_to.begin(), constrained_to.end());
    rows_of_my_cells.add_indices(constrained_to.begin(), constrained_to.end());
    rows_of_my_cells.compress();
    pattern.reinit(owned_rows, owned_rows, rows_of_my_cells, MPI_COMM_WORLD);
    DoFTools::make_sparsity_pattern(dof_handler_, pattern, constraints, false,
                                    rank);
    // Terms that couple vertices beyond the cells reach each row from the
    // rank that owns it (see base::RowsOf).
    for (const auto &[v, w] : coupled)
      for (const auto &[row_vertex, column_vertex] :
           {std::pair{v, w}, std::pair{w, v}})
        for (unsigned int i = 0; i < 3; ++i)
          if (const auto row = vertex_dofs_[row_vertex][i];
              owned_rows.is_element(row))
            for (unsigned int j = 0; j < 3; ++j)
              pattern.add(row, vertex_dofs_[column_vertex][j]);
    pattern.compress();
  }

  element::ShellDisplacements
  ShellModel::cell_values(const CellIterator   &cell,
                          const Vector<double> &u) const
  {
    std::vector<global_dof_index> dofs(element::shell_dofs);
    cell->get_dof_indices(dofs);
    element::ShellDisplacements values;
    for (unsigned int i = 0; i < element::shell_dofs; ++i)
      values[i] = u[dofs[i]];
    return values;
  }

  std::vector<element::ShellResultants>
  ShellModel::resultants(const Vector<double> &solution) const
  {
    std::vector<element::ShellResultants> result(surface_.n_active_cells());
    for (const auto &cell : dof_handler_.active_cell_iterators())
    {
      auto &r = result[cell->active_cell_index()];
      r       = element::shell_resultants(triangle(cell), material(cell),
                                          element_options(cell),
                                          cell_values(cell, solution));
      orient_moments(cell, r);
    }
    return result;
  }
} // namespace coshell::model
