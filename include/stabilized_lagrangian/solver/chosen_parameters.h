#pragma once

#include <deal.II/base/types.h>

#include <stabilized_lagrangian/parameters.h>

#include <set>

namespace StabilizedLagrangian
{
  /**
   * @brief The values a run chooses from its input, the mesh and the
   * materials: the augmentation parameters r_n and r_t (given, or
   * `automatic`), the contact conditions (given, or `Complementarity =
   * automatic`) and the contact boundaries with their mesh names resolved.
   * They are reported in the log and in run_summary.csv; the parsed
   * Parameters::Contact stays as the user wrote it.
   */
  struct ChosenParameters
  {
    /**
     * @brief The values given in @p contact; the automatic ones are chosen
     * later (SceneChecks::choose_augmentation_parameters,
     * ContactBoundary::choose_complementarity), the named boundaries resolved
     * once the mesh is known (ContactProblem::resolve_boundaries).
     */
    explicit ChosenParameters(const Parameters::Contact &contact)
        : r_n(contact.r_n)
        , r_t(contact.r_t)
        , complementarity(contact.complementarity)
        , contact_boundaries(contact.boundary_ids)
        , master_boundaries(contact.master_ids)
    {
    }

    /** @brief Whether the weighted (mortar) conditions hold (doc/formulation.md). */
    bool
    weighted_complementarity() const
    {
      return complementarity == Parameters::Complementarity::weighted;
    }

    double r_n; ///< N/mm^3, the augmentation λ̂ = λ_n − r_n g_n (doc/formulation.md)
    double r_t; ///< 1/mm, the tangential one
    /** the conditions used: pointwise, or weighted per multiplier node */
    Parameters::Complementarity complementarity;
    /** Γc: `Contact/Contact boundary ids`, the names resolved to the mesh's ids */
    std::set<dealii::types::boundary_id> contact_boundaries;
    /** the master surface of a second body (`Contact/Master boundary ids`), resolved */
    std::set<dealii::types::boundary_id> master_boundaries;
  };
} // namespace StabilizedLagrangian
