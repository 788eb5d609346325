#pragma once

// The contact potential of a pair as a function of its gap, decomposed as
// the IPC Toolkit does: one interface, the log barrier and the smoothed
// penalty its two implementations. Contact asks it every question that
// depends on which of the two is in use, so that the method is decided
// once, where the potential is made.

#include <coshell/contact/barrier.h>

#include <iosfwd>
#include <memory>

namespace coshell::contact
{
  struct ContactParameters;

  /// A pair's energy is weight * area * m * phi(gap) (m: the edge-edge
  /// mollifier); this class gives phi, the weight and what the pair
  /// search and the step filter need to know of phi.
  class ContactPotential
  {
  public:
    virtual ~ContactPotential() = default;

    /// phi(gap) and its first and second derivatives in the gap (length^2,
    /// length, dimensionless).
    virtual ScalarDerivatives of_gap(double gap) const = 0;
    /// The weight per unit area that multiplies phi (force / length^3).
    /// The barrier's stiffness adapts during the run; it is the run's
    /// state, kept and checkpointed by Contact (for either method, so
    /// that the checkpoint has one layout), and passed in here.
    virtual double stiffness(double barrier_stiffness) const = 0;
    /// The gap below which phi acts: a pair farther apart than its offset
    /// plus this distance carries no force and need not be searched.
    virtual double activation_distance() const = 0;
    /// Whether corrections and obstacle moves go through the step filter.
    virtual bool filters_steps() const = 0;
    /// The part of a pair's offset 'kept' that the step filter keeps.
    virtual double filter_offset(double kept) const = 0;
    /// Whether an accepted step whose smallest gap was 'smallest_gap'
    /// doubles the barrier stiffness for the steps after it.
    virtual bool stiffens(double smallest_gap) const = 0;
    /// For a failed solve's message: why the pairs may jam at a nearest
    /// gap 'nearest_gap', and which parameter to change; nothing if this
    /// potential has no such hint.
    virtual void explain_jam(std::ostream &out, double nearest_gap) const = 0;
  };

  /// The log barrier of incremental potential contact (Li et al. 2020):
  /// no iterate interpenetrates, and the stiffness doubles when a step
  /// comes too close.
  class BarrierPotential : public ContactPotential
  {
  public:
    /// 'stiffening_gap_ratio': a step whose smallest gap falls below this
    /// fraction of the activation distance stiffens the barrier.
    BarrierPotential(double activation_distance, double stiffening_gap_ratio);

    ScalarDerivatives of_gap(double gap) const override;
    double            stiffness(double barrier_stiffness) const override;
    double            activation_distance() const override;
    bool              filters_steps() const override;
    double            filter_offset(double kept) const override;
    bool              stiffens(double smallest_gap) const override;
    void explain_jam(std::ostream &out, double nearest_gap) const override;

  private:
    double activation_distance_, stiffening_gap_ratio_;
  };

  /// A C2 penalty on the penetration: it acts only once a pair is closer
  /// than its offset, and filters steps only with a penalty step filter.
  class PenaltyPotential : public ContactPotential
  {
  public:
    /// 'step_filter': 0, or the fraction of each pair's offset that the
    /// step filter keeps the pair apart.
    PenaltyPotential(double stiffness, double smoothing, double step_filter);

    ScalarDerivatives of_gap(double gap) const override;
    double            stiffness(double barrier_stiffness) const override;
    double            activation_distance() const override;
    bool              filters_steps() const override;
    double            filter_offset(double kept) const override;
    bool              stiffens(double smallest_gap) const override;
    void explain_jam(std::ostream &out, double nearest_gap) const override;

  private:
    double stiffness_, smoothing_, step_filter_;
  };

  /// The potential of 'parameters' (whose automatic penalty stiffness and
  /// smoothing are already resolved), with the barrier's activation
  /// distance 'activation_distance'. Throws for Method::none.
  std::unique_ptr<ContactPotential>
  make_contact_potential(const ContactParameters &parameters,
                         double                   activation_distance);
} // namespace coshell::contact
