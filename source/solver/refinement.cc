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

  template <int dim>
  void
  ContactProblem<dim>::write_cycle_errors(const std::string &directory) const
  {
    // ‖u_N − u_k‖ in the energy norm of the tangent of the last state
    // (for a linear material, the energy norm itself)
    FEValues<dim>                    fe_values(*fe_u,
                            cell_quadrature,
                            update_values | update_gradients | update_quadrature_points |
                                update_JxW_values);
    const FEValuesExtractors::Vector displacement(0);
    const unsigned int               n_q = cell_quadrature.size();
    std::vector<Tensor<2, dim>>      last(n_q), earlier(n_q);
    std::vector<Tensor<1, dim>>      last_u(n_q), earlier_u(n_q); // axisymmetric: hoop strains
    std::vector<double>              squared(earlier_cycles.size(), 0.);
    body_response.compute_volume_fields(earlier_cycles.back());
    for (const auto &cell : dof_handler_u.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[displacement].get_function_gradients(earlier_cycles.back(), last);
          fe_values[displacement].get_function_values(earlier_cycles.back(), last_u);
          std::vector<Materials::Response<dim>> tangents(n_q);
          for (unsigned int q = 0; q < n_q; ++q)
            tangents[q] = body_response.committed_response(
                cell,
                q,
                cell_quadrature.point(q),
                last[q],
                nullptr,
                body_response.hoop_strain(fe_values.quadrature_point(q), last_u[q], last[q]));
          for (unsigned int k = 0; k + 1 < earlier_cycles.size(); ++k)
            {
              fe_values[displacement].get_function_gradients(earlier_cycles[k], earlier);
              fe_values[displacement].get_function_values(earlier_cycles[k], earlier_u);
              for (unsigned int q = 0; q < n_q; ++q)
                {
                  const Point<dim>    &x     = fe_values.quadrature_point(q);
                  const Tensor<2, dim> error = last[q] - earlier[q];
                  const double         hoop =
                      body_response.hoop_strain(x, last_u[q] - earlier_u[q], last[q] - earlier[q]);
                  const auto &A = tangents[q];
                  squared[k] +=
                      (scalar_product(error, double_contract<2, 0, 3, 1>(A.tangent, error)) +
                       hoop * (scalar_product(A.hoop_row + A.hoop_column, error) +
                               A.hoop_hoop * hoop)) *
                      fe_values.JxW(q) * radial_weight(x);
                }
            }
        }
    Utilities::MPI::sum(squared, mpi_communicator, squared);
    if (Utilities::MPI::this_mpi_process(mpi_communicator) != 0)
      return;
    std::ostringstream file;
    file << "cycle,displacement_dofs,estimated_error_sqrtNmm,error_against_last_cycle_sqrtNmm,"
            "effectivity_index\n";
    for (unsigned int k = 0; k + 1 < earlier_cycles.size(); ++k)
      {
        const double error = std::sqrt(std::max(squared[k], 0.));
        file << k << ',' << cycle_records[k].first << ',' << std::setprecision(8)
             << cycle_records[k].second << ',' << error << ','
             << (error > 0. ? cycle_records[k].second / error : 0.) << '\n';
      }
    SafeFiles::write_atomically(directory + "/cycle_errors.csv", file.str());
  }

  // Explicit instantiation of the members defined in this file (the class
  // itself is instantiated once, in contact_problem.cc).
#define SL_INSTANTIATE(dim)                                                                      \
  template void ContactProblem<dim>::compute_contact_statistics(StepStatistics &);               \
  template std::vector<types::boundary_id> ContactProblem<dim>::supported_boundaries() const;    \
  template void ContactProblem<dim>::compute_reactions(StepStatistics &) const;                  \
  template StatisticsWriter::Supports         ContactProblem<dim>::statistics_supports() const;  \
  template TrilinosWrappers::MPI::Vector      ContactProblem<dim>::ghosted_displacement() const; \
  template typename MeshRefinement<dim>::View ContactProblem<dim>::refinement_view();            \
  template void ContactProblem<dim>::write_cycle_errors(const std::string &) const;

  SL_INSTANTIATE(2)
  SL_INSTANTIATE(3)
#undef SL_INSTANTIATE
} // namespace StabilizedLagrangian
