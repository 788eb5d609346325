#pragma once

#include <coshell/model/shell_model.h>

#include <deal.II/base/parameter_handler.h>

#include <map>
#include <string>
#include <vector>

namespace coshell::model
{
  /// Named scalar results ("quantities of interest") and their references,
  /// from prm subsection "Quantities of interest".
  class QuantitiesOfInterest
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm);
    void        parse_parameters(dealii::ParameterHandler &prm);

    /// Values of every named quantity for a solution, and the thickness
    /// extremes with Element/Thickness stretch.
    std::map<std::string, double>
    evaluate(const ShellModel             &model,
             const dealii::Vector<double> &solution) const;

    /// Reference values given in the prm, by name.
    const std::map<std::string, double> &references() const;

    /// Reference load-displacement points (load factor, value) by name.
    using Curve = std::vector<std::pair<double, double>>;
    const std::map<std::string, Curve> &reference_curves() const;
    /// Every load factor at which some reference curve has a point.
    std::vector<double> reference_load_factors() const;
    /// Whether dynamic runs also report the largest strains per step.
    bool largest_strains() const
    {
      return largest_strains_;
    }

  private:
    struct PointValue
    {
      std::string      name;
      dealii::Point<3> where;
      Component        component;
    };
    struct MaximumValue
    {
      std::string name;
      Component   component;
    };
    /// Where a region (material id) of the shell sits against an axis: a
    /// lens's optic in its capsular bag.
    struct RegionPose
    {
      std::string          name;
      unsigned int         region;
      dealii::Point<3>     centre;
      dealii::Tensor<1, 3> axis; // unit
    };
    std::vector<PointValue>       point_values_;
    std::vector<MaximumValue>     maximum_values_;
    std::vector<RegionPose>       region_poses_;
    std::map<std::string, double> references_;
    std::map<std::string, Curve>  reference_curves_;
    bool                          largest_strains_ = false;

    void check_defined(const std::string &name,
                       const std::string &parameter) const;
    void parse_region_poses(const std::string &text);
    /// name_decentration, name_tilt, name_axial and name_shape_deviation
    /// of 'pose' into 'values'.
    static void add_region_pose(const RegionPose              &pose,
                                const ShellModel              &model,
                                const dealii::Vector<double>  &solution,
                                std::map<std::string, double> &values);
    /// With Element/Thickness stretch: min_thickness_stretch and
    /// max_thickness_stretch (h / h0 at the vertices, dimensionless) and
    /// min_thickness (the thinnest cell, mm).
    static void add_thickness_extremes(const ShellModel              &model,
                                       const dealii::Vector<double>  &solution,
                                       std::map<std::string, double> &values);
  };
} // namespace coshell::model
