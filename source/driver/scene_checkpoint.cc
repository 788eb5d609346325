// Checkpoint and restart of staged runs: Output/Checkpoint interval,
// SIGINT/SIGTERM, and `coshell scene.prm --restart FILE`.

#include <coshell/base/csv_file.h>
#include <coshell/base/parallel_environment.h>
#include <coshell/driver/interruption.h>
#include <coshell/driver/scene.h>
#include <coshell/io/checkpoint.h>

#include <coshell/driver/staged_output.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <iomanip>
#include <optional>
#include <sstream>
#include <type_traits>

namespace coshell::driver
{
  namespace
  {
    /// The CSV files a staged run writes, in the order of csv_rows, before
    /// the obstacles' Force files.
    const std::vector<std::string> csv_files = {
        "load_displacement.csv", "newton_history.csv", "time_history.csv",
        "contact_forces.csv"};

    /// The run's CSV files in the order of staged_csv_files(), null where
    /// the run does not write one; const or not as 'out' is.
    template<typename Output>
    auto csv_outputs(Output &out)
    {
      using File                = std::conditional_t<std::is_const_v<Output>,
                                      const base::CsvFile, base::CsvFile>;
      std::vector<File *> files = {
          &out.curve, &out.history,
          out.time_history ? &*out.time_history : nullptr,
          out.contact_forces ? &*out.contact_forces : nullptr};
      for (auto &[o, file] : out.obstacle_force_files)
        files.push_back(&file);
      return files;
    }

    /// The rows the earlier run had written to file k of
    /// staged_csv_files() at the checkpoint; none known for a Force file
    /// when that run wrote none. Every Force file gets one row per step,
    /// as contact_forces.csv does, so any of the earlier run's gives their
    /// count, and a Force file added or moved between the runs is found
    /// by its name.
    std::optional<unsigned int> earlier_rows(const io::Checkpoint &checkpoint,
                                             unsigned int          k)
    {
      const unsigned int index = std::min<unsigned int>(k, csv_files.size());
      if (index < checkpoint.csv_rows.size())
        return checkpoint.csv_rows[index];
      return std::nullopt;
    }

    std::string checkpoint_name(unsigned int step)
    {
      std::ostringstream name;
      name << "checkpoint-" << std::setw(6) << std::setfill('0') << step
           << ".h5";
      return name.str();
    }

    std::string earlier_directory(const std::string &restart_file)
    {
      const auto parent = std::filesystem::path(restart_file).parent_path();
      return parent.empty() ? "." : parent.string();
    }
  } // namespace

  void Scene::restart_from(const std::string &file)
  {
    // The ranks read in turn, as when deal.II's reader took the file's
    // write lock; reading is now shared, and the file small.
    io::Checkpoint checkpoint;
    base::one_rank_at_a_time([&] { checkpoint = io::read_checkpoint(file); });
    const std::string where = "restart file '" + file + "': ";
    const auto       &list  = stages_.list();
    if (checkpoint.stage < 1 || checkpoint.stage > list.size() ||
        list[checkpoint.stage - 1].analysis != AnalysisType::dynamic)
      throw std::invalid_argument(where + "it was written in stage " +
                                  std::to_string(checkpoint.stage) +
                                  ", which is not a dynamic stage "
                                  "of this scene (another scene file?)");
    if (mesh_.refinement_levels.size() > 1)
      throw std::invalid_argument(where + "a refinement study cannot restart");
    if (checkpoint.body_frame_translations != time_integration_.se3())
      throw std::invalid_argument(
          where + "it was written with another Time integration/Lie group");
    restart_      = std::move(checkpoint);
    restart_file_ = file;
  }

  bool Scene::skipped_by_restart(unsigned int stage_number) const
  {
    return restart_ && stage_number < restart_->stage;
  }

  std::vector<std::string> Scene::staged_csv_files() const
  {
    std::vector<std::string> files = csv_files;
    if (contact_.enabled())
      for (const auto &obstacle : contact_.obstacles)
        if (!obstacle.force_file.empty())
          files.push_back(obstacle.force_file);
    return files;
  }

  std::vector<std::string> Scene::read_earlier_outputs() const
  {
    const auto               files = staged_csv_files();
    std::vector<std::string> texts(files.size());
    if (!restart_)
      return texts;
    const std::string directory = earlier_directory(restart_file_);
    for (unsigned int k = 0; k < files.size(); ++k)
      if (const auto rows = earlier_rows(*restart_, k))
        texts[k] = base::read_earlier_rows(directory + "/" + files[k], *rows);
    return texts;
  }

