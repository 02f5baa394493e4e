#include <stabilized_lagrangian/solver/contact_problem.h>

namespace StabilizedLagrangian
{
  template <int dim>
  void
  ContactProblem<dim>::setup_contact_points()
  {
    contact.setup();
    // initial statuses from the initial configuration: touching points are in contact
    sparsity_ready = false;
    update_pairings(true);
    setup_sparsity();
    nested_loops.update_statuses();
    if (!free_rigid_motions.empty() && contact.points_in_contact() == 0)
      close_nearest_points();
  }

  template <int dim>
  void
  ContactProblem<dim>::update_pairings(const bool resegment)
  {
    update_partner_configuration();
    const bool   new_points = resegment && contact.update_segments();
    PointRefresh pairing;
    pairing.pairing = true;
    contact.refresh_points(pairing, [](const auto &, const auto &, const auto &) {});
    if (new_points)
      {
        // the new points take the threshold and status of the current iterate,
        // which the loops would give them
        nested_loops.update_friction_thresholds();
        nested_loops.update_statuses();
      }
    if (sparsity_ready && (sparsity_stale || pairings_left_sparsity()))
      setup_sparsity();
  }

  // Explicit instantiation of the members defined in this file (the class
  // itself is instantiated once, in contact_problem.cc).
#define SL_INSTANTIATE(dim)                                  \
  template void ContactProblem<dim>::setup_contact_points(); \
  template void ContactProblem<dim>::update_pairings(bool);

  SL_INSTANTIATE(2)
  SL_INSTANTIATE(3)
#undef SL_INSTANTIATE
} // namespace StabilizedLagrangian
