#include <coshell/model/shell_problem.h>

#include <coshell/base/parallel_environment.h>

#include <deal.II/base/multithread_info.h>
#include <deal.II/lac/affine_constraints.templates.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <tuple>
#include <type_traits>

namespace coshell::model
{
  using namespace dealii;

  ShellProblem::ShellProblem(
      const ShellModel                          &model,
      ShellState                                &state,
      const AffineConstraints<double>           &constraints,
      std::vector<std::unique_ptr<Contribution>> contributions,
      PrescribedIncrementFunction                prescribed)
      : model_(model), state_(state), contributions_(std::move(contributions)),
        prescribed_(std::move(prescribed))
  {
    constraints_.copy_from(constraints);
    homogeneous_.copy_from(constraints);
    make_sparsities();
    for (const auto &contribution : contributions_)
      couples_beyond_cells_ |= contribution->couples_beyond_cells();
    for (auto &force : forces_)
      force.reinit(model_.n_dofs());
    global_force_.reinit(model_.n_dofs());
    one_global_force_.reinit(model_.n_dofs());
    set_path_parameter(0);
    // A force that strains an element by 1e-6: below it, forces are
    // round-off. It keeps the convergence test meaningful while nothing is
    // loaded yet (a shell at rest before an obstacle reaches it). At 1e-8
    // a residual tolerance of 1e-7 asked for a residual of a few machine
    // epsilons of the element forces, which a soft lens at rest (E = 1
    // MPa, 480 triangles) could not reach.
    double longest_edge = 0;
    for (const auto &cell : model_.surface().active_cell_iterators())
      for (unsigned int i = 0; i < 3; ++i)
        longest_edge = std::max(
            longest_edge, cell->vertex(i).distance(cell->vertex((i + 1) % 3)));
    const auto &material = model_.element_parameters().material;
    force_floor_ =
        1e-6 * material.youngs_modulus * material.thickness * longest_edge;
  }

