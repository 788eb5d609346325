#include <coshell/base/csv_file.h>
#include <coshell/base/expressions.h>
#include <coshell/contact/obstacle.h>
#include <coshell/mesh/mesh.h>

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

namespace coshell::contact
{
  using namespace dealii;

  void InputPath::append(double now, double time, double value)
  {
    // A hold at the present first, so that the ramp to the new sample
    // starts where the run is and the time integrated so far keeps its
    // positions.
    if (samples_.empty() || now > samples_.back().first)
      samples_.emplace_back(now, this->value(now));
    if (!(time > samples_.back().first))
      throw std::invalid_argument("an input must be for a time after the "
                                  "present");
    samples_.emplace_back(time, value);
  }

  double InputPath::value(double time) const
  {
    if (samples_.empty())
      return 0;
    const auto after = std::upper_bound(samples_.begin(), samples_.end(), time,
                                        [](double t, const auto &sample)
                                        { return t < sample.first; });
    if (after == samples_.begin())
      return samples_.front().second;
    if (after == samples_.end())
      return samples_.back().second;
    const auto &[t0, s0] = *(after - 1);
    const auto &[t1, s1] = *after;
    return s0 + (s1 - s0) * (time - t0) / (t1 - t0);
  }

  double Obstacle::friction_at(double time) const
  {
    if (!friction_of_time)
      return friction_coefficient;
    friction_of_time->set_time(time);
    const double mu = friction_of_time->value(Point<1>());
    // An expression that reaches 0 may round to -1e-17 there.
    if (mu > -1e-12)
      return std::max(mu, 0.0);
    std::ostringstream message;
    message << "obstacle '" << name << "': Friction coefficient is " << mu
            << " at t = " << time << " s; it must be >= 0";
    throw std::runtime_error(message.str());
  }

  std::vector<Point<3>> Obstacle::positions(double time) const
  {
    auto pose = motion.pose(time);
    if (input)
      pose.translation += input->value(time) * input_direction;
    std::vector<Point<3>> x(vertices.size());
    for (unsigned int i = 0; i < vertices.size(); ++i)
      x[i] = pose(vertices[i]);
    return x;
  }

  namespace
  {
    /// Merges coincident corners (STL lists every triangle's corners).
    class VertexMerger
    {
    public:
      explicit VertexMerger(std::vector<Point<3>> &vertices)
          : vertices_(vertices)
      {
      }
      unsigned int index(const Point<3> &p)
      {
        const auto key = std::array<double, 3>{{p[0], p[1], p[2]}};
        const auto [it, inserted] =
            known_.emplace(key, static_cast<unsigned int>(vertices_.size()));
        if (inserted)
          vertices_.push_back(p);
        return it->second;
      }

    private:
      std::vector<Point<3>>                        &vertices_;
      std::map<std::array<double, 3>, unsigned int> known_;
    };

    bool read_ascii_stl(std::istream                         &in,
                        std::vector<Point<3>>                &vertices,
                        std::vector<std::array<unsigned, 3>> &triangles)
    {
      VertexMerger            merger(vertices);
      std::string             word;
      std::array<unsigned, 3> triangle{};
      unsigned int            corner = 0;
      while (in >> word)
        if (word == "vertex")
        {
          Point<3> p;
          if (!(in >> p[0] >> p[1] >> p[2]))
            return false;
          triangle[corner++] = merger.index(p);
          if (corner == 3)
            triangles.push_back(triangle), corner = 0;
        }
      return corner == 0;
    }

    bool read_binary_stl(std::istream                         &in,
                         std::vector<Point<3>>                &vertices,
                         std::vector<std::array<unsigned, 3>> &triangles)
    {
      char          header[80];
      std::uint32_t count = 0;
      if (!in.read(header, 80) || !in.read(reinterpret_cast<char *>(&count), 4))
        return false;
      VertexMerger merger(vertices);
      for (std::uint32_t k = 0; k < count; ++k)
      {
        float         record[12];
        std::uint16_t attribute;
        if (!in.read(reinterpret_cast<char *>(record), sizeof(record)) ||
            !in.read(reinterpret_cast<char *>(&attribute), 2))
          return false;
        std::array<unsigned, 3> triangle;
        for (unsigned int c = 0; c < 3; ++c) // record[0..2]: the normal
          triangle[c] = merger.index(Point<3>(
              record[3 + 3 * c], record[4 + 3 * c], record[5 + 3 * c]));
        triangles.push_back(triangle);
      }
      return true;
    }

