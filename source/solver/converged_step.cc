#include <deal.II/base/timer.h>

#include <deal.II/fe/fe_values.h>

#include <stabilized_lagrangian/solver/contact_problem.h>

#include <algorithm>
#include <functional>

namespace StabilizedLagrangian
{
  // What the problem does with a converged load step before the next one:
  // the state at the nodes of Γc is sampled once, the step's slip is
  // committed from it, and the output reads both.

  template <int dim>
  void
  ContactProblem<dim>::commit_converged_step(const unsigned int step, const double t)
  {
    TimerOutput::Scope scope(timer, "output");
    update_partner_configuration();
    // The nodes of the contact faces: the Gauss-Lobatto points of the larger
    // of the two degrees (the vertices for Q1/P1, also the midsides for
    // quadratic pairs; on triangle faces the vertices only: see face_nodes())
    std::vector<ContactSample<dim>> samples = contact.sample(body_mesh.face_nodes(
        (dim == 3 && body_mesh.simplex())
            ? 1u
            : std::max({fe_pair->displacement_degree(), fe_pair->multiplier_degree(), 1u})));
    cumulative_slip.commit(step, samples);
    output_results(step, t, samples);
  }

  template <int dim>
  void
  ContactProblem<dim>::output_results(const unsigned int                     step,
                                      const double                           t,
                                      const std::vector<ContactSample<dim>> &samples)
  {
    const TrilinosWrappers::MPI::Vector u = ghosted_displacement();
    // (computed for a VTU only: they refresh the F-bar fields of compute_volume_fields())
    const CellAverages averages = solution_output.writes_vtu() ? cell_averages(u) : CellAverages();
    const std::function<bool(const typename Triangulation<dim>::cell_iterator &, unsigned int)>
        on_contact_boundary =
            [this](const typename Triangulation<dim>::cell_iterator &cell, const unsigned int f) {
              return spaces.is_contact_face(cell, f);
            };
    solution_output.write(step,
                          t,
                          {triangulation,
                           dof_handler_u,
                           u,
                           fe_pair->displacement_degree(),
                           body_mesh.simplex(),
                           axisymmetric,
                           averages,
                           error_indicators,
                           on_contact_boundary,
                           static_cast<unsigned int>(contact.faces().size()),
                           samples,
                           partner->is_rigid() ? obstacle.get() : nullptr,
                           *obstacle_motion},
                          output_directory);
  }

  template <int dim>
  CellAverages
  ContactProblem<dim>::cell_averages(const TrilinosWrappers::MPI::Vector &u) const
  {
    CellAverages averages;
    // the history fields of every material, each name once
    std::vector<std::string> &names = averages.history_names;
    for (const auto &body : body_response.slots())
      for (const auto &name : body.model->history_field_names())
        if (std::find(names.begin(), names.end(), name) == names.end())
          names.push_back(name);
    const unsigned int n_cells = triangulation.n_active_cells();
    body_response.compute_volume_fields(u);
    averages.stress.assign(n_cells, Tensor<2, 3>());
    averages.history_fields.assign(names.size(), Vector<float>(n_cells));
    FEValues<dim> fe_values(
        *fe_u, cell_quadrature, update_gradients | update_values | update_quadrature_points);
    const FEValuesExtractors::Vector displacement(0);
    std::vector<Tensor<2, dim>>      gradients(cell_quadrature.size());
    std::vector<Tensor<1, dim>>      values(cell_quadrature.size()); // axisymmetric: u_r/r
    const double                     weight = 1. / cell_quadrature.size();
    for (const auto &cell : dof_handler_u.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[displacement].get_function_gradients(u, gradients);
          fe_values[displacement].get_function_values(u, values);
          const unsigned int               index       = cell->active_cell_index();
          const Materials::Interface<dim> &material    = body_response.material_of(cell);
          const std::vector<std::string>   field_names = material.history_field_names();
          for (unsigned int q = 0; q < cell_quadrature.size(); ++q)
            {
              // the committed history is that of this converged state
              const auto   history = material_history.committed(index, q);
              const double hoop =
                  body_response.hoop_strain(fe_values.quadrature_point(q), values[q], gradients[q]);
              const auto response = body_response.committed_response(
                  cell, q, cell_quadrature.point(q), gradients[q], nullptr, hoop);
              averages.stress[index] +=
                  weight * Materials::cauchy_stress(
                               gradients[q], response, material.is_finite_strain(), hoop);
              const std::vector<double> fields = material.history_fields(history);
              for (unsigned int f = 0; f < fields.size(); ++f)
                averages.history_fields[std::find(names.begin(), names.end(), field_names[f]) -
                                        names.begin()][index] += weight * fields[f];
            }
        }
    return averages;
  }

  template void
  ContactProblem<2>::commit_converged_step(unsigned int, double);
  template void
  ContactProblem<3>::commit_converged_step(unsigned int, double);
  template void
  ContactProblem<2>::output_results(unsigned int, double, const std::vector<ContactSample<2>> &);
  template void
  ContactProblem<3>::output_results(unsigned int, double, const std::vector<ContactSample<3>> &);
  template CellAverages
  ContactProblem<2>::cell_averages(const TrilinosWrappers::MPI::Vector &) const;
  template CellAverages
  ContactProblem<3>::cell_averages(const TrilinosWrappers::MPI::Vector &) const;
} // namespace StabilizedLagrangian