  void CorrectionLimits::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Nonlinear solver");
    prm.declare_entry(
        "Largest rotation per correction", "0", Patterns::Double(0),
        "0 = no bound. A Newton correction that would turn some vertex "
        "by more than this is scaled down to it, translations with it (the "
        "contact filter's fraction, if smaller, is taken instead; the line "
        "search works on the scaled correction). Load control and time "
        "steps, not the arc-length corrector. A trust region for first "
        "steps whose linear predictor is far off (the slit annular plate "
        "needs fewer Newton corrections with it, "
        "doc/performance/nonlinear.md); it "
        "costs iterations where large rotations are right (an end moment "
        "rolling a strip up). Unit: rad.");
    prm.leave_subsection();
  }

  void CorrectionLimits::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Nonlinear solver");
    largest_rotation = prm.get_double("Largest rotation per correction");
    prm.leave_subsection();
  }

  void ShellProblem::set_correction_limits(const CorrectionLimits &limits)
  {
    correction_limits_ = limits;
  }

  void ShellProblem::set_schedule(const Schedule &schedule)
  {
    schedule_ = schedule;
  }

  double ShellProblem::time() const
  {
    return time_;
  }

  double ShellProblem::load_factor() const
  {
    return load_factor_;
  }

  const SparsityPattern &ShellProblem::sparsity() const
  {
    return sparsity_;
  }

  void ShellProblem::make_sparsities()
  {
    model_.make_sparsity(homogeneous_, sparsity_, coupled_vertices_);
    static std::atomic<std::uint64_t> versions{0};
    sparsity_version_ = ++versions;
    cell_scatter_.invalidate();
    if (!base::distributed())
      return;
    if (!distributed_sparsity_)
      distributed_sparsity_ =
          std::make_unique<TrilinosWrappers::SparsityPattern>();
    model_.make_distributed_sparsity(homogeneous_, model_.locally_owned_dofs(),
                                     *distributed_sparsity_, coupled_vertices_);
  }

  void ShellProblem::reinit_tangent(base::TangentMatrix &tangent) const
  {
    if (distributed_sparsity_)
      tangent.reinit(*distributed_sparsity_);
    else
      tangent.reinit(sparsity_, sparsity_version_);
  }

  void ShellProblem::begin_solve()
  {
    const EvaluationPoint      at = point();
    std::vector<std::uint64_t> generations;
    for (const auto &contribution : contributions_)
    {
      contribution->begin_solve();
      generations.push_back(contribution->update_coupled_vertices(at));
    }
    // Contact keeps its list while the shell moves little: the same lists
    // need neither gathering nor sorting (even comparing a gathered list
    // shows in a haptic step's profile).
    if (generations == coupling_generations_)
      return;
    coupling_generations_ = std::move(generations);
    std::vector<std::array<unsigned int, 2>> couplings;
    for (const auto &contribution : contributions_)
      contribution->coupled_vertices(couplings);
    std::sort(couplings.begin(), couplings.end());
    couplings.erase(std::unique(couplings.begin(), couplings.end()),
                    couplings.end());
    if (couplings == coupled_vertices_)
      return;
    coupled_vertices_ = std::move(couplings);
    make_sparsities();
  }

  EvaluationPoint ShellProblem::point() const
  {
    return {state_, time_, load_factor_, acceleration_coefficient_,
            velocity_coefficient_};
  }

  /// Sets each prescribed DoF's inhomogeneity to the increment it still
  /// needs; after the correction that realises it, that is round-off.
  void ShellProblem::update_inhomogeneities()
  {
    pending_ = false;
    if (!prescribed_)
      return;
    increments_.clear();
    prescribed_(time_, state_, increments_);
    for (const auto &[dof, increment] : increments_)
    {
      constraints_.set_inhomogeneity(dof, increment);
      const double size = std::max(1.0, std::abs(state_.values()[dof]));
      if (std::abs(increment) > 1e-12 * size)
        pending_ = true;
    }
  }

  namespace
  {
    /// The force kinds cells contribute (internal, external, inertia).
    constexpr unsigned int n_cell_force_kinds =
        std::tuple_size_v<decltype(CellContribution::forces_by_kind)>;
  } // namespace

  template<typename Matrix>
  void
  ShellProblem::assemble(const std::function<bool(const Contribution &)> &use,
                         const EvaluationPoint                           &at,
                         Vector<double> *residual,
                         Matrix         *tangent)
  {
    std::vector<const Contribution *> active;
    for (const auto &contribution : contributions_)
      if (use(*contribution) && contribution->has_cell_terms())
        active.push_back(contribution.get());
    if (active.empty())
      return;
    const bool with_tangent = tangent != nullptr;
    const bool split        = base::distributed();
    auto      &kind_forces  = split ? rank_forces_ : forces_;
    if (split)
      for (auto &force : rank_forces_)
        force.reinit(model_.n_dofs());
    for_each_cell(
        model_.dof_handler(),
        [&](const CellIterator &cell, CellContribution &copy)
        {
          copy.vector.reinit(element::shell_dofs);
          if (with_tangent)
            copy.matrix.reinit(element::shell_dofs, element::shell_dofs);
          for (auto &part : copy.forces_by_kind)
            part.fill(0);
          std::array<double, element::shell_dofs> before;
          for (const Contribution *contribution : active)
          {
            std::copy(copy.vector.begin(), copy.vector.end(), before.begin());
            contribution->add_cell(cell, at, copy, with_tangent);
            auto &part = copy.forces_by_kind[static_cast<unsigned int>(
                contribution->kind())];
            for (unsigned int i = 0; i < element::shell_dofs; ++i)
              part[i] += copy.vector[i] - before[i];
          }
        },
        [&](const CellContribution &copy)
        {
          for (unsigned int k = 0; k < n_cell_force_kinds; ++k)
            for (unsigned int i = 0; i < element::shell_dofs; ++i)
              kind_forces[k][copy.dofs[i]] += copy.forces_by_kind[k][i];
          if (with_tangent)
            add_cell_terms(copy, *tangent, residual);
          else
            constraints_.distribute_local_to_global(copy.vector, copy.dofs,
                                                    *residual);
        },
        CellRange::owned);
    if (split)
      add_up_over_ranks(residual, tangent);
  }

  template<typename Matrix>
  void ShellProblem::add_cell_terms(const CellContribution &copy,
                                    Matrix                 &tangent,
                                    Vector<double>         *residual)
  {
    // Trilinos matrices (MPI) keep deal.II's path, which also sends the
    // entries of rows that other ranks own.
    if constexpr (std::is_same_v<Matrix, SparseMatrix<double>>)
      if (constraints_.n_constraints() == 0 &&
          CellScatter::worth_a_map(
              model_.dof_handler().get_triangulation().n_active_cells()))
      {
        if (residual)
          for (unsigned int i = 0; i < copy.dofs.size(); ++i)
            (*residual)(copy.dofs[i]) += copy.vector(i);
        cell_scatter_.add(copy.matrix, copy.cell_index, copy.dofs, tangent,
                          lower_only_);
        return;
      }
    if (residual)
      constraints_.distribute_local_to_global(copy.matrix, copy.vector,
                                              copy.dofs, tangent, *residual);
    else
      constraints_.distribute_local_to_global(copy.matrix, copy.dofs, tangent);
  }

  void ShellProblem::add_up_over_ranks(Vector<double>       *residual,
                                       SparseMatrix<double> *tangent)
  {
    for (unsigned int k = 0; k < n_cell_force_kinds; ++k)
    {
      base::sum_over_ranks(rank_forces_[k]);
      forces_[k] += rank_forces_[k];
    }
    if (residual)
      base::sum_over_ranks(*residual);
    if (tangent)
      base::sum_over_ranks(*tangent);
  }

  void
  ShellProblem::add_up_over_ranks(Vector<double> *residual,
                                  TrilinosWrappers::SparseMatrix * /*tangent*/)
  {
    // Each rank's cells went into the distributed tangent; its compress()
    // adds them up.
    add_up_over_ranks(residual, static_cast<SparseMatrix<double> *>(nullptr));
  }

  template<typename Matrix>
  void ShellProblem::assemble_blocks(const EvaluationPoint &at,
                                     Vector<double>        &residual,
                                     Matrix                *tangent)
  {
    for (unsigned int k = 0; k < contributions_.size(); ++k)
    {
      const Contribution &contribution = *contributions_[k];
      Vector<double>     &force =
          forces_[static_cast<unsigned int>(contribution.kind())];
      const auto add = [&](const DofBlock &block)
      {
        for (unsigned int i = 0; i < block.dofs.size(); ++i)
          force[block.dofs[i]] += block.vector[i];
        if (scatter_directly(block.matrix, block.vector, block.dofs, tangent,
                             &residual))
          return;
        if (tangent)
          constraints_.distribute_local_to_global(within_pattern(block),
                                                  block.vector, block.dofs,
                                                  *tangent, residual);
        else
          constraints_.distribute_local_to_global(block.vector, block.dofs,
                                                  residual);
      };
      if (blocks_made_on_task_ && !contribution.has_cell_terms())
        for (unsigned int b = 0; b < made_blocks_[k].count; ++b)
          add(made_blocks_[k].blocks[b]);
      else
        contributions_[k]->add_blocks(at, add, tangent != nullptr);
    }
    // Kept blocks are this evaluation's only.
    blocks_made_on_task_ = false;
  }

  template<typename Matrix>
  bool ShellProblem::scatter_directly(
      const FullMatrix<double>                   &matrix,
      const Vector<double>                       &vector,
      const std::vector<types::global_dof_index> &dofs,
      Matrix                                     *tangent,
      Vector<double>                             *residual)
  {
    // Trilinos matrices (MPI) keep deal.II's path, which also sends the
    // entries of rows that other ranks own.
    if constexpr (std::is_same_v<Matrix, SparseMatrix<double>>)
      if (constraints_.n_constraints() == 0)
      {
        scatter_.add(matrix, vector, dofs, tangent, residual, lower_only_);
        return true;
      }
    return false;
  }

  /// The block's matrix without the couplings the pattern lacks (a self
  /// contact pair that came closer than the step's margin foresaw): its
  /// force stays exact, the tangent approximate for that step.
  const FullMatrix<double> &
  ShellProblem::within_pattern(const DofBlock &block) const
  {
    if (!couples_beyond_cells_)
      return block.matrix;
    trimmed_ = block.matrix;
    for (unsigned int i = 0; i < block.dofs.size(); ++i)
      for (unsigned int j = 0; j < block.dofs.size(); ++j)
        // operator() bisects the sorted row; exists() would scan it.
        if (sparsity_(block.dofs[i], block.dofs[j]) ==
            SparsityPattern::invalid_entry)
          trimmed_(i, j) = 0;
    return trimmed_;
  }

  double ShellProblem::assembly_seconds() const
  {
    return assembly_seconds_;
  }

  namespace
  {
    /// Sets a flag for a scope, and unsets it however the scope ends.
    class LowerOnly
    {
    public:
      LowerOnly(bool &flag, bool value) : flag_(flag)
      {
        flag_ = value;
      }
      ~LowerOnly()
      {
        flag_ = false;
      }

    private:
      bool &flag_;
    };
  } // namespace

  void ShellProblem::MadeBlocks::keep(const DofBlock &block)
  {
    if (count == blocks.size())
      blocks.emplace_back();
    DofBlock &kept = blocks[count++];
    kept.dofs      = block.dofs;
    kept.vector    = block.vector;
    kept.matrix    = block.matrix;
  }

  Threads::Task<std::exception_ptr>
  ShellProblem::prepare_contributions(const EvaluationPoint &at,
                                      const bool             with_tangent)
  {
    for (const auto &contribution : contributions_)
      if (contribution->has_cell_terms())
        contribution->prepare(at);
    // The blocks are made on the task as well when it runs beside the
    // cells (contact's pair terms, a tenth of a haptic step), and kept
    // for assemble_blocks: the matrix takes them after the cells, in the
    // same order as before.
    blocks_made_on_task_ = MultithreadInfo::n_threads() > 1;
    made_blocks_.resize(contributions_.size());
    // The task hands back what it threw: deal.II 9.4's Task<void> drops it
    // (a friction coefficient gone negative passed unreported).
    return Threads::new_task(
        [this, &at, with_tangent]() -> std::exception_ptr
        {
          try
          {
            for (const auto &contribution : contributions_)
              if (!contribution->has_cell_terms())
                contribution->prepare(at);
            for (unsigned int k = 0; k < contributions_.size(); ++k)
              if (blocks_made_on_task_ && !contributions_[k]->has_cell_terms())
              {
                MadeBlocks &made = made_blocks_[k];
                made.count       = 0;
                contributions_[k]->add_blocks(
                    at, [&made](const DofBlock &block) { made.keep(block); },
                    with_tangent);
              }
          }
          catch (...)
          {
            return std::current_exception();
          }
          return nullptr;
        });
  }

  void ShellProblem::finish_preparation(
      Threads::Task<std::exception_ptr> &preparation)
  {
    if (const std::exception_ptr failure = preparation.return_value())
      std::rethrow_exception(failure);
    blocked_ = false;
    for (const auto &contribution : contributions_)
      blocked_ = blocked_ || contribution->pending();
    pending_ = pending_ || blocked_;
  }

  void ShellProblem::evaluate(Vector<double>      &residual,
                              base::TangentMatrix *tangent)
  {
    const auto start = std::chrono::steady_clock::now();
    update_inhomogeneities();
    residual = 0;
    if (tangent)
      tangent->zero();
    for (auto &force : forces_)
      force = 0;
    const EvaluationPoint at = point();
    auto       preparation   = prepare_contributions(at, tangent != nullptr);
    const auto every         = [](const Contribution &) { return true; };
    if (tangent && tangent->distributed())
    {
      auto &matrix = tangent->trilinos();
      assemble(every, at, &residual, &matrix);
      finish_preparation(preparation);
      base::RowsOf owned_rows(matrix, model_.locally_owned_dofs());
      assemble_blocks(at, residual, &owned_rows);
      matrix.compress(VectorOperation::add);
    }
    else
    {
      SparseMatrix<double> *matrix = tangent ? &tangent->serial() : nullptr;
      const LowerOnly lower(lower_only_, tangent && tangent->lower_only());
      assemble(every, at, &residual, matrix);
      finish_preparation(preparation);
      assemble_blocks(at, residual, matrix);
    }
    // Each contribution's global terms, kept by kind for the force scale.
    global_force_ = 0;
    for (const auto &contribution : contributions_)
    {
      one_global_force_ = 0;
      contribution->add_global(at, one_global_force_);
      forces_[static_cast<unsigned int>(contribution->kind())] +=
          one_global_force_;
      global_force_ += one_global_force_;
    }
    homogeneous_.condense(global_force_);
    residual += global_force_;
    assembly_seconds_ +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
            .count();
  }

  double ShellProblem::energy()
  {
    for (const auto &contribution : contributions_)
      if (!contribution->has_potential())
        return std::numeric_limits<double>::quiet_NaN();
    const EvaluationPoint at          = point();
    double                cell_energy = 0;
    for_each_cell(
        model_.dof_handler(),
        [&](const CellIterator &cell, CellContribution &copy)
        {
          copy.energy = 0;
          for (const auto &contribution : contributions_)
            if (contribution->has_cell_terms())
              copy.energy += contribution->cell_energy(cell, at);
        },
        [&cell_energy](const CellContribution &copy)
        { cell_energy += copy.energy; },
        CellRange::owned);
    if (base::distributed())
    {
      Vector<double> sum(1);
      sum[0] = cell_energy;
      base::sum_over_ranks(sum);
      cell_energy = sum[0];
    }
    double energy = cell_energy;
    for (const auto &contribution : contributions_)
      energy += contribution->global_energy(at);
    return energy;
  }

  double ShellProblem::current_force_scale() const
  {
    double scale = 0;
    for (const auto &force : forces_)
      scale = std::max(scale, force.l2_norm());
    return scale;
  }

  double ShellProblem::force_scale() const
  {
    // Forces that die out (a structure coming to rest) must not make
    // round-off look large: the scale keeps the largest force of the
    // converged states so far.
    return std::max(
        {current_force_scale(), converged_force_scale_, force_floor_});
  }

  const Vector<double> &ShellProblem::force(ForceKind kind) const
  {
    return forces_[static_cast<unsigned int>(kind)];
  }

  bool ShellProblem::prescribed_increment_pending() const
  {
    return pending_;
  }

  bool ShellProblem::prescribed_move_blocked() const
  {
    return blocked_;
  }

  void ShellProblem::distribute(Vector<double> &correction) const
  {
    constraints_.distribute(correction);
  }

  void ShellProblem::apply_increment(const Vector<double> &correction)
  {
    state_.apply_increment(correction);
  }

  double
  ShellProblem::admissible_fraction(const Vector<double> &correction) const
  {
    double fraction = rotation_limit_fraction(correction);
    for (const auto &contribution : contributions_)
      fraction = std::min(
          fraction, contribution->admissible_fraction(state_, correction));
    return fraction;
  }

  double
  ShellProblem::rotation_limit_fraction(const Vector<double> &correction) const
  {
    const double bound = correction_limits_.largest_rotation;
    if (bound <= 0)
      return 1;
    double largest = 0;
    for (unsigned int v = 0; v < model_.surface().n_vertices(); ++v)
      if (model_.vertex_is_used(v))
      {
        largest = std::max(
            largest,
            vertex_block(correction, model_.vertex_dofs(v), rx).norm());
      }
    return largest > bound ? bound / largest : 1;
  }

  void ShellProblem::extrapolate_reports(const Vector<double> &correction)
  {
    for (const auto &contribution : contributions_)
      contribution->extrapolate_reports(correction);
  }

  void ShellProblem::save()
  {
    converged_force_scale_ =
        std::max(converged_force_scale_, current_force_scale());
    state_.save();
    for (const auto &contribution : contributions_)
      contribution->save();
  }

  void ShellProblem::restore()
  {
    state_.restore();
    for (const auto &contribution : contributions_)
      contribution->restore();
  }

  void ShellProblem::begin_trial()
  {
    trial_start_.emplace(state_);
    for (const auto &contribution : contributions_)
      contribution->begin_trial();
  }

  void ShellProblem::end_trial()
  {
    if (trial_start_)
      state_ = *trial_start_;
    trial_start_.reset();
    for (const auto &contribution : contributions_)
      contribution->end_trial();
  }

  /// What the trial's evaluation changed in the contributions (contact's
  /// obstacles moved against the trial shape) simply stays.
  void ShellProblem::keep_trial()
  {
    trial_start_.reset();
  }

  bool ShellProblem::symmetric_tangent() const
  {
    for (const auto &contribution : contributions_)
      if (!contribution->symmetric_tangent())
        return false;
    return true;
  }

  bool ShellProblem::use_convex_tangent()
  {
    bool changed = false;
    for (const auto &contribution : contributions_)
      changed = contribution->use_convex_tangent() || changed;
    return changed;
  }

  std::string ShellProblem::failure_context() const
  {
    std::string context;
    for (const auto &contribution : contributions_)
      context += contribution->failure_context();
    return context;
  }

  void ShellProblem::set_path_parameter(double s)
  {
    time_        = schedule_.start_time + s * schedule_.duration;
    load_factor_ = schedule_.load_factor(time_, s);
  }

  void ShellProblem::path_direction(Vector<double> &direction)
  {
    // d lambda / d s by central differences of the schedule (exact for the
    // linear ramps the arc-length method is used with).
    const double s  = schedule_.duration > 0
                          ? (time_ - schedule_.start_time) / schedule_.duration
                          : 0;
    const double ds = 1e-6;
    const double slope =
        (schedule_.load_factor(time_ + ds * schedule_.duration, s + ds) -
         schedule_.load_factor(time_ - ds * schedule_.duration, s - ds)) /
        (2 * ds);
    direction.reinit(model_.n_dofs());
    Vector<double>        unit_load(model_.n_dofs());
    const EvaluationPoint at{state_, time_, 1.0, 0, 0};
    assemble([](const Contribution &c)
             { return c.kind() == ForceKind::external; },
             at, &unit_load, static_cast<SparseMatrix<double> *>(nullptr));
    for (const auto &contribution : contributions_)
      if (contribution->kind() == ForceKind::external)
        contribution->add_global(at, unit_load);
    homogeneous_.condense(unit_load);
    direction.equ(slope, unit_load);
  }

  void ShellProblem::set_time(double time)
  {
    time_          = time;
    const double s = schedule_.duration > 0
                         ? (time - schedule_.start_time) / schedule_.duration
                         : 0;
    load_factor_   = schedule_.load_factor(time, s);
  }

  void ShellProblem::step_increment(Vector<double> &increment) const
  {
    state_.step_increment(increment);
  }

  void ShellProblem::set_step_increment(const Vector<double> &increment)
  {
    state_.set_step_increment(increment);
  }

  void ShellProblem::step_displacement(const Vector<double> &increment,
                                       Vector<double>       &displacement) const
  {
    state_.step_displacement(increment, displacement);
  }

  void ShellProblem::set_step_displacement(const Vector<double> &displacement)
  {
    state_.set_step_displacement(displacement);
  }

  Vector<double> &ShellProblem::velocity()
  {
    return state_.velocity();
  }

  Vector<double> &ShellProblem::acceleration()
  {
    return state_.acceleration();
  }

  void ShellProblem::set_rate_coefficients(double acceleration_coefficient,
                                           double velocity_coefficient)
  {
    acceleration_coefficient_ = acceleration_coefficient;
    velocity_coefficient_     = velocity_coefficient;
  }

  void ShellProblem::mass_matrix(base::TangentMatrix &mass)
  {
    mass.zero();
    EvaluationPoint at          = point();
    at.acceleration_coefficient = 1;
    at.velocity_coefficient     = 0;
    at.rate_mass                = true;
    for (auto &force : forces_)
      force = 0;
    Vector<double> unused(model_.n_dofs());
    const auto     inertia = [](const Contribution &c)
    { return c.kind() == ForceKind::inertia; };
    if (mass.distributed())
    {
      assemble(inertia, at, &unused, &mass.trilinos());
      mass.trilinos().compress(VectorOperation::add);
    }
    else
      assemble(inertia, at, &unused, &mass.serial());
  }

  double ShellProblem::converged_force_scale() const
  {
    return std::max(converged_force_scale_, current_force_scale());
  }

  void ShellProblem::set_converged_force_scale(double scale)
  {
    converged_force_scale_ = scale;
  }

  const ShellState &ShellProblem::state() const
  {
    return state_;
  }

  const ShellModel &ShellProblem::model() const
  {
    return model_;
  }

  const AffineConstraints<double> &ShellProblem::constraints() const
  {
    return homogeneous_;
  }
} // namespace coshell::model
