#pragma once

#include <coshell/base/parallel_environment.h>
#include <coshell/element/shell_element.h>

#include <deal.II/base/work_stream.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/grid/filtered_iterator.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <array>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace coshell::model
{
  /// What one cell contributes: an 18x18 matrix and/or an 18-vector.
  struct CellContribution
  {
    dealii::FullMatrix<double>                   matrix;
    dealii::Vector<double>                       vector;
    std::vector<dealii::types::global_dof_index> dofs =
        std::vector<dealii::types::global_dof_index>(element::shell_dofs);
    unsigned int cell_index = 0; ///< the cell's active_cell_index()
    /// The part of 'vector' of each force kind (internal, external,
    /// inertia): assembled unconstrained, they give the force scale of a
    /// nonlinear solve and the work of the loads.
    std::array<std::array<double, element::shell_dofs>, 3> forces_by_kind{};
    /// The cell's energy, when a loop asks for energies.
    double      energy = 0;
    std::string error;
  };

  /// Which cells a loop visits: all of them (results every rank needs,
  /// computed on each), or the cells this rank owns (assembly whose sums
  /// the caller adds up over the ranks).
  enum class CellRange
  {
    all,
    owned
  };

  /// Multithreaded loop over the active cells (WorkStream): 'compute(cell,
  /// contribution)' fills the cell's contribution in parallel and
  /// 'distribute(contribution)' adds it to global objects in order. An
  /// exception thrown by 'compute' would abort the program inside
  /// WorkStream, so it is carried to the copier and rethrown afterwards,
  /// naming the element. With CellRange::owned on several ranks, a failure
  /// on any rank is raised on all of them, so none waits for the others.
  template<typename Compute, typename Distribute>
  void for_each_cell(const dealii::DoFHandler<2, 3> &dof_handler,
                     const Compute                  &compute,
                     const Distribute               &distribute,
                     CellRange                       range = CellRange::all)
  {
    using CellIterator = dealii::DoFHandler<2, 3>::active_cell_iterator;
    struct Scratch
    {
    };
    std::string first_error;
    const auto  worker =
        [&compute](const CellIterator &cell, Scratch &, CellContribution &copy)
    {
      copy.error.clear();
      cell->get_dof_indices(copy.dofs);
      copy.cell_index = cell->active_cell_index();
      try
      {
        compute(cell, copy);
      }
      catch (const std::exception &error)
      {
        std::ostringstream message;
        message << "element " << cell->active_cell_index() << " at ("
                << cell->center() << "): " << error.what();
        copy.error = message.str();
      }
    };
    const auto copier = [&](const CellContribution &copy)
    {
      if (!copy.error.empty())
      {
        if (first_error.empty())
          first_error = copy.error;
        return;
      }
      distribute(copy);
    };
    if (range == CellRange::owned && base::distributed())
    {
      // The mesh is partitioned by subdomain id (METIS), one part per rank.
      using Filtered = dealii::FilteredIterator<CellIterator>;
      const dealii::IteratorFilters::SubdomainEqualTo mine(base::this_rank());
      dealii::WorkStream::run(Filtered(mine, dof_handler.begin_active()),
                              Filtered(mine, dof_handler.end()), worker, copier,
                              Scratch(), CellContribution());
      if (base::any_rank(!first_error.empty()) && first_error.empty())
        first_error = "an element on another rank failed (its message is "
                      "above)";
    }
    else
      dealii::WorkStream::run(dof_handler.begin_active(), dof_handler.end(),
                              worker, copier, Scratch(), CellContribution());
    if (!first_error.empty())
      throw std::runtime_error(first_error);
  }
} // namespace coshell::model
