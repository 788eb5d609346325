#include <algorithm>
#include <coshell/base/csv_file.h>
#include <coshell/io/results.h>

#include <cmath>
#include <iomanip>
#include <sstream>

namespace coshell::io
{
  std::map<std::string, double> LevelResult::relative_errors() const
  {
    std::map<std::string, double> errors;
    for (const auto &[name, value] : reference)
      if (qoi.count(name))
        errors[name] = std::abs(qoi.at(name) - value) / std::abs(value);
    return errors;
  }

  namespace
  {
    /// A phase's wall time and its split, in seconds; the factorization
    /// is a part of the linear solver, the rest of it substitution.
    void write_split(Json  &split,
                     double total,
                     double assembly,
                     double linear_solver,
                     double factorization)
    {
      split["total"]         = total;
      split["assembly"]      = assembly;
      split["linear_solver"] = linear_solver;
      split["factorization"] = factorization;
      split["other"]         = total - assembly - linear_solver;
    }
  } // namespace

  namespace
  {
    /// Each dynamic stage's number, simulated and wall time (s) and their
    /// ratio: the real-time factor of one stage alone.
    Json::Array stage_times_json(const std::vector<DynamicStageTime> &stages)
    {
      Json::Array array;
      for (const auto &stage : stages)
      {
        Json entry;
        entry["stage"]            = stage.stage;
        entry["simulated_time_s"] = stage.simulated_time_s;
        entry["wall_time_s"]      = stage.wall_time_s;
        entry["real_time_factor"] =
            stage.simulated_time_s / std::max(stage.wall_time_s, 1e-12);
        array.push_back(entry);
      }
      return array;
    }
  } // namespace

  Json LevelResult::to_json() const
  {
    Json json;
    json["refinement_level"]         = level;
    json["h"]                        = h;
    json["n_cells"]                  = n_cells;
    json["n_vertices"]               = n_vertices;
    json["n_dofs"]                   = n_dofs;
    json["n_inactive_dofs"]          = n_inactive_dofs;
    json["linear_solver_iterations"] = linear_solver_iterations;
    if (mass > 0)
      json["mass"] = mass;
    if (cholmod_fallbacks > 0)
      json["cholmod_fallbacks"] = cholmod_fallbacks;
    if (reused_factor_solves > 0)
    {
      json["factorizations"]       = factorizations;
      json["reused_factor_solves"] = reused_factor_solves;
    }
    Json &times       = json["wall_time_s"];
    times["setup"]    = wall_time_s.setup;
    times["assemble"] = wall_time_s.assemble;
    times["solve"]    = wall_time_s.solve;
    times["output"]   = wall_time_s.output;
    times["total"]    = wall_time_s.total;
    if (load_steps > 0 || steps > 0)
    {
      json["newton_iterations"]  = newton_iterations;
      json["newton_corrections"] = newton_corrections;
    }
    if (load_steps > 0)
    {
      json["load_steps"] = load_steps;
      write_split(json["load_stepping_s"], static_wall_time_s,
                  static_assembly_s, static_linear_solver_s,
                  static_factorization_s);
    }
    if (steps > 0)
    {
      json["steps"]            = steps;
      json["simulated_time_s"] = simulated_time_s;
      if (!std::isnan(initial_total_energy))
        json["initial_total_energy"] = initial_total_energy;
      if (energy_guard_rejections)
        json["energy_guard_rejections"] = *energy_guard_rejections;
      write_split(json["time_stepping_s"], dynamic_wall_time_s,
                  dynamic_assembly_s, dynamic_linear_solver_s,
                  dynamic_factorization_s);
      // Simulated time over the wall time of the time stepping.
      json["real_time_factor"] =
          simulated_time_s / std::max(dynamic_wall_time_s, 1e-12);
      json["dynamic_stages"] = stage_times_json(dynamic_stages);
    }
    if (!contact.empty())
      json["contact"] = Json::Object(contact.begin(), contact.end());
    Json::Object qoi_json(qoi.begin(), qoi.end());
    json["qoi"] = qoi_json;
    if (!reference.empty())
    {
      json["reference"]      = Json::Object(reference.begin(), reference.end());
      const auto errors      = relative_errors();
      json["relative_error"] = Json::Object(errors.begin(), errors.end());
    }
    return json;
  }

  namespace
  {
    std::string primary_quantity(const LevelResult &level)
    {
      for (const auto &[name, value] : level.reference)
        if (level.qoi.count(name))
          return name;
      return level.qoi.empty() ? "" : level.qoi.begin()->first;
    }

    std::string optional_number(const std::map<std::string, double> &map,
                                const std::string                   &key)
    {
      if (!map.count(key))
        return "";
      std::ostringstream out;
      out << std::setprecision(base::csv_digits) << map.at(key);
      return out.str();
    }
  } // namespace

  std::string convergence_csv(const std::vector<LevelResult> &levels)
  {
    std::ostringstream csv;
    if (levels.empty())
      return "";
    const std::string primary = primary_quantity(levels.front());
    csv << "level,h,n_cells,n_dofs," << (primary.empty() ? "qoi" : primary)
        << ",relative_error,rate,wall_time_s";
    for (const auto &[name, value] : levels.front().qoi)
      if (name != primary)
        csv << ',' << name << ',' << name << "_relative_error";
    csv << '\n' << std::setprecision(base::csv_digits);
    for (unsigned int k = 0; k < levels.size(); ++k)
    {
      const auto &l      = levels[k];
      const auto  errors = l.relative_errors();
      std::string rate;
      if (k > 0 && errors.count(primary) &&
          levels[k - 1].relative_errors().count(primary))
      {
        const double previous = levels[k - 1].relative_errors().at(primary);
        std::ostringstream r;
        r << std::log(previous / errors.at(primary)) /
                 std::log(levels[k - 1].h / l.h);
        rate = r.str();
      }
      csv << l.level << ',' << l.h << ',' << l.n_cells << ',' << l.n_dofs << ','
          << optional_number(l.qoi, primary) << ','
          << optional_number(errors, primary) << ',' << rate << ','
          << l.wall_time_s.total;
      for (const auto &[name, value] : l.qoi)
        if (name != primary)
          csv << ',' << value << ',' << optional_number(errors, name);
      csv << '\n';
    }
    return csv.str();
  }
} // namespace coshell::io
