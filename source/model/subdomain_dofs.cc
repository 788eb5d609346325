#include <coshell/model/subdomain_dofs.h>

#include <vector>

namespace coshell::model
{
  using namespace dealii;

  IndexSet dofs_of_subdomain_cells(const DoFHandler<2, 3> &dof_handler,
                                   types::subdomain_id     subdomain)
  {
    IndexSet                             dofs(dof_handler.n_dofs());
    std::vector<types::global_dof_index> cell_dofs(
        dof_handler.get_fe().n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->subdomain_id() == subdomain)
      {
        cell->get_dof_indices(cell_dofs);
        dofs.add_indices(cell_dofs.begin(), cell_dofs.end());
      }
    dofs.compress();
    return dofs;
  }
} // namespace coshell::model
