#include <stabilized_lagrangian/contact/stabilized_lagrangian.h>
#include <stabilized_lagrangian/contact/stabilized_point_law.h>

namespace StabilizedLagrangian
{
  template <int dim>
  Contact::PointResponse<dim - 1>
  StabilizedPointLaw<dim>::point_response(const ContactPointState<dim> &state,
                                          const ContactKinematics<dim> &k) const
  {
    return Contact::PointResponse<dim - 1>(
        k.contact_pressure,
        state.pairing.gap(k.position),
        k.semi_multiplier,
        state.pairing.tangential_components(k.step_increment),
        state.in_contact,
        state.friction_threshold,
        friction_law_of(state).has_friction(),
        view.r_n,
        view.r_t,
        view.loops.linearised(Loop::friction)
            ? friction_law_of(state).threshold_derivative(threshold_pressure(k.contact_pressure))
            : 0.);
  }

  template <int dim>
  void
  StabilizedPointLaw<dim>::evaluate_point_state(ContactPointState<dim> &state,
                                                ContactKinematics<dim> &k,
                                                const PointRefresh     &what) const
  {
    if (what.pairing)
      state.pairing = view.partner->project(k.position);
    k.step_increment -= view.partner->follow(
        state.pairing, view.ghosted_solution, view.step_start, k.position - k.step_increment);
    if (what.threshold)
      state.friction_threshold =
          friction_law_of(state).threshold(threshold_pressure(k.contact_pressure));
    if (what.status)
      state.in_contact = status(state, k);
  }

  template <int dim>
  bool
  StabilizedPointLaw<dim>::status(const ContactPointState<dim> &state,
                                  const ContactKinematics<dim> &k) const
  {
    // A gap within round-off of zero touches: a body resting on the obstacle
    // by a vertex placed 1e-14 mm above it must start in contact, as one at
    // exactly zero does, or a load-controlled body has no support at all.
    const double gap = state.pairing.gap(k.position);
    return Contact::is_in_contact(
        Contact::augmented_pressure(k.contact_pressure, status_gap(gap), view.r_n));
  }

  template class StabilizedPointLaw<2>;
  template class StabilizedPointLaw<3>;
} // namespace StabilizedLagrangian
