#pragma once

// The registry of the terms a stage's residual sums (model::Contribution):
// each kind says when a stage has it and how it is made from its own
// parameters (each of which declares and parses its own prm subsection:
// Element and Nonlinear solver/Tangent, Loads, Mass and damping, Contact).
// A new kind of term is one more entry in contribution_kinds().

#include <coshell/contact/contact.h>
#include <coshell/driver/stage.h>
#include <coshell/model/contribution.h>
#include <coshell/model/element_parameters.h>
#include <coshell/model/inertia.h>
#include <coshell/model/loads.h>
#include <coshell/model/shell_model.h>
#include <coshell/model/tangent_settings.h>

#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace coshell::driver
{
  /// The parsed parameters the contributions are made from.
  struct ContributionParameters
  {
    const model::ElementParameters &element;
    const model::TangentSettings   &tangent;
    const model::Loads             &loads;
    const model::InertiaParameters &inertia;
    /// Time integration/Lie group = SE3.
    bool se3 = false;
  };

  /// The stage a set of contributions is made for.
  struct StageContext
  {
    const model::ShellModel &model;
    const Stage             &stage;
    /// The run's contact (nullptr: Contact is off).
    contact::Contact *contact = nullptr;
    std::ostream     &log;
  };

  /// One kind of term of the residual.
  struct ContributionKind
  {
    std::string name;
    /// Whether the stage has this term.
    std::function<bool(const StageContext &)> present;
    std::function<std::unique_ptr<model::Contribution>(
        const ContributionParameters &, const StageContext &)>
        make;
  };

  /// The kinds, in the order their terms are summed: the internal force,
  /// the external loads, the inertia (dynamic stages), the contact
  /// (Contact/Method not none).
  const std::vector<ContributionKind> &contribution_kinds();

  /// The stage's contributions.
  std::vector<std::unique_ptr<model::Contribution>>
  make_contributions(const ContributionParameters &parameters,
                     const StageContext           &context);
} // namespace coshell::driver
