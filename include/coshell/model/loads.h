#pragma once

#include <coshell/model/shell_model.h>

#include <deal.II/base/parameter_handler.h>

#include <ostream>
#include <vector>

namespace coshell::model
{
  /// A force or moment applied at the mesh vertex nearest to 'where'.
  struct PointLoad
  {
    dealii::Point<3>     where;
    dealii::Tensor<1, 3> value;
  };

  /// Parses "x y z : vx vy vz; x y z : vx vy vz ...".
  std::vector<PointLoad> parse_point_loads(const std::string &text);

  /// prm subsection "Loads". Every load is a dead load in global axes,
  /// except pressure, which acts along the (oriented) cell normals.
  class Loads
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm);
    void        parse_parameters(dealii::ParameterHandler &prm);

    /// Adds the load vector. Pressure and gravity are lumped: each vertex
    /// of a triangle receives a third of its resultant, and no moment.
    /// 'log' is told which vertex each point load snapped to.
    void assemble(const ShellModel       &model,
                  dealii::Vector<double> &rhs,
                  std::ostream           &log) const;

    /// Multiplies every load (for parameter sweeps such as paper Table 1).
    double scale = 1;

  private:
    double                 pressure = 0;
    dealii::Tensor<1, 3>   gravity;
    std::vector<PointLoad> point_forces, point_moments;

    void add_distributed(const ShellModel       &model,
                         dealii::Vector<double> &rhs) const;
  };
} // namespace coshell::model
