#pragma once

#include <deal.II/base/tensor.h>
#include <deal.II/lac/vector.h>

#include <map>
#include <string>
#include <vector>

namespace coshell::io
{
  /// The state of a run at the end of a step of a dynamic stage, enough to
  /// resume it exactly (the restarted run equals the uninterrupted one to
  /// round-off): written to HDF5 by Output/Checkpoint interval and on
  /// SIGINT/SIGTERM, read by `coshell scene.prm --restart FILE`.
  struct Checkpoint
  {
    /// Where the run stands: 1-based stage number, time in s, steps done
    /// over the whole run, the step of the last VTU written.
    unsigned int stage = 1, step = 0, last_written = 0;
    double       time = 0;
    /// The integrator's carry-over: the next step size, s, and generalized
    /// alpha's pseudo-acceleration (layout of the rates).
    double step_size = 0;
    /// The stage's largest converged force scale (Newton's convergence
    /// test never goes below it).
    double                 converged_force_scale = 0;
    dealii::Vector<double> pseudo_acceleration;
    /// The configuration: DoF values (translations, rotation vectors),
    /// vertex rotation matrices (row-major, 9 per vertex; identity for
    /// unused vertices), rates.
    dealii::Vector<double>            values, velocity, acceleration;
    std::vector<dealii::Tensor<2, 3>> rotations;
    /// Body-frame translational rates (Time integration/Lie group = SE3).
    bool body_frame_translations = false;
    /// The energy bookkeeping: accumulated works (N mm or the scene's
    /// units) and the forces of the last step for the trapezoidal rule.
    double                 external_work = 0, dissipated_energy = 0;
    dealii::Vector<double> generalized_force, damping_force;
    /// Rows of each CSV file and entries of the PVD series written up to
    /// this step: a restart keeps that much of the earlier run's files.
    std::vector<unsigned int> csv_rows;
    unsigned int              pvd_entries = 0;
    /// Further state by name (the contact's), written as datasets.
    std::map<std::string, std::vector<double>> arrays;
    /// The scene file of the run, for the record.
    std::string prm_file;
  };

  /// Writes 'checkpoint' to PATH (via PATH.partial and a rename, so an
  /// interrupted write leaves no file that looks valid).
  void write_checkpoint(const Checkpoint &checkpoint, const std::string &path);

  /// Reads a checkpoint; throws std::invalid_argument naming the file and
  /// what is wrong (missing, not HDF5, not a CoShell checkpoint, a
  /// dataset missing or of the wrong size).
  Checkpoint read_checkpoint(const std::string &path);

  /// The HDF5 format tag of the files (attribute "format").
  inline constexpr const char *checkpoint_format = "coshell checkpoint 2";
} // namespace coshell::io