    void read_stl(const std::string                    &file,
                  std::vector<Point<3>>                &vertices,
                  std::vector<std::array<unsigned, 3>> &triangles)
    {
      std::ifstream in(file, std::ios::binary);
      if (!in)
        throw std::runtime_error("cannot open STL file '" + file + "'");
      const std::string text((std::istreambuf_iterator<char>(in)),
                             std::istreambuf_iterator<char>());
      // "solid" opens an ASCII file, but some binary files start so too:
      // a binary file's size is 84 + 50 * (its triangle count).
      std::uint32_t count = 0;
      if (text.size() >= 84)
        std::memcpy(&count, text.data() + 80, 4);
      const bool binary =
          text.size() >= 84 && text.size() == 84 + 50ull * count;
      std::istringstream stream(text);
      const bool ok = binary ? read_binary_stl(stream, vertices, triangles)
                             : read_ascii_stl(stream, vertices, triangles);
      if (!ok)
        throw std::runtime_error("STL file '" + file +
                                 "' is truncated or "
                                 "malformed");
    }
  } // namespace

  void read_triangle_surface(const std::string                    &file,
                             std::vector<Point<3>>                &vertices,
                             std::vector<std::array<unsigned, 3>> &triangles,
                             const mesh::GmshConstants            &constants)
  {
    vertices.clear();
    triangles.clear();
    if (!std::filesystem::is_regular_file(file))
      throw std::runtime_error("mesh file '" + file + "' does not exist");
    const auto extension = std::filesystem::path(file).extension().string();
    if ((extension == ".stl" || extension == ".STL") && !constants.empty())
      throw std::runtime_error("mesh file '" + file +
                               "' is an STL file; it takes no gmsh "
                               "parameters");
    if (extension == ".stl" || extension == ".STL")
      read_stl(file, vertices, triangles);
    else
    {
      mesh::Surface surface;
      mesh::read_gmsh(surface, file, 0, constants);
      vertices = surface.get_vertices();
      for (const auto &cell : surface.active_cell_iterators())
      {
        if (cell->n_vertices() != 3)
          throw std::runtime_error("mesh file '" + file +
                                   "' has a cell that is not a triangle");
        triangles.push_back({cell->vertex_index(0), cell->vertex_index(1),
                             cell->vertex_index(2)});
      }
    }
    if (triangles.empty())
      throw std::runtime_error("mesh file '" + file + "' has no triangles");
  }

  namespace
  {
    std::string obstacle_section(unsigned int number)
    {
      return "Obstacle " + std::to_string(number);
    }

    /// Lumped areas; throws naming the first degenerate triangle.
    std::vector<double> vertex_areas(const Obstacle &obstacle)
    {
      std::vector<double> area(obstacle.vertices.size(), 0);
      double              largest = 0;
      for (const auto &t : obstacle.triangles)
        for (const unsigned v : t)
          largest = std::max(
              largest, obstacle.vertices[v].distance(obstacle.vertices[t[0]]));
      for (unsigned int k = 0; k < obstacle.triangles.size(); ++k)
      {
        const auto  &t = obstacle.triangles[k];
        const auto  &x = obstacle.vertices;
        const double a =
            0.5 * cross_product_3d(x[t[1]] - x[t[0]], x[t[2]] - x[t[0]]).norm();
        if (!(a > 1e-12 * largest * largest))
        {
          std::ostringstream message;
          message << "triangle " << k << " (vertices " << x[t[0]] << "; "
                  << x[t[1]] << "; " << x[t[2]] << ") is degenerate";
          throw std::runtime_error(message.str());
        }
        for (const unsigned v : t)
          area[v] += a / 3;
      }
      return area;
    }

