#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_interface_values.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>

#include <deal.II/grid/grid_tools.h>

#include <stabilized_lagrangian/contact/stabilized_lagrangian.h>
#include <stabilized_lagrangian/solver/contact_problem.h>
#include <stabilized_lagrangian/solver/error_estimator.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace StabilizedLagrangian
{
  // The residual a posteriori error estimate of the converged state
  // (doc/formulation.md, "Error estimate"): for each cell K
  //
  //   η_K² = (1/E_K) [ h_K² ‖div P‖²_K + ½ Σ_F h_F ‖⟦P N⟧‖²_F + Σ_{F⊂Γ} h_F ‖P N − t̄‖²_F ]
  //        + η_{C,K}²,
  //
  // η_{C,K}² the contact terms of its faces on Γc: the traction residual
  // (h_F/E) ‖P N − t_c‖², the tension (h_F/E) ‖λ_n⁻‖², the penetration
  // (E/h_F) ‖g_n⁻‖², the complementarity |∫_Γc λ_n g_n| (shared by the faces),
  // the friction cone (h_F/E) ‖(|t_t| − s(λ_n))⁺‖² and the dissipation
  // ∫ s(λ_n)|Δs| + t_t·Δs (≥ 0 point by point: |t_t| ≤ s).
  // Every term is an energy (N mm), so η = (Σ_K η_K²)^½ estimates the energy
  // norm of the error, in √(N mm).

  namespace
  {
    // The complementarity enters as the global |∫_Γc λ_n g_n| (Hild and
    // Nicaise 2007): the weak non-penetration ∫ψ_j g_n = 0 makes it cancel
    // over the patch of each multiplier node, while a face's own ∫_F λ_n g_n
    // (with the O(h²) gap between the nodes of a quadratic face) stays of
    // order h and would make the estimate decay more slowly than the error.
    // Each face takes the share of its own |∫_F λ_n g_n| (@p face_complementarity:
    // its cell's index and ∫_F λ_n g_n).
    void
    add_complementarity_shares(
        const std::vector<std::pair<unsigned int, double>> &face_complementarity,
        const MPI_Comm                                      communicator,
        Vector<double>                                     &contact)
    {
      double signed_total = 0., absolute_total = 0.;
      for (const auto &[cell, value] : face_complementarity)
        {
          signed_total += value;
          absolute_total += std::abs(value);
        }
      signed_total   = Utilities::MPI::sum(signed_total, communicator);
      absolute_total = Utilities::MPI::sum(absolute_total, communicator);
      if (absolute_total > 0.)
        for (const auto &[cell, value] : face_complementarity)
          contact[cell] += std::abs(signed_total) * std::abs(value) / absolute_total;
    }
  } // namespace

  template <int dim>
  Vector<float>
  ErrorEstimator<dim>::estimate(const TrilinosWrappers::MPI::Vector &u, StepStatistics &stats)
  {
    Vector<double> squared(view.triangulation.n_active_cells()), contact(squared.size());
    double         energy          = residual_indicators(u, squared, contact);
    stats.estimated_pressure_error = pressure_estimate(u);
    Vector<float> indicators(squared.size());
    double        total = 0., contact_total = 0.;
    for (const auto &cell : view.triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const unsigned int k = cell->active_cell_index();
          indicators[k]        = std::sqrt(squared[k] + contact[k]);
          total += squared[k] + contact[k];
          contact_total += contact[k];
        }
    total                         = Utilities::MPI::sum(total, view.communicator);
    contact_total                 = Utilities::MPI::sum(contact_total, view.communicator);
    energy                        = Utilities::MPI::sum(energy, view.communicator);
    stats.estimated_error         = std::sqrt(total);
    stats.estimated_contact_error = std::sqrt(contact_total);
    stats.energy_norm             = std::sqrt(std::max(energy, 0.));
    return indicators;
  }

  template <int dim>
  EnergyEstimate
  ErrorEstimator<dim>::energy_estimate(const TrilinosWrappers::MPI::Vector &u)
  {
    Vector<double> squared(view.triangulation.n_active_cells()), contact(squared.size());
    const double   energy = residual_indicators(u, squared, contact);
    squared += contact;
    EnergyEstimate estimate;
    estimate.error       = std::sqrt(Utilities::MPI::sum(squared.l1_norm(), view.communicator));
    estimate.energy_norm = std::sqrt(std::max(Utilities::MPI::sum(energy, view.communicator), 0.));
    return estimate;
  }

  template <int dim>
  double
  ErrorEstimator<dim>::residual_indicators(const TrilinosWrappers::MPI::Vector &u,
                                           Vector<double>                      &squared,
                                           Vector<double>                      &contact)
  {
    share_ghost_history();
    view.body_response.compute_volume_fields(u);
    const double energy = add_volume_residuals(u, squared);
    add_face_residuals(u, squared);
    add_contact_residuals(u, contact);
    return energy;
  }

  template <int dim>
  void
  ErrorEstimator<dim>::share_ghost_history()
  {
    // the stress of a ghost neighbour depends on its history, which only its
    // owner updates
    const bool has_history =
        std::any_of(view.body_response.slots().begin(),
                    view.body_response.slots().end(),
                    [](const auto &body) { return body.model->n_history() > 0; });
    if (!has_history || Utilities::MPI::n_mpi_processes(view.communicator) == 1)
      return;
    Materials::QuadratureHistory &history = view.ghost_history;
    GridTools::exchange_cell_data_to_ghosts<std::vector<double>, DoFHandler<dim>>(
        view.displacement_dofs,
        [&history](const DoFCell &cell) {
          return history.committed_cell(cell->active_cell_index());
        },
        [&history](const DoFCell &cell, const std::vector<double> &values) {
          history.set_committed_cell(cell->active_cell_index(), values);
        });
  }

  template <int dim>
  Tensor<2, dim>
  ErrorEstimator<dim>::stress_at(const TriaCell       &cell,
                                 const Tensor<2, dim> &grad_u,
                                 const Point<dim>     &point,
                                 const double          hoop) const
  {
    // the history lives at the cell's quadrature points: the nearest one's;
    // F-bar and mixed evaluate the kept volume change at the point
    const Quadrature<dim> &rule    = view.cell_quadrature;
    const bool             history = material_of(cell).n_history() > 0;
    const Point<dim>       unit    = history || view.body_response.body_of(cell).modified_volume()
                                         ? cell->reference_cell()
                                      .template get_default_linear_mapping<dim>()
                                      .transform_real_to_unit_cell(cell, point)
                                         : Point<dim>();
    unsigned int           nearest = 0;
    if (history)
      for (unsigned int q = 1; q < rule.size(); ++q)
        if (rule.point(q).distance(unit) < rule.point(nearest).distance(unit))
          nearest = q;
    return view.body_response.committed_response(cell, nearest, unit, grad_u, nullptr, hoop).stress;
  }

  template <int dim>
  double
  ErrorEstimator<dim>::add_volume_residuals(const TrilinosWrappers::MPI::Vector &u,
                                            Vector<double>                      &squared) const
  {
    const Quadrature<dim>           &rule = view.cell_quadrature;
    FEValues<dim>                    fe_values(view.displacement_fe,
                            rule,
                            update_gradients | update_hessians | update_JxW_values |
                                update_inverse_jacobians | update_values |
                                update_quadrature_points);
    const FEValuesExtractors::Vector displacement(0);
    std::vector<Tensor<2, dim>>      gradients(rule.size());
    std::vector<Tensor<1, dim>>      values(rule.size());
    std::vector<Tensor<3, dim>>      hessians(rule.size());
    double                           energy = 0.;
    for (const auto &cell : view.displacement_dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[displacement].get_function_gradients(u, gradients);
          fe_values[displacement].get_function_hessians(u, hessians);
          fe_values[displacement].get_function_values(u, values);
          // mixed on Q2: the kept volume change v̄ = Σ c_a ψ_a varies in the
          // cell, ψ_a = ξ_(a−1) − ξ_c (a ≥ 1)
          const auto &body = view.body_response.body_of(cell);
          const bool  varying_volume =
              body.modified_volume() && view.body_response.volume_projection(body).n_basis() > 1;
          double residual = 0.;
          for (unsigned int q = 0; q < rule.size(); ++q)
            {
              Tensor<2, dim>    d_kept;
              const Point<dim> &x        = fe_values.quadrature_point(q);
              const double      hoop     = hoop_strain(x, values[q], gradients[q]);
              const auto        response = view.body_response.committed_response(
                  cell, q, rule.point(q), gradients[q], varying_volume ? &d_kept : nullptr, hoop);
              // div P = A : ∇∇u (A = ∂P/∂F) + ∂P/∂v̄ ∇v̄, no body force
              Tensor<1, dim> divergence;
              for (unsigned int i = 0; i < dim; ++i)
                for (unsigned int j = 0; j < dim; ++j)
                  for (unsigned int k = 0; k < dim; ++k)
                    for (unsigned int l = 0; l < dim; ++l)
                      divergence[i] += response.tangent[i][j][k][l] * hessians[q][k][l][j];
              if (varying_volume)
                {
                  const auto &coefficients =
                      view.body_response.kept_volume(cell->active_cell_index());
                  Tensor<1, dim> grad_kept;
                  for (unsigned int a = 1; a <= dim; ++a)
                    for (unsigned int j = 0; j < dim; ++j)
                      grad_kept[j] += coefficients[a] * fe_values.inverse_jacobian(q)[a - 1][j];
                  divergence += d_kept * grad_kept;
                }
              if (view.axisymmetric)
                {
                  // (1/r) ∂(r P_ij)/∂x_j − δ_i1 P_θθ/r, with ∂P/∂F₃₃ ∇(u_r/r) in ∂P_ij/∂x_j
                  const double   r         = x[0];
                  Tensor<1, dim> grad_hoop = gradients[q][0] / r;
                  grad_hoop[0] -= values[q][0] / (r * r);
                  divergence += response.hoop_column * grad_hoop;
                  for (unsigned int i = 0; i < dim; ++i)
                    divergence[i] += response.stress[i][0] / r;
                  divergence[0] -= response.hoop_stress / r;
                }
              const double JxW = fe_values.JxW(q) * view.spaces.radial_weight(x);
              residual += divergence.norm_square() * JxW;
              energy +=
                  (scalar_product(response.stress, gradients[q]) + response.hoop_stress * hoop) *
                  JxW;
            }
          const double h = cell->diameter();
          squared[cell->active_cell_index()] +=
              h * h * residual / material_of(cell).youngs_modulus();
        }
    return energy;
  }

  template <int dim>
  void
  ErrorEstimator<dim>::add_jump(const TrilinosWrappers::MPI::Vector &u,
                                const TriaCell                      &a,
                                const FEFaceValuesBase<dim>         &on_a,
                                const std::vector<Tensor<2, dim>>   &gradients_a,
                                const TriaCell                      &b,
                                const std::vector<Tensor<2, dim>>   &gradients_b,
                                const double                         h,
                                Vector<double>                      &squared) const
  {
    // (u continuous: the hoop strain of an axisymmetric model is that of side a)
    std::vector<Tensor<1, dim>> face_u(on_a.n_quadrature_points);
    if (view.axisymmetric)
      on_a[FEValuesExtractors::Vector(0)].get_function_values(u, face_u);
    double jump = 0.;
    for (unsigned int q = 0; q < on_a.n_quadrature_points; ++q)
      {
        const Point<dim> &x    = on_a.quadrature_point(q);
        const double      hoop = view.axisymmetric ? hoop_strain(x, face_u[q], gradients_a[q]) : 0.;
        jump += ((stress_at(a, gradients_a[q], x, hoop) - stress_at(b, gradients_b[q], x, hoop)) *
                 on_a.normal_vector(q))
                    .norm_square() *
                on_a.JxW(q) * view.spaces.radial_weight(x);
      }
    for (const TriaCell &side : {a, b})
      if (side->is_locally_owned())
        squared[side->active_cell_index()] += 0.5 * h * jump / material_of(side).youngs_modulus();
  }

  template <int dim>
  void
  ErrorEstimator<dim>::add_hanging_jump(const TrilinosWrappers::MPI::Vector           &u,
                                        const DoFCell                                 &fine,
                                        const unsigned int                             face,
                                        const typename DoFHandler<dim>::cell_iterator &coarse,
                                        FEFaceValues<dim>                             &fine_values,
                                        Vector<double> &squared) const
  {
    const FEValuesExtractors::Vector displacement(0);
    const unsigned int               n_points = fine_values.n_quadrature_points;
    std::vector<Tensor<2, dim>>      inside(n_points), outside(n_points);
    fine_values.reinit(fine, face);
    fine_values[displacement].get_function_gradients(u, inside);
    const Mapping<dim> &mapping =
        coarse->reference_cell().template get_default_linear_mapping<dim>();
    std::vector<Point<dim>> unit(n_points);
    for (unsigned int q = 0; q < unit.size(); ++q)
      unit[q] = mapping.transform_real_to_unit_cell(coarse, fine_values.quadrature_point(q));
    FEValues<dim> coarse_values(
        mapping, view.displacement_fe, Quadrature<dim>(unit), update_gradients);
    coarse_values.reinit(coarse);
    coarse_values[displacement].get_function_gradients(u, outside);
    add_jump(u, fine, fine_values, inside, coarse, outside, fine->face(face)->diameter(), squared);
  }

  template <int dim>
  void
  ErrorEstimator<dim>::add_face_residuals(const TrilinosWrappers::MPI::Vector &u,
                                          Vector<double>                      &squared)
  {
    const FiniteElement<dim> &fe              = view.displacement_fe;
    const Quadrature<dim - 1> face_quadrature = face_gauss(fe.degree + 1);
    const UpdateFlags flags = update_gradients | update_normal_vectors | update_quadrature_points |
                              update_JxW_values | update_values;
    FEInterfaceValues<dim>      interface(fe, face_quadrature, flags);
    FEFaceValues<dim>           boundary(fe, face_quadrature, flags);
    std::vector<Tensor<2, dim>> inside(face_quadrature.size()), outside(face_quadrature.size());
    const unsigned int          none = numbers::invalid_unsigned_int;

    // ½ h_F ‖⟦P N⟧‖² to each side of an interior face. The jump is the same
    // seen from either side, so it is computed once: by the side of lower
    // index when both cells are this rank's, by the own side when the other is
    // a ghost (whose owner adds its half).
    const auto add_interface_jump = [&](const TriaCell &cell, const double h) {
      const auto &own   = interface.get_fe_face_values(0);
      const auto &other = interface.get_fe_face_values(1);
      own[FEValuesExtractors::Vector(0)].get_function_gradients(u, inside);
      other[FEValuesExtractors::Vector(0)].get_function_gradients(u, outside);
      add_jump(u, cell, own, inside, other.get_cell(), outside, h, squared);
    };
    const auto computes = [](const DoFCell &cell, const DoFCell &neighbor) {
      return !neighbor->is_locally_owned() ||
             cell->active_cell_index() < neighbor->active_cell_index();
    };

    for (const auto &cell : view.displacement_dofs.active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        for (const unsigned int f : cell->face_indices())
          {
            if (cell->face(f)->at_boundary())
              add_boundary_residual(cell, f, u, boundary, squared);
            else if (cell->neighbor(f)->has_children())
              for (unsigned int s = 0; s < cell->face(f)->n_children(); ++s)
                {
                  const auto fine = cell->neighbor_child_on_subface(f, s);
                  if (!computes(cell, fine))
                    continue;
                  if (view.simplex)
                    {
                      for (const unsigned int g : fine->face_indices())
                        if (!fine->face(g)->at_boundary() && fine->neighbor(g) == cell)
                          add_hanging_jump(u, fine, g, cell, boundary, squared);
                      continue;
                    }
                  interface.reinit(cell, f, s, fine, cell->neighbor_of_neighbor(f), none);
                  add_interface_jump(cell, cell->face(f)->child(s)->diameter());
                }
            else if (!computes(cell, cell->neighbor(f)))
              continue;
            else if (cell->neighbor_is_coarser(f) && view.simplex)
              add_hanging_jump(u, cell, f, cell->neighbor(f), boundary, squared);
            else if (cell->neighbor_is_coarser(f))
              {
                const auto [neighbor_face, neighbor_subface] =
                    cell->neighbor_of_coarser_neighbor(f);
                interface.reinit(cell, f, none, cell->neighbor(f), neighbor_face, neighbor_subface);
                add_interface_jump(cell, cell->face(f)->diameter());
              }
            else
              {
                interface.reinit(
                    cell, f, none, cell->neighbor(f), cell->neighbor_of_neighbor(f), none);
                add_interface_jump(cell, cell->face(f)->diameter());
              }
          }
      }
  }

  template <int dim>
  void
  ErrorEstimator<dim>::add_boundary_residual(const DoFCell                       &cell,
                                             const unsigned int                   f,
                                             const TrilinosWrappers::MPI::Vector &u,
                                             FEFaceValues<dim>                   &face_values,
                                             Vector<double>                      &squared) const
  {
    const types::boundary_id id = cell->face(f)->boundary_id();
    // Γc carries the contact terms; the master surface receives the slave's
    // tractions at points it does not hold (no term: doc/formulation.md)
    if (view.contact_boundaries.count(id) > 0 || view.master_boundaries.count(id) > 0)
      return;
    // the prescribed components take any traction: the reactions
    std::vector<bool> free(dim, true);
    for (const auto &condition : view.boundary_conditions)
      condition->hold_components(id, free);
    if (std::none_of(free.begin(), free.end(), [](const bool b) { return b; }))
      return;
    face_values.reinit(cell, f);
    std::vector<Tensor<2, dim>> gradients(face_values.n_quadrature_points);
    std::vector<Tensor<1, dim>> values(face_values.n_quadrature_points);
    face_values[FEValuesExtractors::Vector(0)].get_function_gradients(u, gradients);
    face_values[FEValuesExtractors::Vector(0)].get_function_values(u, values);
    Vector<double> load(dim);
    double         residual = 0.;
    for (unsigned int q = 0; q < face_values.n_quadrature_points; ++q)
      {
        const Point<dim> &x = face_values.quadrature_point(q);
        load                = 0.;
        for (const auto &condition : view.boundary_conditions)
          condition->add_boundary_load(view.boundary_problem, id, x, values[q], load);
        const Tensor<1, dim> traction =
            stress_at(cell, gradients[q], x, hoop_strain(x, values[q], gradients[q])) *
            face_values.normal_vector(q);
        for (unsigned int d = 0; d < dim; ++d)
          if (free[d])
            residual += std::pow(traction[d] - load[d], 2) * face_values.JxW(q) *
                        view.spaces.radial_weight(x);
      }
    squared[cell->active_cell_index()] +=
        cell->face(f)->diameter() * residual / material_of(cell).youngs_modulus();
  }

  template <int dim>
  void
  ErrorEstimator<dim>::add_contact_residuals(const TrilinosWrappers::MPI::Vector &u,
                                             Vector<double>                      &contact) const
  {
    FaceEvaluator<dim>                           evaluator(view.spaces, view.contact_quadrature);
    std::unique_ptr<FEFaceValues<dim>>           face_values;
    const Quadrature<dim - 1>                   *rule = nullptr;
    std::vector<Tensor<2, dim>>                  gradients;
    std::vector<std::pair<unsigned int, double>> face_complementarity;
    const ContactPointLaw<dim>                  &law = view.law;
    for (const auto &face : view.contact.faces())
      {
        if (!face_values || &face.points(view.contact_quadrature) != rule)
          {
            rule        = &face.points(view.contact_quadrature);
            face_values = std::make_unique<FEFaceValues<dim>>(
                view.displacement_fe,
                *rule,
                update_gradients | update_normal_vectors | update_quadrature_points);
          }
        face_values->reinit(face.cell, face.face_no);
        gradients.resize(rule->size());
        (*face_values)[FEValuesExtractors::Vector(0)].get_function_gradients(u, gradients);
        evaluator.reinit(face, view.ghosted_solution);
        const double E        = material_of(face.cell).youngs_modulus();
        const double h        = face.cell->face(face.face_no)->diameter();
        double       residual = 0., gap_terms = 0., complementarity = 0., dissipation = 0.;
        for (unsigned int q = 0; q < evaluator.n_points(); ++q)
          {
            ContactPointState<dim> state = view.contact.point(face, q);
            ContactKinematics<dim> k     = evaluator.kinematics(q);
            law.evaluate_point_state(state, k, PointRefresh());
            const auto           point      = law.point_response(state, k);
            const auto           tangential = point.tangential_traction();
            const double         gap        = state.pairing.gap(k.position);
            const double         lambda     = k.contact_pressure;
            const Tensor<1, dim> applied    = point.normal_traction() * state.pairing.normal +
                                           state.pairing.from_tangential_components(tangential);
            const Point<dim>    &x = face_values->quadrature_point(q);
            const Tensor<1, dim> traction =
                stress_at(
                    face.cell, gradients[q], x, hoop_strain(x, k.displacement, gradients[q])) *
                face_values->normal_vector(q);
            residual += (traction - applied).norm_square() * k.JxW;
            gap_terms += (h / E * std::pow(std::max(-lambda, 0.), 2) +
                          E / h * std::pow(std::max(-gap, 0.), 2)) *
                         k.JxW;
            complementarity += lambda * gap * k.JxW;
            if (law.friction_law_of(state).has_friction())
              {
                const double threshold =
                    law.friction_law_of(state).threshold(law.threshold_pressure(lambda));
                const auto slip = state.pairing.tangential_components(k.step_increment);
                residual += std::pow(std::max(tangential.norm() - threshold, 0.), 2) * k.JxW;
                dissipation += (threshold * slip.norm() + tangential * slip) * k.JxW;
              }
          }
        // ∫(s|Δs| + t_t·Δs) ≥ 0 where the traction obeys the law point by point;
        // with the weighted conditions the law holds per node, and between
        // the nodes a traction beyond s makes it negative (its square root
        // was NaN): its magnitude is the defect
        contact[face.cell->active_cell_index()] +=
            h / E * residual + gap_terms + std::abs(dissipation);
        face_complementarity.emplace_back(face.cell->active_cell_index(), complementarity);
      }
    add_complementarity_shares(face_complementarity, view.communicator, contact);
  }

  template class ErrorEstimator<2>;
  template class ErrorEstimator<3>;

  // --- ContactProblem's part: the view, and the estimates it asks for ---

  template <int dim>
  typename ErrorEstimator<dim>::View
  ContactProblem<dim>::error_estimator_view()
  {
    return typename ErrorEstimator<dim>::View{triangulation,
                                              dof_handler_u,
                                              *fe_u,
                                              cell_quadrature,
                                              contact_quadrature,
                                              spaces,
                                              contact,
                                              ghosted_solution,
                                              law,
                                              chosen.contact_boundaries,
                                              chosen.master_boundaries,
                                              boundary_conditions,
                                              boundary_view(),
                                              mpi_communicator,
                                              body_mesh.cell_shape(),
                                              body_mesh.simplex(),
                                              axisymmetric,
                                              negligible_pressure,
                                              body_response,
                                              material_history};
  }

  template <int dim>
  void
  ContactProblem<dim>::estimate_error(StepStatistics &stats)
  {
    TimerOutput::Scope scope(timer, "error estimate");
    error_indicators =
        ErrorEstimator<dim>(error_estimator_view()).estimate(ghosted_displacement(), stats);
  }

  template <int dim>
  EnergyEstimate
  ContactProblem<dim>::estimated_energy_error()
  {
    TimerOutput::Scope scope(timer, "error estimate");
    return ErrorEstimator<dim>(error_estimator_view()).energy_estimate(ghosted_displacement());
  }

  // Explicit instantiation of the members defined in this file (the class
  // itself is instantiated once, in contact_problem.cc).
#define SL_INSTANTIATE(dim)                                                                          \
  template typename ErrorEstimator<dim>::View ContactProblem<dim>::error_estimator_view();           \
  template void                               ContactProblem<dim>::estimate_error(StepStatistics &); \
  template EnergyEstimate                     ContactProblem<dim>::estimated_energy_error();

  SL_INSTANTIATE(2)
  SL_INSTANTIATE(3)
#undef SL_INSTANTIATE
} // namespace StabilizedLagrangian
