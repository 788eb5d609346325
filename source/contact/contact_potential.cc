#include <coshell/contact/contact.h>
#include <coshell/contact/contact_potential.h>

#include <ostream>
#include <stdexcept>

namespace coshell::contact
{
  BarrierPotential::BarrierPotential(double activation_distance,
                                     double stiffening_gap_ratio)
      : activation_distance_(activation_distance),
        stiffening_gap_ratio_(stiffening_gap_ratio)
  {
  }

  ScalarDerivatives BarrierPotential::of_gap(double gap) const
  {
    return log_barrier(gap, activation_distance_);
  }

  double BarrierPotential::stiffness(double barrier_stiffness) const
  {
    return barrier_stiffness;
  }

  double BarrierPotential::activation_distance() const
  {
    return activation_distance_;
  }

  // The barrier is infinite at contact: only a filtered step keeps every
  // iterate where it is defined.
  bool BarrierPotential::filters_steps() const
  {
    return true;
  }

  double BarrierPotential::filter_offset(double kept) const
  {
    return kept;
  }

  // So close to contact the barrier is too stiff a spring for Newton; a
  // stiffer barrier keeps the next steps farther away.
  bool BarrierPotential::stiffens(double smallest_gap) const
  {
    return smallest_gap < stiffening_gap_ratio_ * activation_distance_;
  }

  void BarrierPotential::explain_jam(std::ostream &, double) const {}

  PenaltyPotential::PenaltyPotential(double stiffness,
                                     double smoothing,
                                     double step_filter)
      : stiffness_(stiffness), smoothing_(smoothing), step_filter_(step_filter)
  {
  }

  ScalarDerivatives PenaltyPotential::of_gap(double gap) const
  {
    return smoothed_penalty(gap, smoothing_);
  }

  double PenaltyPotential::stiffness(double /*barrier_stiffness*/) const
  {
    return stiffness_;
  }

  double PenaltyPotential::activation_distance() const
  {
    return 0.0;
  }

  bool PenaltyPotential::filters_steps() const
  {
    return step_filter_ > 0;
  }

  double PenaltyPotential::filter_offset(double kept) const
  {
    return step_filter_ * kept;
  }

  bool PenaltyPotential::stiffens(double /*smallest_gap*/) const
  {
    return false;
  }

  void PenaltyPotential::explain_jam(std::ostream &out,
                                     double        nearest_gap) const
  {
    if (!(step_filter_ > 0 && nearest_gap < 0))
      return;
    // The filter stops pairs at f of their offset whatever the force: a
    // penalty that cannot carry the load within the rest stalls there.
    out << "; the penalty step filter keeps each pair " << step_filter_
        << " of its offset apart, and a penalty too soft to carry the "
           "contact force within the rest jams: raise Contact/Penalty "
           "stiffness ("
        << stiffness_
        << " N/mm^3 in mm-N units) or lower Contact/Penalty step filter";
  }

  std::unique_ptr<ContactPotential>
  make_contact_potential(const ContactParameters &parameters,
                         double                   activation_distance)
  {
    switch (parameters.method)
    {
    case Method::barrier:
      return std::make_unique<BarrierPotential>(
          activation_distance, parameters.stiffening_gap_ratio);
    case Method::penalty:
      return std::make_unique<PenaltyPotential>(parameters.penalty_stiffness,
                                                parameters.penalty_smoothing,
                                                parameters.penalty_step_filter);
    case Method::none:
      break;
    }
    throw std::invalid_argument(
        "make_contact_potential: Contact/Method is none; there is no "
        "contact potential to make");
  }
} // namespace coshell::contact
