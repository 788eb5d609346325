#pragma once

#include <coshell/mesh/mesh.h>
#include <coshell/model/rigid_motion.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace coshell::contact
{
  /// A scalar of time given by another program during an --interactive
  /// run (a haptic device's plunger travel): linear between the samples
  /// (t, s) received, held after the last one, 0 before any.
  class InputPath
  {
  public:
    /// s reached at 'time', linearly from where the path is at 'now'
    /// (the present of the run, after every sample so far). Earlier
    /// times keep their values: the integrated past does not move.
    void   append(double now, double time, double value);
    double value(double time) const;

  private:
    std::vector<std::pair<double, double>> samples_;
  };

  /// A rigid obstacle: a triangle surface mesh in its reference position,
  /// moved by a rigid motion of time, with a friction coefficient and an
  /// offset added to the shell's half thickness.
  struct Obstacle
  {
    std::string                          name;
    std::vector<dealii::Point<3>>        vertices; ///< reference positions
    std::vector<std::array<unsigned, 3>> triangles;
    model::RigidMotion                   motion;
    double                               friction_coefficient = 0;
    /// Friction coefficient as an expression of t (null: the constant
    /// friction_coefficient, its value at t = 0 otherwise): a tool that
    /// grips and then lets go.
    std::shared_ptr<dealii::FunctionParser<1>> friction_of_time;
    double                                     offset = 0; ///< length
    /// Area of the triangles around each vertex, a third of each (length^2).
    std::vector<double> vertex_area;
    /// Contact/Obstacle k/Input direction: on top of 'motion' the obstacle
    /// moves by input->value(t) times this vector (zero: not driven).
    dealii::Tensor<1, 3>             input_direction;
    std::shared_ptr<const InputPath> input;
    /// Contact/Obstacle k/Force file and Force direction (unit vector):
    /// the CSV of the obstacle's travel and push along that direction
    /// written to the output directory ("" for none).
    std::string          force_file;
    dealii::Tensor<1, 3> force_direction;

    /// mu at time t; throws std::runtime_error naming the obstacle where
    /// it is negative.
    double friction_at(double time) const;
    /// Vertex positions at time t.
    std::vector<dealii::Point<3>> positions(double time) const;
  };

  /// prm subsections "Contact/Obstacle 1" ... "Obstacle 12" (the tuck
  /// takes 8 tools, the probes of its hand-off up to 12:
  /// doc/validation.md).
  struct ObstacleParameters
  {
    static constexpr unsigned int max_obstacles = 12;

    static void declare_parameters(dealii::ParameterHandler &prm);
    /// Reads the meshes too. Throws std::runtime_error naming the obstacle
    /// (its subsection and name) and the file or entry at fault: a missing,
    /// unreadable or empty mesh, a degenerate triangle, a negative friction
    /// coefficient or offset, an unparsable motion.
    static std::vector<Obstacle>
    parse_parameters(dealii::ParameterHandler &prm,
                     const std::string        &prm_directory);
  };

  /// Reads a triangle surface: a gmsh .msh or .geo (every physical
  /// surface) or an STL file (ASCII or binary; coincident vertices are
  /// merged). Throws std::runtime_error naming the file.
  void read_triangle_surface(const std::string                    &file,
                             std::vector<dealii::Point<3>>        &vertices,
                             std::vector<std::array<unsigned, 3>> &triangles,
                             const mesh::GmshConstants &constants = {});
} // namespace coshell::contact