    /// Throws unless 'file' is a plain NAME.csv (letters, digits, '_', '-'
    /// and '.', not starting with '.') that the run does not write itself:
    /// it is written beside the run's own files, and a clash found only
    /// when the run renames its files would lose one of them.
    void check_force_file_name(const std::string &file,
                               const std::string &where)
    {
      const std::string quoted = where + "/Force file: '" + file + "'";
      const bool        plain =
          std::all_of(file.begin(), file.end(),
                      [](char c)
                      {
                        return std::isalnum(static_cast<unsigned char>(c)) ||
                               c == '_' || c == '-' || c == '.';
                      });
      const auto ends_with = [&file](const std::string &end)
      {
        return file.size() > end.size() &&
               file.compare(file.size() - end.size(), end.size(), end) == 0;
      };
      if (!plain || file[0] == '.' || !ends_with(".csv"))
        throw std::invalid_argument(
            quoted + " is not a plain file name NAME.csv (letters, digits, "
                     "'_', '-', '.'; no path): it is written to the output "
                     "directory");
      const auto &taken = base::run_csv_files();
      if (std::find(taken.begin(), taken.end(), file) != taken.end() ||
          ends_with(".vertices.csv"))
        throw std::invalid_argument(quoted + " is a file the run writes "
                                             "itself; choose another name");
    }

    /// Force file and Force direction.
    void parse_force_file(ParameterHandler  &prm,
                          const std::string &where,
                          Obstacle          &obstacle)
    {
      obstacle.force_file         = Utilities::trim(prm.get("Force file"));
      const std::string direction = Utilities::trim(prm.get("Force direction"));
      if (obstacle.force_file.empty())
      {
        if (!direction.empty())
          throw std::invalid_argument(where + "/Force direction: given "
                                              "without a Force file");
        return;
      }
      check_force_file_name(obstacle.force_file, where);
      if (direction.empty())
        throw std::invalid_argument(where + "/Force direction: required with "
                                            "a Force file ('a, b, c')");
      obstacle.force_direction =
          model::parse_three_values(direction, where + "/Force direction");
      if (obstacle.force_direction.norm() == 0)
        throw std::invalid_argument(where +
                                    "/Force direction: must not be zero");
      obstacle.force_direction /= obstacle.force_direction.norm();
    }

    /// A number, or an expression of t (s) whose value at t = 0 is the
    /// constant friction_coefficient.
    void parse_friction(ParameterHandler  &prm,
                        const std::string &where,
                        Obstacle          &obstacle)
    {
      const std::string text = Utilities::trim(prm.get("Friction coefficient"));
      try
      {
        obstacle.friction_coefficient = Utilities::string_to_double(text);
      }
      catch (...)
      {
        obstacle.friction_of_time = base::parse_expressions<1>(
            text, 1, "x,t", true, "t", where + "/Friction coefficient");
        obstacle.friction_coefficient = obstacle.friction_at(0);
      }
      if (!(obstacle.friction_coefficient >= 0))
        throw std::runtime_error("Friction coefficient: " + text +
                                 " is negative; it must be >= 0");
    }

    Obstacle parse_obstacle(ParameterHandler  &prm,
                            const std::string &file,
                            const std::string &where)
    {
      Obstacle obstacle;
      obstacle.name = Utilities::trim(prm.get("Name"));
      read_triangle_surface(file, obstacle.vertices, obstacle.triangles,
                            mesh::parse_gmsh_constants(
                                prm.get("Gmsh parameters"), "Gmsh parameters"));
      obstacle.vertex_area = vertex_areas(obstacle);
      obstacle.motion.parse_entries(prm, where);
      const std::string direction = Utilities::trim(prm.get("Input direction"));
      if (!direction.empty())
      {
        obstacle.input_direction =
            model::parse_three_values(direction, where + "/Input direction");
        if (obstacle.input_direction.norm() == 0)
          throw std::invalid_argument(where +
                                      "/Input direction: must not be zero");
      }
      parse_force_file(prm, where, obstacle);
      parse_friction(prm, where, obstacle);
      obstacle.offset = prm.get_double("Offset");
      if (!(obstacle.offset >= 0))
        throw std::runtime_error("Offset: " + prm.get("Offset") +
                                 " is negative; it must be >= 0");
      return obstacle;
    }
  } // namespace

