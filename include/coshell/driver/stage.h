#pragma once

#include <deal.II/base/parameter_handler.h>

#include <functional>
#include <string>
#include <vector>

namespace coshell::driver
{
  /// The analyses a scene or a stage runs (prm: Analysis/Type, Stage
  /// k/Analysis type).
  enum class AnalysisType
  {
    linear_static,
    nonlinear_static,
    dynamic,
    modes
  };

  /// The AnalysisType of its prm name ("linear static", "nonlinear
  /// static", "dynamic", "modes"); throws std::invalid_argument otherwise.
  AnalysisType analysis_type(const std::string &name);
  /// The prm name of an AnalysisType.
  std::string analysis_name(AnalysisType type);

  /// One stage of a scene: an analysis over a time interval with its own
  /// loads, prescribed motions and released supports. The configuration
  /// carries over from one stage to the next.
  struct Stage
  {
    unsigned int number = 1;
    /// nonlinear static or dynamic.
    AnalysisType analysis = AnalysisType::nonlinear_static;
    /// Length of the stage, s (pseudo-time in statics).
    double duration = 1;
    /// Load factor as a function of (time t, stage fraction s).
    std::function<double(double, double)> load_factor;
    /// Numbers of the prescribed motions active in this stage.
    std::vector<unsigned int> motions;
    /// Boundary ids whose support conditions this stage releases.
    std::vector<unsigned int> released;

    std::string name() const;
  };

  /// prm subsections "Stage 1" ... "Stage 8". A scene that defines no stage
  /// runs one stage of Analysis/Type with every defined motion.
  class Stages
  {
  public:
    static constexpr unsigned int max_stages = 8;

    static void declare_parameters(dealii::ParameterHandler &prm);
    /// 'defined_motions' lists the motions of "Prescribed motions";
    /// 'single_stage' is used when no stage is defined. Throws naming the
    /// stage and entry.
    void parse_parameters(dealii::ParameterHandler        &prm,
                          const std::vector<unsigned int> &defined_motions,
                          const Stage                     &single_stage);

    const std::vector<Stage> &list() const;
    /// True when the scene defined its stages (rather than one implicit).
    bool staged() const;

    /// The default load factor of an analysis: a ramp s in statics, 1 in
    /// dynamics.
    static std::function<double(double, double)>
    default_load_factor(AnalysisType analysis);

  private:
    std::vector<Stage> stages_;
    bool               staged_ = false;
  };
} // namespace coshell::driver
