#include <deal.II/base/mpi.h>

#include <stabilized_lagrangian/solver/contact_problem.h>

#include <algorithm>
#include <limits>
#include <string>

namespace StabilizedLagrangian
{
  template <int dim>
  typename SceneChecks<dim>::View
  ContactProblem<dim>::scene_view() const
  {
    return {mpi_communicator,
            pcout,
            triangulation,
            boundary_conditions,
            boundary_view(),
            contact_parameters,
            load_stepping,
            chosen.contact_boundaries,
            chosen.master_boundaries,
            newton_constraints,
            *obstacle_motion,
            *obstacle,
            *geometry,
            partner.get(),
            *fe_pair,
            body_response.slots(),
            [this](const typename Triangulation<dim>::cell_iterator &cell)
                -> const Materials::Interface<dim> & { return body_response.material_of(cell); },
            axisymmetric,
            contact_zones.any_friction(),
            body_mesh.simplex()};
  }

  template <int dim>
  typename InfSupTest<dim>::View
  ContactProblem<dim>::inf_sup_view()
  {
    return {mpi_communicator,
            dof_handler_u,
            *fe_u,
            locally_owned_u,
            locally_relevant_u,
            n_u,
            cell_quadrature,
            // a Gauss rule exact for both
            body_mesh.face_gauss(
                std::max(fe_pair->displacement_degree(), fe_pair->multiplier_degree()) + 1),
            [this](AffineConstraints<double> &constraints) {
              SystemConstraints<dim>(constraints_view()).add_homogeneous_dirichlet(constraints);
            },
            owned_multiplier_components,
            hanging_constraints,
            contact,
            spaces,
            ghosted_solution,
            *partner,
            linear_solver_parameters.direct_solver};
  }

  template <int dim>
  void
  ContactProblem<dim>::run_inf_sup_test(const unsigned int n_meshes)
  {
    inf_sup.run(n_meshes, output_directory, [this](const unsigned int mesh) {
      if (mesh == 1)
        setup();
      else
        {
          body_mesh.refine_globally(fe_pair->displacement_degree());
          setup_after_refinement();
        }
      return inf_sup_view();
    });
  }

  template <int dim>
  void
  ContactProblem<dim>::close_nearest_points()
  {
    // Nothing touches and a rigid motion is free (the Dirichlet conditions
    // leave it, or the Newton system proved singular: a body carried only by
    // prescribed forces): the loads alone cannot bring the body onto its
    // partner in a quasi-static step. It is put on the partner by its points
    // nearest to it, as a body lowered until it touches; those points count
    // as touching (approach_gap) until the step converges.
    double nearest = std::numeric_limits<double>::max();
    contact.for_each_point([&](ContactPointState<dim> &state, const ContactKinematics<dim> &k) {
      nearest = std::min(nearest, state.pairing.gap(k.position));
    });
    nearest                     = Utilities::MPI::min(nearest, mpi_communicator);
    contact_start.approach_gap  = std::max(nearest, 0.) + touching_gap;
    contact_start.approach_used = true;
    // the conditions' own gaps (the nodes' weighted gaps): the nearest closes
    contact_start.approach_gap =
        std::max(contact_start.approach_gap,
                 std::max(contact.conditions().least_gap(nearest), 0.) + touching_gap);
    contact.conditions().close_nearest(nearest, touching_gap);
    pcout << "  nothing touches the "
          << (free_rigid_motions.empty()
                  ? std::string("partner and the Newton system is singular")
                  : "obstacle and the Dirichlet conditions leave " + free_rigid_motions + " free")
          << ": the " << contact.points_in_contact() << " contact point(s) nearest to it (gap "
          << nearest << " mm) start in contact\n";
  }

  // Explicit instantiation of the members defined in this file (the class
  // itself is instantiated once, in contact_problem.cc).
#define SL_INSTANTIATE(dim)                                                                     \
  template typename SceneChecks<dim>::View ContactProblem<dim>::scene_view() const;             \
  template typename InfSupTest<dim>::View  ContactProblem<dim>::inf_sup_view();                 \
  template void                            ContactProblem<dim>::run_inf_sup_test(unsigned int); \
  template void                            ContactProblem<dim>::close_nearest_points();

  SL_INSTANTIATE(2)
  SL_INSTANTIATE(3)
#undef SL_INSTANTIATE
} // namespace StabilizedLagrangian
