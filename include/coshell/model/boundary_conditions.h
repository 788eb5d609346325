#pragma once

#include <coshell/model/shell_model.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/lac/affine_constraints.h>

#include <map>
#include <string>
#include <vector>

namespace coshell::model
{
  /// Kinematic condition on the vertices of one boundary set, expressed as
  /// directions along which translations / rotations are held at zero.
  struct BoundaryCondition
  {
    enum class Type
    {
      clamped,               ///< all translations and rotations fixed
      simply_supported_hard, ///< translations fixed, and the rotation
                             ///< about the in-plane edge normal
      simply_supported_soft, ///< translations fixed, rotations free
      symmetry,              ///< mirror plane with a given normal
      fixed_components,      ///< listed global components fixed
      free
    };
    Type                   type = Type::free;
    dealii::Tensor<1, 3>   plane_normal; ///< for symmetry
    std::vector<Component> components;   ///< for fixed
  };

  /// Parses "clamped", "simply supported hard", "simply supported soft",
  /// "symmetry x|y|z", "free" or "fixed ux uz ...".
  BoundaryCondition parse_boundary_condition(const std::string &text);

  /// prm subsection "Boundary conditions": a map boundary id -> condition,
  /// and conditions at single vertices nearest given points.
  class BoundaryConditions
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm);
    void        parse_parameters(dealii::ParameterHandler &prm);

    /// Homogeneous constraints for every listed boundary set. Directions
    /// from several sets meeting at a vertex are combined (a corner of two
    /// hard simply supported edges has both in-plane slopes fixed).
    void make_constraints(const ShellModel                  &model,
                          dealii::AffineConstraints<double> &constraints) const;

    const std::map<unsigned int, BoundaryCondition> &conditions() const;

    /// The same conditions with those of the listed boundary ids removed
    /// (a stage that releases supports); throws naming an id that has no
    /// condition.
    BoundaryConditions without(const std::vector<unsigned int> &ids) const;

  private:
    std::map<unsigned int, BoundaryCondition> conditions_;
    std::vector<std::pair<dealii::Point<3>, BoundaryCondition>>
        point_conditions_;
  };
} // namespace coshell::model
