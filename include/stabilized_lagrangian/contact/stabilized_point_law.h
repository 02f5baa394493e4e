#pragma once

#include <deal.II/lac/trilinos_vector.h>

#include <stabilized_lagrangian/contact/contact_conditions.h>
#include <stabilized_lagrangian/contact/friction_zones.h>
#include <stabilized_lagrangian/contact/partner.h>
#include <stabilized_lagrangian/solver/loop_policy.h>

#include <memory>

/**
 * @file
 * The law at one contact point: its pairing with the contact partner, its
 * friction threshold and status, and the point-wise stabilized Lagrangian of
 * seed eqs. (5)–(8) with them.
 */

namespace StabilizedLagrangian
{
  using namespace dealii;

  /**
   * @brief The seed's point-wise law against the contact partner, the one
   * ContactPointLaw the conditions, the assembly, the Newton iteration and the
   * error estimate ask. It owns nothing: it reads the partner, the iterate,
   * the zones' friction laws, r_n and r_t and the loop policy through a View
   * of references, so it follows them as they change (a new partner per mesh,
   * the automatic r_n, the loops of a step).
   */
  template <int dim> class StabilizedPointLaw : public ContactPointLaw<dim>
  {
  public:
    /** What the law reads, by reference (their current values are used at each call). */
    struct View
    {
      /** the contact partner of the current mesh (rigid obstacle or master surface) */
      const std::unique_ptr<Contact::Partner<dim>> &partner;
      /** relevant: the iterate, and the solution at the step start */
      const TrilinosWrappers::MPI::Vector &ghosted_solution;
      const TrilinosWrappers::MPI::Vector &step_start;
      /** the friction law of each zone */
      const Contact::FrictionZones &zones;
      /** the stabilization parameters (N/mm³, 1/mm) */
      const double &r_n;
      const double &r_t;
      /** which loops the generalized Newton linearises (the threshold's derivative) */
      const LoopPolicy &loops;
      /** |g_n| at most this counts as touching (round-off of the coordinates) */
      const double &touching_gap;
      /** the gap a step's contact start counts as touching (ContactStart::approach_gap) */
      const double &approach_gap;
      /** below it a contact pressure is round-off: the threshold sees provisional_pressure */
      const double &negligible_pressure;
      /** the pressure a threshold sees before the contact carries any (ContactStart) */
      const double &provisional_pressure;
    };

    /** @brief The law of the partner and iterate @p view shows. */
    explicit StabilizedPointLaw(const View &view)
        : view(view)
    {
    }

    void
    evaluate_point_state(ContactPointState<dim> &state,
                         ContactKinematics<dim> &k,
                         const PointRefresh     &what) const override;

    Contact::PointResponse<dim - 1>
    point_response(const ContactPointState<dim> &state,
                   const ContactKinematics<dim> &k) const override;

    double
    status_gap(const double gap) const override
    {
      return std::abs(gap) <= std::max(view.touching_gap, view.approach_gap) ? 0. : gap;
    }

    double
    threshold_pressure(double contact_pressure) const override
    {
      return contact_pressure > view.negligible_pressure ? contact_pressure
                                                         : view.provisional_pressure;
    }

    const FrictionLaws::Interface &
    friction_law_of(const ContactPointState<dim> &state) const override
    {
      return view.zones.law_of(state.zone);
    }

  private:
    /**
     * The status χ of a point at the iterate: in contact when the augmented
     * pressure λ_n − r_n g_n is positive, a gap within round-off of zero
     * counting as touching.
     */
    bool
    status(const ContactPointState<dim> &state, const ContactKinematics<dim> &k) const;

    const View view;
  };
} // namespace StabilizedLagrangian
