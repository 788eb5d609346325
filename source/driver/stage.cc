#include <coshell/base/expressions.h>
#include <coshell/driver/stage.h>

#include <deal.II/base/function_parser.h>
#include <deal.II/base/utilities.h>

#include <algorithm>
#include <memory>
#include <stdexcept>

namespace coshell::driver
{
  using namespace dealii;

  namespace
  {
    std::string stage_section(unsigned int number)
    {
      return "Stage " + std::to_string(number);
    }

    std::vector<unsigned int> parse_numbers(const std::string &text,
                                            const std::string &where)
    {
      std::vector<unsigned int> numbers;
      for (const auto &entry : Utilities::split_string_list(text, ','))
      {
        try
        {
          const int n = Utilities::string_to_int(entry);
          if (n < 0)
            throw std::invalid_argument("");
          numbers.push_back(n);
        }
        catch (...)
        {
          throw std::invalid_argument(where + ": '" + entry +
                                      "' is not a non-negative integer");
        }
      }
      return numbers;
    }

    /// lambda(t, s) from a muparser expression, checked by one evaluation.
    std::function<double(double, double)>
    parse_load_factor(const std::string &expression, const std::string &where)
    {
      std::shared_ptr<FunctionParser<2>> function = base::parse_expressions<2>(
          expression, 1, "t,s", false, "t and s", where);
      return [function](double t, double s)
      { return function->value(Point<2>(t, s)); };
    }

    std::vector<unsigned int>
    active_motions(const std::string               &text,
                   const std::vector<unsigned int> &defined,
                   const std::string               &where)
    {
      const std::string trimmed = Utilities::trim(text);
      if (trimmed == "all")
        return defined;
      if (trimmed == "none" || trimmed.empty())
        return {};
      const auto numbers = parse_numbers(trimmed, where);
      for (const unsigned int n : numbers)
        if (std::find(defined.begin(), defined.end(), n) == defined.end())
          throw std::invalid_argument(where + ": motion " + std::to_string(n) +
                                      " is not defined (subsection "
                                      "Prescribed motions/Motion " +
                                      std::to_string(n) + " has no Where)");
      return numbers;
    }
  } // namespace

  AnalysisType analysis_type(const std::string &name)
  {
    for (const AnalysisType type :
         {AnalysisType::linear_static, AnalysisType::nonlinear_static,
          AnalysisType::dynamic, AnalysisType::modes})
      if (analysis_name(type) == name)
        return type;
    throw std::invalid_argument("unknown analysis type '" + name + "'");
  }

  std::string analysis_name(AnalysisType type)
  {
    switch (type)
    {
    case AnalysisType::linear_static:
      return "linear static";
    case AnalysisType::nonlinear_static:
      return "nonlinear static";
    case AnalysisType::dynamic:
      return "dynamic";
    case AnalysisType::modes:
      return "modes";
    }
    throw std::logic_error("analysis_name: no such AnalysisType");
  }

  std::string Stage::name() const
  {
    return stage_section(number) + " (" + analysis_name(analysis) + ")";
  }

  std::function<double(double, double)>
  Stages::default_load_factor(AnalysisType analysis)
  {
    if (analysis == AnalysisType::dynamic)
      return [](double, double) { return 1.0; };
    return [](double, double s) { return s; };
  }

  void Stages::declare_parameters(ParameterHandler &prm)
  {
    for (unsigned int k = 1; k <= max_stages; ++k)
    {
      prm.enter_subsection(stage_section(k));
      prm.declare_entry("Analysis type", "none",
                        Patterns::Selection("none|nonlinear static|dynamic"),
                        "none: no such stage. Stages run in order, the "
                        "configuration (and velocities) carried over; a "
                        "static stage after a dynamic one leaves the shell "
                        "at rest (its equilibrium has no velocities).");
      prm.declare_entry("Duration", "1", Patterns::Anything(),
                        "Length of the stage (in statics a pseudo-time "
                        "that drives the load factor and the motions); > 0. "
                        "A number or an expression of pi and the scene's "
                        "Constants (e.g. 'push_time - rod_out_time'), so "
                        "that a stage follows the design values it ends "
                        "with. Unit: time (s).");
      prm.declare_entry("Load factor", "", Patterns::Anything(),
                        "Dimensionless factor on every load of subsection "
                        "Loads, a muparser expression of the time t (s, "
                        "counted from the start of the scene) and the stage "
                        "fraction s in [0, 1]. Empty: s in statics (a "
                        "ramp), 1 in dynamics. Unit: dimensionless.");
      prm.declare_entry("Motions", "all", Patterns::Anything(),
                        "The prescribed motions active in this stage: all, "
                        "none, or their numbers ('1, 3'). The others' "
                        "vertices are free.");
      prm.declare_entry("Release", "", Patterns::Anything(),
                        "Boundary ids (comma separated) whose support "
                        "conditions (Boundary conditions/Conditions) this "
                        "stage releases.");
      prm.leave_subsection();
    }
  }

  void
  Stages::parse_parameters(ParameterHandler                &prm,
                           const std::vector<unsigned int> &defined_motions,
                           const Stage                     &single_stage)
  {
    stages_.clear();
    for (unsigned int k = 1; k <= max_stages; ++k)
    {
      prm.enter_subsection(stage_section(k));
      const std::string where = stage_section(k) + "/";
      try
      {
        Stage             stage;
        const std::string type = prm.get("Analysis type");
        const bool        used = type != "none";
        stage.number           = k;
        if (used)
          stage.analysis = analysis_type(type);
        stage.duration = base::evaluate_constant_expression(
            prm.get("Duration"), base::expression_constants(),
            where + "Duration");
        const std::string load_factor = Utilities::trim(prm.get("Load factor"));
        stage.load_factor =
            load_factor.empty()
                ? default_load_factor(stage.analysis)
                : parse_load_factor(load_factor, where + "Load factor");
        stage.motions  = active_motions(prm.get("Motions"), defined_motions,
                                        where + "Motions");
        stage.released = parse_numbers(prm.get("Release"), where + "Release");
        if (used && stage.duration <= 0)
          throw std::invalid_argument(where + "Duration must be positive");
        if (used)
          stages_.push_back(stage);
      }
      catch (...)
      {
        prm.leave_subsection();
        throw;
      }
      prm.leave_subsection();
    }
    staged_ = !stages_.empty();
    if (!staged_)
      stages_.push_back(single_stage);
  }

  const std::vector<Stage> &Stages::list() const
  {
    return stages_;
  }

  bool Stages::staged() const
  {
    return staged_;
  }
} // namespace coshell::driver
