#pragma once

#include <coshell/model/shell_model.h>

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <vector>

namespace coshell::io
{
  /// VTU + PVD output of nodal displacement and rotation vectors and of
  /// per-cell membrane forces and bending moments (global-axis tensor
  /// components), from prm subsection "Output".
  class VtuOutput
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm);
    void        parse_parameters(dealii::ParameterHandler &prm);

    /// Writes DIRECTORY/solution.vtu and its index DIRECTORY/solution.pvd
    /// (when output is enabled). Returns the .pvd path or "".
    std::string write(const model::ShellModel                     &model,
                      const dealii::Vector<double>                &solution,
                      const std::vector<element::ShellResultants> &resultants,
                      const std::string &directory) const;

    /// Output directory from the prm ("Output/Directory").
    std::string directory = "output";

  private:
    bool write_vtu_ = true;
  };
} // namespace coshell::io
