#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/vector.h>

#include <deal.II/fe/fe_values.h>

#include <stabilized_lagrangian/contact/friction_law_check.h>
#include <stabilized_lagrangian/contact/stabilized_lagrangian.h>
#include <stabilized_lagrangian/postprocessing/safe_files.h>
#include <stabilized_lagrangian/solver/contact_problem.h>

#include <cmath>
#include <iomanip>
#include <optional>
#include <sstream>

namespace StabilizedLagrangian
{
  template <int dim>
  typename StepStatisticsCollector<dim>::View
  ContactProblem<dim>::statistics_view()
  {
    return typename StepStatisticsCollector<dim>::View{
        solution,
        system_rhs,
        locally_owned_u,
        owned_multiplier_components,
        multiplier_length_weights,
        contact.conditions(),
        solver_parameters.friction_tolerance,
        internal_force,
        external_force,
        contact_residual,
        boundary_conditions,
        boundary_view(),
        body_mesh.face_gauss(fe_pair->displacement_degree() + 1),
        contact_zones,
        force_unit(dim, axisymmetric, true),
        mpi_communicator,
        [this]() { return ghosted_displacement(); },
        active_set};
  }

  template <int dim>
  TrilinosWrappers::MPI::Vector
  ContactProblem<dim>::ghosted_displacement() const
  {
    TrilinosWrappers::MPI::Vector u_owned(locally_owned_u, mpi_communicator);
    for (const auto index : locally_owned_u)
      u_owned(index) = solution(index);
    u_owned.compress(VectorOperation::insert);
    TrilinosWrappers::MPI::Vector u(locally_owned_u, locally_relevant_u, mpi_communicator);
    u = u_owned;
    return u;
  }

  template <int dim>
  typename MeshRefinement<dim>::View
  ContactProblem<dim>::refinement_view()
  {
    return typename MeshRefinement<dim>::View{triangulation,
                                              refinement_history,
                                              earlier_cycles,
                                              dof_handler_u,
                                              locally_owned_u,
                                              locally_relevant_u,
                                              fe_pair->displacement_degree(),
                                              adaptive_refinement,
                                              error_indicators,
                                              active_set,
                                              memory_at_start,
                                              static_cast<bool>(iterative_solver),
                                              mpi_communicator,
                                              pcout,
                                              [this]() { return ghosted_displacement(); },
                                              [this]() { setup_after_refinement(); },
                                              [this]() {
                                                return ErrorEstimator<dim>(error_estimator_view())
                                                    .pressure_indicators(ghosted_displacement());
                                              }};
  }

  // Explicit instantiation of the members defined in this file (the class
  // itself is instantiated once, in contact_problem.cc).
#define SL_INSTANTIATE(dim)                                                                      \
  template typename StepStatisticsCollector<dim>::View ContactProblem<dim>::statistics_view();   \
  template TrilinosWrappers::MPI::Vector      ContactProblem<dim>::ghosted_displacement() const; \
  template typename MeshRefinement<dim>::View ContactProblem<dim>::refinement_view();

  SL_INSTANTIATE(2)
  SL_INSTANTIATE(3)
#undef SL_INSTANTIATE
} // namespace StabilizedLagrangian
