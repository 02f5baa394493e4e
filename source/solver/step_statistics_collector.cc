#include <deal.II/base/mpi.h>

#include <stabilized_lagrangian/contact/friction_law_check.h>
#include <stabilized_lagrangian/solver/step_statistics_collector.h>

#include <cmath>
#include <optional>

namespace StabilizedLagrangian
{
  template <int dim>
  void
  StepStatisticsCollector<dim>::collect(StepStatistics &stats) const
  {
    double largest_displacement = 0.;
    for (const auto i : view.locally_owned_u)
      largest_displacement = std::max(largest_displacement, std::abs(view.solution(i)));
    // the multiplier equations of the converged iterate (the residual)
    Contact::FrictionLawCheck<dim> check(largest_displacement);
    for (const auto &[row, component] : view.multiplier_components)
      if (view.multiplier_length_weights(row) > 0.)
        check.add_multiplier_row(
            component == 0, std::abs(view.residual(row)) / view.multiplier_length_weights(row));
    view.conditions.statistics(stats, check, view.active_set);
    stats.friction_law_violations = check.gather(view.communicator, view.friction_tolerance);
    stats.friction_law_report     = check.report();
    add_reactions(stats);
  }

  template <int dim>
  std::vector<types::boundary_id>
  StepStatisticsCollector<dim>::supported_boundaries() const
  {
    std::vector<types::boundary_id> ids;
    for (const auto &condition : view.boundary_conditions)
      condition->add_supported_boundaries(ids);
    return ids;
  }

  template <int dim>
  StatisticsWriter::Supports
  StepStatisticsCollector<dim>::supports() const
  {
    StatisticsWriter::Supports supports;
    supports.force_unit          = view.force_unit;
    supports.reaction_boundaries = supported_boundaries();
    for (const auto &condition : view.boundary_conditions)
      condition->add_statistics_columns(supports);
    for (const auto &zone : view.zones)
      supports.zones.push_back(zone.name);
    return supports;
  }

  template <int dim>
  void
  StepStatisticsCollector<dim>::add_reactions(StepStatistics &stats) const
  {
    const std::vector<types::boundary_id> ids = supported_boundaries();
    std::vector<Tensor<1, dim>>           reactions(ids.size());
    IndexSet                              claimed(view.boundary.dof_handler.n_dofs());
    // the Dirichlet conditions' residual on their DoFs (each once), the springs' force
    std::optional<TrilinosWrappers::MPI::Vector>  u;
    const BoundaryConditions::ReactionInputs<dim> inputs{
        view.internal_force,
        view.external_force,
        view.contact_residual,
        [&]() -> const TrilinosWrappers::MPI::Vector & {
          if (!u)
            u = view.ghosted_displacement();
          return *u;
        },
        view.face_quadrature};
    for (const auto &condition : view.boundary_conditions)
      condition->add_reactions(view.boundary, inputs, ids, reactions, claimed);
    stats.reactions.assign(ids.size(), {{0., 0., 0.}});
    for (unsigned int b = 0; b < ids.size(); ++b)
      {
        const Tensor<1, dim> total = Utilities::MPI::sum(reactions[b], view.communicator);
        for (unsigned int d = 0; d < dim; ++d)
          stats.reactions[b][d] = total[d];
      }
    stats.point_reactions.clear();
    stats.condition_values.clear();
    for (const auto &condition : view.boundary_conditions)
      condition->add_statistics(view.boundary, inputs, stats);
  }

  template class StepStatisticsCollector<2>;
  template class StepStatisticsCollector<3>;
} // namespace StabilizedLagrangian
