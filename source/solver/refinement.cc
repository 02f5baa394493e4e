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
  void
  ContactProblem<dim>::compute_contact_statistics(StepStatistics &stats)
  {
    double largest_displacement = 0.;
    for (const auto i : locally_owned_u)
      largest_displacement = std::max(largest_displacement, std::abs(solution(i)));
    // the multiplier equations of the converged iterate (system_rhs is its residual)
    Contact::FrictionLawCheck<dim> check(largest_displacement);
    for (const auto &[row, component] : owned_multiplier_components)
      if (multiplier_length_weights(row) > 0.)
        check.add_multiplier_row(component == 0,
                                 std::abs(system_rhs(row)) / multiplier_length_weights(row));
    conditions->statistics(stats, check, active_set);
    stats.friction_law_violations =
        check.gather(mpi_communicator, solver_parameters.friction_tolerance);
    stats.friction_law_report = check.report();
    compute_reactions(stats);
  }

  template <int dim>
  std::vector<types::boundary_id>
  ContactProblem<dim>::supported_boundaries() const
  {
    std::vector<types::boundary_id> ids;
    for (const auto &condition : boundary_conditions)
      condition->add_supported_boundaries(ids);
    return ids;
  }

  template <int dim>
  StatisticsWriter::Supports
  ContactProblem<dim>::statistics_supports() const
  {
    StatisticsWriter::Supports supports;
    supports.force_unit          = force_unit(true);
    supports.reaction_boundaries = supported_boundaries();
    for (const auto &condition : boundary_conditions)
      condition->add_statistics_columns(supports);
    for (const auto &zone : contact_zones)
      supports.zones.push_back(zone.name);
    return supports;
  }

  template <int dim>
  void
  ContactProblem<dim>::compute_reactions(StepStatistics &stats) const
  {
    const std::vector<types::boundary_id> ids = supported_boundaries();
    std::vector<Tensor<1, dim>>           reactions(ids.size());
    IndexSet                              claimed(dof_handler_u.n_dofs());
    // the Dirichlet conditions' residual on their DoFs (each once), the springs' force
    std::optional<TrilinosWrappers::MPI::Vector> u;
    const Quadrature<dim - 1> face_quadrature = face_gauss(fe_pair->displacement_degree() + 1);
    const BoundaryConditions::ReactionInputs<dim> inputs{
        internal_force,
        external_force,
        contact_residual,
        [&]() -> const TrilinosWrappers::MPI::Vector & {
          if (!u)
            u = ghosted_displacement();
          return *u;
        },
        face_quadrature};
    for (const auto &condition : boundary_conditions)
      condition->add_reactions(boundary_view(), inputs, ids, reactions, claimed);
    stats.reactions.assign(ids.size(), {{0., 0., 0.}});
    for (unsigned int b = 0; b < ids.size(); ++b)
      {
        const Tensor<1, dim> total = Utilities::MPI::sum(reactions[b], mpi_communicator);
        for (unsigned int d = 0; d < dim; ++d)
          stats.reactions[b][d] = total[d];
      }
    stats.point_reactions.clear();
    stats.condition_values.clear();
    for (const auto &condition : boundary_conditions)
      condition->add_statistics(boundary_view(), inputs, stats);
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
                                              [this]() { setup_after_refinement(); }};
  }

  // Explicit instantiation of the members defined in this file (the class
  // itself is instantiated once, in contact_problem.cc).
#define SL_INSTANTIATE(dim)                                                                      \
  template void ContactProblem<dim>::compute_contact_statistics(StepStatistics &);               \
  template std::vector<types::boundary_id> ContactProblem<dim>::supported_boundaries() const;    \
  template void ContactProblem<dim>::compute_reactions(StepStatistics &) const;                  \
  template StatisticsWriter::Supports         ContactProblem<dim>::statistics_supports() const;  \
  template TrilinosWrappers::MPI::Vector      ContactProblem<dim>::ghosted_displacement() const; \
  template typename MeshRefinement<dim>::View ContactProblem<dim>::refinement_view();

  SL_INSTANTIATE(2)
  SL_INSTANTIATE(3)
#undef SL_INSTANTIATE
} // namespace StabilizedLagrangian
