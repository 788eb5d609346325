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

  /// A force spread uniformly along the boundary edges with one id.
  struct EdgeLoad
  {
    dealii::types::boundary_id boundary = 0;
    dealii::Tensor<1, 3>       total; ///< resultant force
  };

  /// Parses "id : fx fy fz; id : fx fy fz ...".
  std::vector<EdgeLoad> parse_edge_loads(const std::string &text);

  /// prm subsection "Loads". Every load is a dead load in global axes,
  /// except pressure, which acts along the (oriented) cell normals: the
  /// initial ones (dead pressure) or, optionally in co-rotational runs, the
  /// current ones (follower pressure).
  class Loads
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm);
    void        parse_parameters(dealii::ParameterHandler &prm);

    /// Adds the dead-load vector. Pressure and gravity are lumped: each vertex
    /// of a triangle receives a third of its resultant, and no moment.
    /// 'log' is told which vertex each point load snapped to. A follower
    /// pressure is included along the initial normals unless
    /// 'follower_handled_elsewhere' (co-rotational runs add it per
    /// configuration).
    void assemble(const ShellModel       &model,
                  dealii::Vector<double> &rhs,
                  std::ostream           &log,
                  bool follower_handled_elsewhere = false) const;

    /// Pressure that follows the deformed normal (co-rotational runs), or 0
    /// when the pressure is a dead load (then it is in assemble()).
    double follower_pressure() const;

  private:
    double                 scale            = 1;
    double                 pressure         = 0;
    bool                   pressure_follows = false;
    dealii::Tensor<1, 3>   gravity;
    std::vector<PointLoad> point_forces, point_moments;
    std::vector<EdgeLoad>  edge_forces;

    void add_distributed(const ShellModel       &model,
                         double                  dead_pressure,
                         dealii::Vector<double> &rhs) const;
  };
} // namespace coshell::model