  void Scene::restore_checkpoint(model::ShellState              &state,
                                 StagedOutput                   &out,
                                 const std::vector<std::string> &earlier,
                                 const std::string              &directory,
                                 std::ostream                   &log)
  {
    const io::Checkpoint    &c     = *restart_;
    const model::ShellModel &model = state.model();
    try
    {
      state.load(model.from_vertex_order(c.values), c.rotations,
                 model.from_vertex_order(c.velocity),
                 model.from_vertex_order(c.acceleration));
    }
    catch (const std::invalid_argument &error)
    {
      throw std::invalid_argument("restart file '" + restart_file_ +
                                  "': " + error.what());
    }
    out.step              = c.step;
    out.last_written      = c.last_written;
    out.external_work     = c.external_work;
    out.dissipated_energy = c.dissipated_energy;
    carry_ = {model.from_vertex_order(c.pseudo_acceleration), c.step_size};
    if (out.contact)
      restore_contact(c, state, out);
    const auto files   = csv_outputs(out);
    bool       carried = true;
    for (unsigned int k = 0; k < earlier.size() && k < files.size(); ++k)
      if (files[k] && !earlier[k].empty())
        carried = files[k]->resume(earlier[k]) && carried;
      else if (files[k] && earlier_rows(c, k).value_or(1) > 0)
        carried = false;
    const std::string pvd = earlier_directory(restart_file_) + "/solution.pvd";
    if (c.pvd_entries > 0 &&
        !output_.resume_series(directory, pvd, c.pvd_entries))
      carried = false;
    log << "restarting from " << restart_file_ << ": stage " << c.stage
        << ", t = " << c.time << " s, step " << c.step << '\n';
    if (!carried)
      log << "  note: the earlier run's CSV files or solution.pvd are not "
             "next to the checkpoint (or are shorter); the histories start "
             "at the restart\n";
    // The next multiple of the interval, as in the run that wrote it.
    next_checkpoint_time_ =
        checkpoint_interval_ *
        (std::floor(c.time / std::max(checkpoint_interval_, 1e-300) + 1e-9) +
         1);
  }

  void Scene::checkpoint_step(const model::ShellProblem &problem,
                              const StagedOutput        &out,
                              const Stage               &stage,
                              double                     time,
                              const std::string         &directory,
                              std::ostream              &log)
  {
    const int  signal = interrupt_signal();
    const bool due =
        checkpoint_interval_ > 0 &&
        time >= next_checkpoint_time_ - 1e-9 * checkpoint_interval_;
    if (!due && signal == 0)
      return;
    // An obstacle driven by --interactive input is where the input put it,
    // which a checkpoint does not hold: a restart would move it back.
    if (interactive_ && interactive_->drives_obstacles())
      throw Interrupted("stopped by signal " + std::to_string(signal) +
                        " at t = " + std::to_string(time) +
                        " s; no checkpoint written: it would not hold the "
                        "obstacles' interactive input");
    // Vectors go by mesh vertex: the DoF numbering depends on the ranks.
    const model::ShellModel &model = problem.model();
    io::Checkpoint           c;
    c.prm_file              = prm_file_;
    c.stage                 = stage.number;
    c.step                  = out.step;
    c.last_written          = out.last_written;
    c.time                  = time;
    c.step_size             = carry_.step_size;
    c.pseudo_acceleration   = model.to_vertex_order(carry_.pseudo_acceleration);
    c.converged_force_scale = problem.converged_force_scale();
    c.values                = model.to_vertex_order(problem.state().values());
    c.rotations             = problem.state().rotations();
    c.velocity              = model.to_vertex_order(problem.state().velocity());
    c.acceleration = model.to_vertex_order(problem.state().acceleration());
    c.body_frame_translations = problem.state().body_frame_translations();
    c.external_work           = out.external_work;
    c.dissipated_energy       = out.dissipated_energy;
    c.generalized_force       = model.to_vertex_order(out.generalized_force);
    c.damping_force           = model.to_vertex_order(out.damping_force);
    for (const base::CsvFile *file : csv_outputs(out))
      c.csv_rows.push_back(file ? file->rows() : 0u);
    if (out.contact)
    {
      c.arrays                   = out.contact->checkpoint_arrays();
      c.arrays["output_contact"] = {out.contact_work, out.smallest_gap,
                                    out.largest_penetration};
      const auto force           = model.to_vertex_order(out.contact_force);
      c.arrays["output_contact_force"].assign(force.begin(), force.end());
    }
    c.pvd_entries          = output_.series_size(directory);
    const std::string file = directory + "/" + checkpoint_name(out.step);
    io::write_checkpoint(c, file);
    while (checkpoint_interval_ > 0 &&
           next_checkpoint_time_ <= time + 1e-9 * checkpoint_interval_)
      next_checkpoint_time_ += checkpoint_interval_;
    if (signal == 0)
      return;
    log << "checkpoint written to " << file << '\n';
    throw Interrupted("stopped by signal " + std::to_string(signal) +
                      " at t = " + std::to_string(time) +
                      " s; checkpoint written to " + file +
                      "; resume with --restart " + file);
  }

  void Scene::restore_contact(const io::Checkpoint    &c,
                              const model::ShellState &state,
                              StagedOutput            &out) const
  {
    try
    {
      out.contact->restore_checkpoint_arrays(c.arrays, state, c.time);
      const auto &totals = c.arrays.at("output_contact");
      const auto &force  = c.arrays.at("output_contact_force");
      if (totals.size() != 3)
        throw std::out_of_range("");
      out.contact_work        = totals[0];
      out.smallest_gap        = totals[1];
      out.largest_penetration = totals[2];
      out.contact_force       = state.model().from_vertex_order(
                dealii::Vector<double>(force.begin(), force.end()));
    }
    catch (const std::invalid_argument &error)
    {
      throw std::invalid_argument("restart file '" + restart_file_ +
                                  "': " + error.what());
    }
    catch (const std::out_of_range &)
    {
      throw std::invalid_argument("restart file '" + restart_file_ +
                                  "': it has no contact state (written by a "
                                  "scene without contact?)");
    }
  }

  void Scene::stop_if_interrupted_in_static_stage()
  {
    if (const int signal = interrupt_signal())
      throw Interrupted("stopped by signal " + std::to_string(signal) +
                        " in a static stage; no checkpoint (static stages "
                        "are not checkpointed: a restart resumes dynamic "
                        "stages)");
  }
} // namespace coshell::driver