  void ObstacleParameters::declare_parameters(ParameterHandler &prm)
  {
    for (unsigned int k = 1; k <= max_obstacles; ++k)
    {
      prm.enter_subsection(obstacle_section(k));
      prm.declare_entry("Mesh file", "", Patterns::Anything(),
                        "The obstacle's surface: a gmsh .msh or .geo file "
                        "(every physical surface) or an STL file, "
                        "coordinates in length units; relative paths are "
                        "looked up beside the prm file. Empty: no obstacle.");
      prm.declare_entry("Gmsh parameters", "", Patterns::Anything(),
                        "Constants set when a .geo Mesh file is meshed, as "
                        "'name = value' entries separated by ',' (see "
                        "Mesh/Gmsh parameters). Unit: each constant's own, "
                        "as the Mesh file documents it.");
      prm.declare_entry("Name", "obstacle " + std::to_string(k),
                        Patterns::Anything(),
                        "Name in messages and in contact_forces.csv.");
      model::RigidMotion::declare_entries(prm);
      prm.declare_entry(
          "Input direction", "", Patterns::Anything(),
          "'a, b, c' (numbers or expressions of the "
          "Constants): with --interactive, a protocol line "
          "'t s' moves this obstacle by s times this vector (s in length "
          "units) at time t (s), linearly from the present, on top of its "
          "Translation and Rotation: a haptic device drives it. Empty: the "
          "obstacle takes no input. Unit: dimensionless (the protocol's s "
          "carries the length).");
      prm.declare_entry(
          "Force file", "", Patterns::Anything(),
          "A CSV file written to the output directory, one row per step "
          "with a contact_forces.csv row: 'time' (s), "
          "'<Name>_displacement' (length units: how far the obstacle's "
          "centroid has moved along Force direction since t = 0) and "
          "'force_n' (force units, N in mm-N-s-tonne scenes: the contact "
          "and friction force the obstacle exerts on the shell along Force "
          "direction; positive where it pushes). Characters of the Name "
          "other than letters and digits become '_'. A plain NAME.csv, "
          "not one of the run's own files. A restart appends to the "
          "earlier run's file: keep its Force direction. Empty: none.");
      prm.declare_entry("Force direction", "", Patterns::Anything(),
                        "'a, b, c' (normalized; each a "
                        "number or an expression of the Constants): the "
                        "direction Force file measures along; required "
                        "with it, refused without it. Unit: dimensionless.");
      prm.declare_entry("Friction coefficient", "0", Patterns::Anything(),
                        "Coulomb friction coefficient mu against the shell "
                        "(>= 0): a number, or an expression "
                        "of t (s) and the Constants, e.g. '0.5 * (t < 1.3)' "
                        "for forceps that let go at 1.3 s (taken at each "
                        "step's end time). Unit: dimensionless.");
      prm.declare_entry("Offset", "0", Patterns::Double(),
                        "Distance kept between the obstacle and the shell's "
                        "surface, added to half the shell thickness (>= 0). "
                        "Unit: length (mm in the IOL scenes).");
      prm.leave_subsection();
    }
  }

  std::vector<Obstacle>
  ObstacleParameters::parse_parameters(ParameterHandler  &prm,
                                       const std::string &prm_directory)
  {
    std::vector<Obstacle>              obstacles;
    std::map<std::string, std::string> force_file_owners;
    for (unsigned int k = 1; k <= max_obstacles; ++k)
    {
      prm.enter_subsection(obstacle_section(k));
      const std::string where = "Contact/" + obstacle_section(k);
      const std::string file  = mesh::resolve_path(
           Utilities::trim(prm.get("Mesh file")), prm_directory);
      const std::string name = Utilities::trim(prm.get("Name"));
      try
      {
        if (!file.empty())
          obstacles.push_back(parse_obstacle(prm, file, where));
      }
      catch (const std::exception &error)
      {
        prm.leave_subsection();
        const std::string message = error.what();
        // Motion errors already start with the subsection.
        throw std::runtime_error(message.rfind(where, 0) == 0
                                     ? message
                                     : where + " ('" + name + "'): " + message);
      }
      prm.leave_subsection();
      // Two obstacles writing one file would interleave their rows.
      if (!file.empty() && !obstacles.back().force_file.empty())
      {
        const auto [owner, added] =
            force_file_owners.emplace(obstacles.back().force_file, where);
        if (!added)
          throw std::invalid_argument(where + "/Force file: '" + owner->first +
                                      "' is " + owner->second +
                                      "'s Force file too");
      }
    }
    return obstacles;
  }
} // namespace coshell::contact
