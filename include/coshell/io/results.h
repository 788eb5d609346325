#pragma once

#include <coshell/io/json.h>

#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace coshell::io
{
  /// Wall-clock seconds of the phases of one run.
  struct PhaseTimes
  {
    double setup = 0, assemble = 0, solve = 0, output = 0, total = 0;
  };

  /// One dynamic stage's simulated time and the wall time it took, both
  /// in seconds (from a restart's time when the run resumed inside it).
  struct DynamicStageTime
  {
    unsigned int stage            = 0;
    double       simulated_time_s = 0, wall_time_s = 0;
  };

  /// What one refinement level produced.
  struct LevelResult
  {
    unsigned int  level   = 0;
    double        h       = 0; ///< longest edge in the mesh
    unsigned int  n_cells = 0, n_vertices = 0;
    unsigned long n_dofs = 0, n_inactive_dofs = 0;
    /// The shell's mass (ShellModel::mass); written when positive.
    double mass = 0;
    /// Krylov iterations of the linear solve (1 for a direct solver).
    unsigned long linear_solver_iterations = 0;
    /// Factorizations CHOLMOD refused (not positive definite), done by
    /// UMFPACK instead, over the run so far.
    unsigned int cholmod_fallbacks = 0;
    /// With Linear solver/Reuse factorization: numeric factorizations, and
    /// solves done by GMRES with kept factors instead.
    unsigned int factorizations = 0, reused_factor_solves = 0;
    PhaseTimes   wall_time_s;
    unsigned int load_steps = 0, newton_iterations = 0;
    /// Every Newton correction solved, those of failed attempts (steps
    /// later cut) included; newton_iterations counts converged steps only.
    unsigned int newton_corrections = 0;
    /// Dynamics: time steps, simulated time (s) and the wall time the time
    /// stepping took (s), whose ratio is the real-time factor.
    unsigned int steps            = 0;
    double       simulated_time_s = 0, dynamic_wall_time_s = 0;
    /// The same per dynamic stage, in the order they ran.
    std::vector<DynamicStageTime> dynamic_stages;
    /// Kinetic + strain energy at the start of the first dynamic stage
    /// (the reference of "the energy does not grow"); NaN: none.
    double initial_total_energy = std::numeric_limits<double>::quiet_NaN();
    /// Steps the energy guard rejected in this run (Time integration/
    /// Energy growth limit); written only when the guard is on.
    std::optional<unsigned int> energy_guard_rejections;
    /// Of that wall time: residual/tangent assembly and linear solver,
    /// and of the linear solver the factorizations.
    double dynamic_assembly_s = 0, dynamic_linear_solver_s = 0,
           dynamic_factorization_s = 0;
    /// Static stages of a nonlinear analysis: the wall time of the load
    /// path (s), and of it the assembly, the linear solver and of that the
    /// factorizations.
    double static_wall_time_s = 0, static_assembly_s = 0,
           static_linear_solver_s = 0, static_factorization_s = 0;
    std::map<std::string, double> qoi, reference;
    /// Contact: smallest gap and largest penetration over the run (length),
    /// barrier stiffness, and the seconds spent in detection, pair terms
    /// and the collision filter.
    std::map<std::string, double> contact;

    /// |qoi - reference| / |reference| for every quantity with a reference.
    std::map<std::string, double> relative_errors() const;
    Json                          to_json() const;
  };

  /// convergence.csv: level,h,n_cells,n_dofs,<qoi>,relative_error,rate,
  /// wall_time_s for the primary quantity (the first with a reference,
  /// else the first), then value and relative error of any others. The
  /// rate is log(e_{k-1}/e_k) / log(h_{k-1}/h_k).
  std::string convergence_csv(const std::vector<LevelResult> &levels);
} // namespace coshell::io
