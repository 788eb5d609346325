#pragma once

#include <deal.II/base/index_set.h>
#include <deal.II/base/types.h>
#include <deal.II/dofs/dof_handler.h>

namespace coshell::model
{
  /// The DoFs of the active cells whose subdomain id is 'subdomain': the
  /// rows a rank writes when it assembles its own cells into a distributed
  /// matrix (its owned rows and those its cells share with other ranks).
  dealii::IndexSet
  dofs_of_subdomain_cells(const dealii::DoFHandler<2, 3> &dof_handler,
                          dealii::types::subdomain_id     subdomain);
} // namespace coshell::model
