#include <coshell/driver/contributions.h>

#include <coshell/model/external_loads.h>
#include <coshell/model/internal_force.h>
#include <coshell/model/thickness_stretch.h>

namespace coshell::driver
{
  namespace
  {
    bool always(const StageContext &)
    {
      return true;
    }

    bool is_dynamic(const StageContext &context)
    {
      return context.stage.analysis == AnalysisType::dynamic;
    }

    bool has_contact(const StageContext &context)
    {
      return context.contact != nullptr;
    }

    bool has_thickness_stretch(const StageContext &context)
    {
      return context.model.has_thickness_stretch();
    }

    bool has_face_pressure(const StageContext &context)
    {
      return context.model.element_parameters().face_pressure != 0;
    }

    std::unique_ptr<model::Contribution>
    internal_force(const ContributionParameters &parameters,
                   const StageContext           &context)
    {
      const auto &tangent = parameters.tangent;
      return std::make_unique<model::InternalForce>(
          context.model, parameters.element.formulation, tangent.tangent(),
          tangent.extrapolated_geometric_stiffness(is_dynamic(context)),
          tangent.exact_tangent_after_failure());
    }

    std::unique_ptr<model::Contribution>
    thick_membrane(const ContributionParameters &, const StageContext &context)
    {
      return std::make_unique<model::ThickMembraneForce>(context.model);
    }

    std::unique_ptr<model::Contribution>
    face_pressure(const ContributionParameters &parameters,
                  const StageContext           &context)
    {
      return std::make_unique<model::FacePressure>(
          context.model, parameters.element.face_pressure);
    }

    std::unique_ptr<model::Contribution>
    external_loads(const ContributionParameters &parameters,
                   const StageContext           &context)
    {
      return std::make_unique<model::ExternalLoads>(
          context.model, parameters.loads,
          parameters.element.formulation == model::Formulation::corotational,
          context.log);
    }

    std::unique_ptr<model::Contribution>
    inertia(const ContributionParameters &parameters,
            const StageContext           &context)
    {
      return std::make_unique<model::Inertia>(context.model, parameters.inertia,
                                              parameters.se3);
    }

    std::unique_ptr<model::Contribution>
    contact_forces(const ContributionParameters &, const StageContext &context)
    {
      return std::make_unique<contact::ContactContribution>(*context.contact);
    }
  } // namespace

  const std::vector<ContributionKind> &contribution_kinds()
  {
    static const std::vector<ContributionKind> kinds = {
        {"internal force", always, internal_force},
        {"thick membrane", has_thickness_stretch, thick_membrane},
        {"external loads", always, external_loads},
        {"face pressure", has_face_pressure, face_pressure},
        {"inertia", is_dynamic, inertia},
        {"contact", has_contact, contact_forces}};
    return kinds;
  }

  std::vector<std::unique_ptr<model::Contribution>>
  make_contributions(const ContributionParameters &parameters,
                     const StageContext           &context)
  {
    std::vector<std::unique_ptr<model::Contribution>> contributions;
    for (const ContributionKind &kind : contribution_kinds())
      if (kind.present(context))
        contributions.push_back(kind.make(parameters, context));
    return contributions;
  }
} // namespace coshell::driver
