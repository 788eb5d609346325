#pragma once

// The outputs a staged run writes as it goes and the energy bookkeeping
// they share, used by the scene's stage loop (scene.cc), its
// postprocessors (postprocessors.cc) and its checkpointing
// (scene_checkpoint.cc).

#include <coshell/base/csv_file.h>
#include <coshell/contact/contact.h>

#include <deal.II/lac/vector.h>

#include <limits>
#include <optional>
#include <utility>
#include <vector>

namespace coshell::driver
{
  using dealii::Vector;

  /// The files and running totals of one staged run.
  struct StagedOutput
  {
    StagedOutput(base::CsvFile &&curve, base::CsvFile &&history)
        : curve(std::move(curve)), history(std::move(history))
    {
    }

    base::CsvFile                curve, history;
    std::optional<base::CsvFile> time_history, contact_forces;
    /// Each Contact/Obstacle k/Force file: the obstacle's index in
    /// Contact::obstacles() (the subsections with a mesh, in order) and
    /// its file.
    std::vector<std::pair<unsigned int, base::CsvFile>> obstacle_force_files;
    /// The contact of the run (nullptr when Contact is off), and the
    /// extremes of its gap over every iterate of the run.
    contact::Contact *contact      = nullptr;
    double            smallest_gap = std::numeric_limits<double>::infinity();
    double            largest_penetration = 0;
    unsigned int      step = 0, last_written = 0;
    /// Energy bookkeeping of the dynamic stages: work of the loads and
    /// reactions, energy dissipated by damping and drag (trapezoidal in
    /// time), and the working and damping forces of the last step. Both
    /// works use the trapezoidal rule on the step increment, the rule the
    /// time integrator itself conserves energy with at rho_inf = 1.
    double         external_work = 0, dissipated_energy = 0;
    Vector<double> generalized_force, damping_force;
    /// The work of every contact force on the shell (obstacles, friction,
    /// self contact), trapezoidal like the others, and the contact force
    /// of the last step.
    double         contact_work = 0;
    Vector<double> contact_force;
  };
} // namespace coshell::driver
