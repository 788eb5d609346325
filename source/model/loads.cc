#include <coshell/model/loads.h>

#include <deal.II/base/utilities.h>

#include <sstream>
#include <stdexcept>

namespace coshell::model
{
  using namespace dealii;

  namespace
  {
    std::vector<double> parse_three_numbers(const std::string &text)
    {
      std::istringstream  in(text);
      std::vector<double> numbers;
      double              x;
      while (in >> x)
        numbers.push_back(x);
      if (!in.eof() || numbers.size() != 3)
        throw std::invalid_argument("'" + Utilities::trim(text) +
                                    "' is not three numbers");
      return numbers;
    }

    void add_at_vertex(const ShellModel &model,
                       const PointLoad  &load,
                       unsigned int      first_component,
                       Vector<double>   &rhs,
                       std::ostream     &log)
    {
      const unsigned int v    = model.nearest_vertex(load.where);
      const auto        &dofs = model.vertex_dofs(v);
      for (unsigned int d = 0; d < 3; ++d)
        rhs[dofs[first_component + d]] += load.value[d];
      log << "  point load at (" << load.where << ") applied at vertex " << v
          << " (" << model.surface().get_vertices()[v] << ")\n";
    }

    /// Each boundary edge with the load's id takes the share of the total
    /// given by its length, half to each of its vertices: the consistent
    /// load of a uniform line force on linear edges.
    void add_on_edges(const ShellModel &model,
                      const EdgeLoad   &load,
                      Vector<double>   &rhs,
                      std::ostream     &log)
    {
      std::vector<std::pair<double, std::array<unsigned int, 2>>> edges;
      double                                                      length = 0;
      for (const auto &cell : model.dof_handler().active_cell_iterators())
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary() &&
              cell->face(f)->boundary_id() == load.boundary)
          {
            const auto edge = cell->face(f);
            edges.push_back({edge->measure(),
                             {edge->vertex_index(0), edge->vertex_index(1)}});
            length += edges.back().first;
          }
      if (edges.empty())
        throw std::invalid_argument("Loads/Edge forces: boundary id " +
                                    std::to_string(load.boundary) +
                                    ", which the mesh does not have");
      for (const auto &[edge_length, vertices] : edges)
        for (const unsigned int v : vertices)
          for (unsigned int d = 0; d < 3; ++d)
            rhs[model.vertex_dofs(v)[ux + d]] +=
                0.5 * edge_length / length * load.total[d];
      log << "  edge force on boundary " << load.boundary << ": "
          << edges.size() << " edges, length " << length << "\n";
    }
  } // namespace

  std::vector<EdgeLoad> parse_edge_loads(const std::string &text)
  {
    std::vector<EdgeLoad> loads;
    for (const auto &entry : Utilities::split_string_list(text, ';'))
    {
      const auto parts = Utilities::split_string_list(entry, ':');
      try
      {
        if (parts.size() != 2)
          throw std::invalid_argument("is not of the form 'id : fx fy fz'");
        const int  id    = Utilities::string_to_int(parts[0]);
        const auto value = parse_three_numbers(parts[1]);
        if (id < 0 ||
            types::boundary_id(id) == numbers::internal_face_boundary_id)
          throw std::invalid_argument("has no valid boundary id");
        loads.push_back({types::boundary_id(id),
                         Tensor<1, 3>({value[0], value[1], value[2]})});
      }
      catch (const std::exception &error)
      {
        throw std::invalid_argument("edge force '" + entry +
                                    "': " + error.what());
      }
    }
    return loads;
  }

  std::vector<PointLoad> parse_point_loads(const std::string &text)
  {
    std::vector<PointLoad> loads;
    for (const auto &entry : Utilities::split_string_list(text, ';'))
    {
      const auto parts = Utilities::split_string_list(entry, ':');
      if (parts.size() != 2)
        throw std::invalid_argument("point load '" + entry +
                                    "' is not of the form 'x y z : vx vy vz'");
      try
      {
        const auto where = parse_three_numbers(parts[0]);
        const auto value = parse_three_numbers(parts[1]);
        loads.push_back({Point<3>(where[0], where[1], where[2]),
                         Tensor<1, 3>({value[0], value[1], value[2]})});
      }
      catch (const std::invalid_argument &error)
      {
        throw std::invalid_argument("point load '" + entry +
                                    "': " + error.what());
      }
    }
    return loads;
  }

  void Loads::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Loads");
    prm.declare_entry("Pressure", "0", Patterns::Double(),
                      "Uniform pressure along the oriented cell normal, "
                      "lumped to the vertices. Unit: force/length^2 (Pa = "
                      "N/m^2 in SI, MPa = N/mm^2 in mm-N-s-tonne scenes).");
    prm.declare_entry("Pressure type", "dead",
                      Patterns::Selection("dead|follower"),
                      "Selects the pressure direction. "
                      "dead: the pressure keeps the direction of the initial "
                      "normals; follower: it follows the deformed normals "
                      "(co-rotational formulation only; same as dead in "
                      "linear runs).");
    prm.declare_entry("Gravity", "0, 0, 0",
                      Patterns::List(Patterns::Double(), 3, 3),
                      "Acceleration vector gx, gy, gz; the load is "
                      "density * thickness * area * g, lumped to the "
                      "vertices. Unit: length/time^2 (m/s^2 in SI, mm/s^2 "
                      "in mm-N-s-tonne scenes: 9810 for g).");
    prm.declare_entry("Point forces", "", Patterns::Anything(),
                      "Forces at the vertex nearest each point, as "
                      "'x y z : fx fy fz' entries separated by ';'. Unit: "
                      "length for x y z (m in SI, mm in the IOL scenes), force "
                      "for fx fy fz (N).");
    prm.declare_entry("Point moments", "", Patterns::Anything(),
                      "Moments at the vertex nearest each point, as "
                      "'x y z : mx my mz' entries separated by ';'. Unit: "
                      "length for x y z (m in SI, mm in the IOL scenes), "
                      "force*length for mx my mz (N m in SI, N mm in "
                      "mm-N-s-tonne scenes).");
    prm.declare_entry("Edge forces", "", Patterns::Anything(),
                      "Forces spread uniformly along the boundary edges of "
                      "one boundary id (a gmsh physical curve), as "
                      "'id : fx fy fz' entries separated by ';'; fx fy fz "
                      "is the resultant, each edge taking its share by "
                      "length. Unit: force for fx fy fz (N).");
    prm.declare_entry("Load factor", "1", Patterns::Double(),
                      "Multiplies every load above. Unit: dimensionless.");
    prm.leave_subsection();
  }

  void Loads::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Loads");
    pressure     = prm.get_double("Pressure");
    const auto g = Utilities::string_to_double(
        Utilities::split_string_list(prm.get("Gravity")));
    gravity = Tensor<1, 3>({g[0], g[1], g[2]});
    scale   = prm.get_double("Load factor");
    try
    {
      point_forces  = parse_point_loads(prm.get("Point forces"));
      point_moments = parse_point_loads(prm.get("Point moments"));
      edge_forces   = parse_edge_loads(prm.get("Edge forces"));
    }
    catch (const std::invalid_argument &error)
    {
      prm.leave_subsection();
      throw std::invalid_argument(std::string("Loads: ") + error.what());
    }
    prm.leave_subsection();
  }

  void Loads::add_distributed(const ShellModel &model,
                              double            dead_pressure,
                              Vector<double>   &rhs) const
  {
    for (const auto &cell : model.dof_handler().active_cell_iterators())
    {
      const auto        &material   = model.material(cell);
      const double       areal_mass = material.density * material.thickness;
      const Tensor<1, 3> force_per_area =
          dead_pressure * model.unit_normal(cell) + areal_mass * gravity;
      const Tensor<1, 3> vertex_force =
          force_per_area * element::area(model.triangle(cell)) / 3.0;
      for (unsigned int v = 0; v < 3; ++v)
      {
        const VertexDofs &dofs = model.vertex_dofs(cell->vertex_index(v));
        for (unsigned int d = 0; d < 3; ++d)
          rhs[dofs[ux + d]] += vertex_force[d];
      }
    }
  }

  double Loads::follower_pressure() const
  {
    return pressure_follows ? scale * pressure : 0.0;
  }

  void Loads::assemble(const ShellModel &model,
                       Vector<double>   &rhs,
                       std::ostream     &log,
                       bool              follower_handled_elsewhere) const
  {
    Vector<double> load(rhs.size());
    const double   dead_pressure =
        pressure_follows && follower_handled_elsewhere ? 0.0 : pressure;
    if (dead_pressure != 0 || gravity.norm() != 0)
      add_distributed(model, dead_pressure, load);
    for (const auto &force : point_forces)
      add_at_vertex(model, force, ux, load, log);
    for (const auto &moment : point_moments)
      add_at_vertex(model, moment, rx, load, log);
    for (const auto &force : edge_forces)
      add_on_edges(model, force, load, log);
    rhs.add(scale, load);
  }
} // namespace coshell::model
