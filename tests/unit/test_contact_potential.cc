// The ContactPotential interface and its two implementations, the log
// barrier and the smoothed penalty, made by the factory as Contact makes
// them: derivatives against central differences of the value, support,
// weight, step filter and stiffening.

#include <coshell/contact/contact.h>
#include <coshell/contact/contact_potential.h>

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <sstream>
#include <stdexcept>

namespace
{
  using namespace coshell::contact;

  constexpr double activation = 0.2, smoothing = 0.01;

  std::unique_ptr<ContactPotential> made(Method method)
  {
    ContactParameters parameters;
    parameters.method               = method;
    parameters.penalty_stiffness    = 10;
    parameters.penalty_smoothing    = smoothing;
    parameters.penalty_step_filter  = 0.5;
    parameters.stiffening_gap_ratio = 1e-3;
    return make_contact_potential(parameters, activation);
  }

  /// phi' and phi'' at 'gap' against central differences of phi with the
  /// step 'h' (the second difference also of phi, not of phi').
  void expect_derivatives_of_value(const ContactPotential &potential,
                                   double                  gap,
                                   double                  h)
  {
    const ScalarDerivatives at    = potential.of_gap(gap),
                            above = potential.of_gap(gap + h),
                            below = potential.of_gap(gap - h);
    const double first            = (above.value - below.value) / (2 * h);
    const double second = (above.value - 2 * at.value + below.value) / (h * h);
    EXPECT_NEAR(first, at.first, 1e-6 * std::abs(at.first) + 1e-10)
        << "gap " << gap;
    EXPECT_NEAR(second, at.second, 1e-4 * std::abs(at.second) + 1e-6)
        << "gap " << gap;
  }
} // namespace

TEST(ContactPotentialInterface, BarrierDerivativesMatchCentralDifferences)
{
  const auto barrier = made(Method::barrier);
  for (const double gap : {0.002, 0.01, 0.05, 0.1, 0.19})
    expect_derivatives_of_value(*barrier, gap, 1e-5 * gap);
}

TEST(ContactPotentialInterface, PenaltyDerivativesMatchCentralDifferences)
{
  const auto penalty = made(Method::penalty);
  // Within the cubic start and on the quadratic beyond it, away from the
  // joints at 0 and -smoothing where phi'' jumps.
  for (const double gap : {-0.002, -0.008, -0.02, -0.5})
    expect_derivatives_of_value(*penalty, gap, 1e-6);
}

TEST(ContactPotentialInterface, BarrierIsZeroAtAndBeyondItsActivationDistance)
{
  const auto barrier = made(Method::barrier);
  EXPECT_EQ(barrier->activation_distance(), activation);
  for (const double gap : {activation, 1.5 * activation, 10.0})
  {
    const ScalarDerivatives phi = barrier->of_gap(gap);
    EXPECT_EQ(phi.value, 0);
    EXPECT_EQ(phi.first, 0);
    EXPECT_EQ(phi.second, 0);
  }
  EXPECT_GT(barrier->of_gap(0.5 * activation).value, 0);
  EXPECT_TRUE(std::isinf(barrier->of_gap(0).value));
}

TEST(ContactPotentialInterface, PenaltyActsOnlyOnPenetration)
{
  const auto penalty = made(Method::penalty);
  EXPECT_EQ(penalty->activation_distance(), 0);
  EXPECT_EQ(penalty->of_gap(0).value, 0);
  EXPECT_EQ(penalty->of_gap(0.05).first, 0);
  EXPECT_GT(penalty->of_gap(-0.05).value, 0);
}

TEST(ContactPotentialInterface, WeightFilterAndStiffeningOfEachMethod)
{
  const auto barrier = made(Method::barrier), penalty = made(Method::penalty);
  // The barrier's weight is the run's adaptive stiffness; the penalty's
  // is its own.
  EXPECT_EQ(barrier->stiffness(3.5), 3.5);
  EXPECT_EQ(penalty->stiffness(3.5), 10);
  EXPECT_TRUE(barrier->filters_steps());
  EXPECT_TRUE(penalty->filters_steps());
  EXPECT_EQ(barrier->filter_offset(0.4), 0.4);
  EXPECT_EQ(penalty->filter_offset(0.4), 0.5 * 0.4);
  EXPECT_TRUE(barrier->stiffens(0.5e-3 * activation));
  EXPECT_FALSE(barrier->stiffens(2e-3 * activation));
  EXPECT_FALSE(penalty->stiffens(-1.0));

  ContactParameters unfiltered;
  unfiltered.method = Method::penalty;
  EXPECT_FALSE(make_contact_potential(unfiltered, activation)->filters_steps());
  unfiltered.method = Method::none;
  EXPECT_THROW(make_contact_potential(unfiltered, activation),
               std::invalid_argument);
}

TEST(ContactPotentialInterface, OnlyTheFilteredPenaltyExplainsAJam)
{
  std::ostringstream barrier_hint, penalty_hint, clear_hint;
  made(Method::barrier)->explain_jam(barrier_hint, -0.01);
  made(Method::penalty)->explain_jam(penalty_hint, -0.01);
  made(Method::penalty)->explain_jam(clear_hint, 0.01);
  EXPECT_TRUE(barrier_hint.str().empty());
  EXPECT_TRUE(clear_hint.str().empty());
  EXPECT_NE(penalty_hint.str().find("Penalty step filter"), std::string::npos);
}
