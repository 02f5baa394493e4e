#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_interface_values.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>

#include <deal.II/grid/grid_tools.h>

#include <stabilized_lagrangian/contact/contact_edge.h>
#include <stabilized_lagrangian/contact/stabilized_lagrangian.h>
#include <stabilized_lagrangian/solver/contact_problem.h>
#include <stabilized_lagrangian/solver/stress_recovery.h>

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

  template <int dim>
  void
  ContactProblem<dim>::estimate_error(StepStatistics &stats)
  {
    TimerOutput::Scope                  scope(timer, "error estimate");
    const TrilinosWrappers::MPI::Vector u = ghosted_displacement();
    Vector<double> squared(triangulation.n_active_cells()), contact(squared.size());
    double         energy          = residual_indicators(u, squared, contact);
    stats.estimated_pressure_error = pressure_estimate(u);
    error_indicators.reinit(squared.size());
    double total = 0., contact_total = 0.;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const unsigned int k = cell->active_cell_index();
          error_indicators[k]  = std::sqrt(squared[k] + contact[k]);
          total += squared[k] + contact[k];
          contact_total += contact[k];
        }
    total                         = Utilities::MPI::sum(total, mpi_communicator);
    contact_total                 = Utilities::MPI::sum(contact_total, mpi_communicator);
    energy                        = Utilities::MPI::sum(energy, mpi_communicator);
    stats.estimated_error         = std::sqrt(total);
    stats.estimated_contact_error = std::sqrt(contact_total);
    stats.energy_norm             = std::sqrt(std::max(energy, 0.));
  }

  template <int dim>
  typename ContactProblem<dim>::EnergyEstimate
  ContactProblem<dim>::estimated_energy_error()
  {
    TimerOutput::Scope                  scope(timer, "error estimate");
    const TrilinosWrappers::MPI::Vector u = ghosted_displacement();
    Vector<double> squared(triangulation.n_active_cells()), contact(squared.size());
    const double   energy = residual_indicators(u, squared, contact);
    squared += contact;
    EnergyEstimate estimate;
    estimate.error       = std::sqrt(Utilities::MPI::sum(squared.l1_norm(), mpi_communicator));
    estimate.energy_norm = std::sqrt(std::max(Utilities::MPI::sum(energy, mpi_communicator), 0.));
    return estimate;
  }

  template <int dim>
  double
  ContactProblem<dim>::residual_indicators(const TrilinosWrappers::MPI::Vector &u,
                                           Vector<double>                      &squared,
                                           Vector<double>                      &contact)
  {
    share_ghost_history();
    compute_volume_fields(u);
    const double energy = add_volume_residuals(u, squared);
    add_face_residuals(u, squared);
    add_contact_residuals(u, contact);
    return energy;
  }

  template <int dim>
  void
  ContactProblem<dim>::share_ghost_history()
  {
    // the stress of a ghost neighbour depends on its history, which only its
    // owner updates
    const bool has_history = std::any_of(materials.begin(), materials.end(), [](const auto &body) {
      return body.model->n_history() > 0;
    });
    if (!has_history || Utilities::MPI::n_mpi_processes(mpi_communicator) == 1)
      return;
    using CellIterator = typename DoFHandler<dim>::active_cell_iterator;
    GridTools::exchange_cell_data_to_ghosts<std::vector<double>, DoFHandler<dim>>(
        dof_handler_u,
        [this](const CellIterator &cell) {
          return material_history.committed_cell(cell->active_cell_index());
        },
        [this](const CellIterator &cell, const std::vector<double> &values) {
          material_history.set_committed_cell(cell->active_cell_index(), values);
        });
  }

  template <int dim>
  Tensor<2, dim>
  ContactProblem<dim>::stress_at(const typename Triangulation<dim>::cell_iterator &cell,
                                 const Tensor<2, dim>                             &grad_u,
                                 const Point<dim>                                 &point,
                                 const double                                      hoop) const
  {
    // the history lives at the cell's quadrature points: the nearest one's;
    // F-bar and mixed evaluate the kept volume change at the point
    const bool       history = material_of(cell).n_history() > 0;
    const Point<dim> unit    = history || body_of(cell).modified_volume()
                                   ? cell->reference_cell()
                                      .template get_default_linear_mapping<dim>()
                                      .transform_real_to_unit_cell(cell, point)
                                   : Point<dim>();
    unsigned int     nearest = 0;
    if (history)
      for (unsigned int q = 1; q < cell_quadrature.size(); ++q)
        if (cell_quadrature.point(q).distance(unit) < cell_quadrature.point(nearest).distance(unit))
          nearest = q;
    return committed_response(cell, nearest, unit, grad_u, nullptr, hoop).stress;
  }

  template <int dim>
  double
  ContactProblem<dim>::add_volume_residuals(const TrilinosWrappers::MPI::Vector &u,
                                            Vector<double>                      &squared) const
  {
    FEValues<dim>                    fe_values(*fe_u,
                            cell_quadrature,
                            update_gradients | update_hessians | update_JxW_values |
                                update_inverse_jacobians | update_values |
                                update_quadrature_points);
    const FEValuesExtractors::Vector displacement(0);
    std::vector<Tensor<2, dim>>      gradients(cell_quadrature.size());
    std::vector<Tensor<1, dim>>      values(cell_quadrature.size());
    std::vector<Tensor<3, dim>>      hessians(cell_quadrature.size());
    double                           energy = 0.;
    for (const auto &cell : dof_handler_u.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[displacement].get_function_gradients(u, gradients);
          fe_values[displacement].get_function_hessians(u, hessians);
          fe_values[displacement].get_function_values(u, values);
          const Materials::Interface<dim> &material = material_of(cell);
          // mixed on Q2: the kept volume change v̄ = Σ c_a ψ_a varies in the
          // cell, ψ_a = ξ_(a−1) − ξ_c (a ≥ 1)
          const bool varying_volume =
              body_of(cell).modified_volume() && volume_projection(body_of(cell)).n_basis() > 1;
          double residual = 0.;
          for (unsigned int q = 0; q < cell_quadrature.size(); ++q)
            {
              Tensor<2, dim>    d_kept;
              const Point<dim> &x        = fe_values.quadrature_point(q);
              const double      hoop     = hoop_strain(x, values[q], gradients[q]);
              const auto        response = committed_response(cell,
                                                       q,
                                                       cell_quadrature.point(q),
                                                       gradients[q],
                                                       varying_volume ? &d_kept : nullptr,
                                                       hoop);
              // div P = A : ∇∇u (A = ∂P/∂F) + ∂P/∂v̄ ∇v̄, no body force
              Tensor<1, dim> divergence;
              for (unsigned int i = 0; i < dim; ++i)
                for (unsigned int j = 0; j < dim; ++j)
                  for (unsigned int k = 0; k < dim; ++k)
                    for (unsigned int l = 0; l < dim; ++l)
                      divergence[i] += response.tangent[i][j][k][l] * hessians[q][k][l][j];
              if (varying_volume)
                {
                  const auto    &coefficients = kept_volume_coefficients[cell->active_cell_index()];
                  Tensor<1, dim> grad_kept;
                  for (unsigned int a = 1; a <= dim; ++a)
                    for (unsigned int j = 0; j < dim; ++j)
                      grad_kept[j] += coefficients[a] * fe_values.inverse_jacobian(q)[a - 1][j];
                  divergence += d_kept * grad_kept;
                }
              if (axisymmetric)
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
              const double JxW = fe_values.JxW(q) * radial_weight(x);
              residual += divergence.norm_square() * JxW;
              energy +=
                  (scalar_product(response.stress, gradients[q]) + response.hoop_stress * hoop) *
                  JxW;
            }
          const double h = cell->diameter();
          squared[cell->active_cell_index()] += h * h * residual / material.youngs_modulus();
        }
    return energy;
  }

  template <int dim>
  void
  ContactProblem<dim>::add_face_residuals(const TrilinosWrappers::MPI::Vector &u,
                                          Vector<double>                      &squared)
  {
    const Quadrature<dim - 1> face_quadrature = face_gauss(fe_u->degree + 1);
    const UpdateFlags         flags =
        update_gradients | update_normal_vectors | update_quadrature_points | update_JxW_values;
    FEInterfaceValues<dim>           interface(*fe_u, face_quadrature, flags | update_values);
    FEFaceValues<dim>                boundary(*fe_u, face_quadrature, flags | update_values);
    const FEValuesExtractors::Vector displacement(0);
    std::vector<Tensor<2, dim>> inside(face_quadrature.size()), outside(face_quadrature.size());
    std::vector<Tensor<1, dim>> face_u(face_quadrature.size());
    const unsigned int          none = numbers::invalid_unsigned_int;

    // ½ h_F ‖⟦P N⟧‖² to each side of an interior face. The jump is the same
    // seen from either side, so it is computed once: by the side of lower
    // index when both cells are this rank's, by the own side when the other is
    // a ghost (whose owner adds its half).
    using TriaCell = typename Triangulation<dim>::cell_iterator;
    // (u continuous: the hoop strain of an axisymmetric model is that of side a)
    const auto add_jump = [&](const TriaCell                    &a,
                              const FEFaceValuesBase<dim>       &on_a,
                              const std::vector<Tensor<2, dim>> &gradients_a,
                              const TriaCell                    &b,
                              const std::vector<Tensor<2, dim>> &gradients_b,
                              const double                       h) {
      double jump = 0.;
      if (axisymmetric)
        on_a[displacement].get_function_values(u, face_u);
      for (unsigned int q = 0; q < on_a.n_quadrature_points; ++q)
        {
          const Point<dim> &x    = on_a.quadrature_point(q);
          const double      hoop = axisymmetric ? hoop_strain(x, face_u[q], gradients_a[q]) : 0.;
          jump += ((stress_at(a, gradients_a[q], x, hoop) - stress_at(b, gradients_b[q], x, hoop)) *
                   on_a.normal_vector(q))
                      .norm_square() *
                  on_a.JxW(q) * radial_weight(x);
        }
      for (const TriaCell &side : {a, b})
        if (side->is_locally_owned())
          squared[side->active_cell_index()] += 0.5 * h * jump / material_of(side).youngs_modulus();
    };
    const auto add_interface_jump = [&](const TriaCell &cell, const double h) {
      const auto &own   = interface.get_fe_face_values(0);
      const auto &other = interface.get_fe_face_values(1);
      own[displacement].get_function_gradients(u, inside);
      other[displacement].get_function_gradients(u, outside);
      add_jump(cell, own, inside, other.get_cell(), outside, h);
    };
    // Simplex meshes (deal.II 9.4 has no FESubfaceValues for them): across a
    // hanging face, the fine side's face rule, and the coarse side's gradients
    // at the same points through its inverse mapping.
    const auto add_hanging_jump = [&](const typename DoFHandler<dim>::active_cell_iterator &fine,
                                      const unsigned int                                    face,
                                      const typename DoFHandler<dim>::cell_iterator &coarse) {
      boundary.reinit(fine, face);
      boundary[displacement].get_function_gradients(u, inside);
      const Mapping<dim> &mapping =
          coarse->reference_cell().template get_default_linear_mapping<dim>();
      std::vector<Point<dim>> unit(face_quadrature.size());
      for (unsigned int q = 0; q < unit.size(); ++q)
        unit[q] = mapping.transform_real_to_unit_cell(coarse, boundary.quadrature_point(q));
      FEValues<dim> coarse_values(mapping, *fe_u, Quadrature<dim>(unit), update_gradients);
      coarse_values.reinit(coarse);
      coarse_values[displacement].get_function_gradients(u, outside);
      add_jump(fine, boundary, inside, coarse, outside, fine->face(face)->diameter());
    };
    const auto computes = [](const typename DoFHandler<dim>::active_cell_iterator &cell,
                             const typename DoFHandler<dim>::active_cell_iterator &neighbor) {
      return !neighbor->is_locally_owned() ||
             cell->active_cell_index() < neighbor->active_cell_index();
    };

    for (const auto &cell : dof_handler_u.active_cell_iterators())
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
                  if (simplex_mesh())
                    {
                      for (const unsigned int g : fine->face_indices())
                        if (!fine->face(g)->at_boundary() && fine->neighbor(g) == cell)
                          add_hanging_jump(fine, g, cell);
                      continue;
                    }
                  interface.reinit(cell, f, s, fine, cell->neighbor_of_neighbor(f), none);
                  add_interface_jump(cell, cell->face(f)->child(s)->diameter());
                }
            else if (cell->neighbor_is_coarser(f))
              {
                if (!computes(cell, cell->neighbor(f)))
                  continue;
                if (simplex_mesh())
                  {
                    add_hanging_jump(cell, f, cell->neighbor(f));
                    continue;
                  }
                const auto [neighbor_face, neighbor_subface] =
                    cell->neighbor_of_coarser_neighbor(f);
                interface.reinit(cell, f, none, cell->neighbor(f), neighbor_face, neighbor_subface);
                add_interface_jump(cell, cell->face(f)->diameter());
              }
            else
              {
                if (!computes(cell, cell->neighbor(f)))
                  continue;
                interface.reinit(
                    cell, f, none, cell->neighbor(f), cell->neighbor_of_neighbor(f), none);
                add_interface_jump(cell, cell->face(f)->diameter());
              }
          }
      }
  }

  template <int dim>
  void
  ContactProblem<dim>::add_boundary_residual(
      const typename DoFHandler<dim>::active_cell_iterator &cell,
      const unsigned int                                    f,
      const TrilinosWrappers::MPI::Vector                  &u,
      FEFaceValues<dim>                                    &face_values,
      Vector<double>                                       &squared)
  {
    const types::boundary_id id = cell->face(f)->boundary_id();
    // Γc carries the contact terms; the master surface receives the slave's
    // tractions at points it does not hold (no term: doc/formulation.md)
    if (chosen.contact_boundaries.count(id) > 0 || chosen.master_boundaries.count(id) > 0)
      return;
    // the prescribed components take any traction: the reactions
    std::vector<bool> free(dim, true);
    for (const auto &condition : boundary_conditions)
      condition->hold_components(id, free);
    if (std::none_of(free.begin(), free.end(), [](const bool b) { return b; }))
      return;
    face_values.reinit(cell, f);
    std::vector<Tensor<2, dim>> gradients(face_values.n_quadrature_points);
    std::vector<Tensor<1, dim>> values(face_values.n_quadrature_points);
    face_values[FEValuesExtractors::Vector(0)].get_function_gradients(u, gradients);
    face_values[FEValuesExtractors::Vector(0)].get_function_values(u, values);
    const BoundaryConditions::Problem<dim> problem = boundary_view();
    Vector<double>                         load(dim);
    double                                 residual = 0.;
    for (unsigned int q = 0; q < face_values.n_quadrature_points; ++q)
      {
        const Point<dim> &x = face_values.quadrature_point(q);
        load                = 0.;
        for (const auto &condition : boundary_conditions)
          condition->add_boundary_load(problem, id, x, values[q], load);
        const Tensor<1, dim> traction =
            stress_at(cell, gradients[q], x, hoop_strain(x, values[q], gradients[q])) *
            face_values.normal_vector(q);
        for (unsigned int d = 0; d < dim; ++d)
          if (free[d])
            residual += std::pow(traction[d] - load[d], 2) * face_values.JxW(q) * radial_weight(x);
      }
    squared[cell->active_cell_index()] +=
        cell->face(f)->diameter() * residual / material_of(cell).youngs_modulus();
  }

  template <int dim>
  void
  ContactProblem<dim>::add_contact_residuals(const TrilinosWrappers::MPI::Vector &u,
                                             Vector<double>                      &contact)
  {
    FaceEvaluator                                evaluator(spaces, contact_quadrature);
    std::unique_ptr<FEFaceValues<dim>>           face_values;
    const Quadrature<dim - 1>                   *rule = nullptr;
    std::vector<Tensor<2, dim>>                  gradients;
    std::vector<std::pair<unsigned int, double>> face_complementarity;
    for (const auto &face : contact_faces)
      {
        if (!face_values || &face_quadrature(face) != rule)
          {
            rule        = &face_quadrature(face);
            face_values = std::make_unique<FEFaceValues<dim>>(
                *fe_u, *rule, update_gradients | update_normal_vectors | update_quadrature_points);
          }
        face_values->reinit(face.cell, face.face_no);
        gradients.resize(rule->size());
        (*face_values)[FEValuesExtractors::Vector(0)].get_function_gradients(u, gradients);
        evaluator.reinit(face, ghosted_solution);
        const double E        = material_of(face.cell).youngs_modulus();
        const double h        = face.cell->face(face.face_no)->diameter();
        double       residual = 0., gap_terms = 0., complementarity = 0., dissipation = 0.;
        for (unsigned int q = 0; q < evaluator.n_points(); ++q)
          {
            ContactPointState<dim> state = contact_states[face.first_point + q];
            ContactKinematics<dim> k     = evaluator.kinematics(q);
            evaluate_point_state(state, k, PointRefresh());
            const auto           point      = point_response(state, k);
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
            if (friction_law_of(state).has_friction())
              {
                const double threshold =
                    friction_law_of(state).threshold(threshold_pressure(lambda));
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
    // The complementarity enters as the global |∫_Γc λ_n g_n| (Hild and
    // Nicaise 2007): the weak non-penetration ∫ψ_j g_n = 0 makes it cancel
    // over the patch of each multiplier node, while a face's own ∫_F λ_n g_n
    // (with the O(h²) gap between the nodes of a quadratic face) stays of
    // order h and would make the estimate decay more slowly than the error.
    // Each face takes the share of its own |∫_F λ_n g_n|.
    double signed_total = 0., absolute_total = 0.;
    for (const auto &[cell, value] : face_complementarity)
      {
        signed_total += value;
        absolute_total += std::abs(value);
      }
    signed_total   = Utilities::MPI::sum(signed_total, mpi_communicator);
    absolute_total = Utilities::MPI::sum(absolute_total, mpi_communicator);
    if (absolute_total > 0.)
      for (const auto &[cell, value] : face_complementarity)
        contact[cell] += std::abs(signed_total) * std::abs(value) / absolute_total;
  }

  template <int dim>
  double
  ContactProblem<dim>::pressure_estimate(const TrilinosWrappers::MPI::Vector &u) const
  {
    // ‖p* − λ_n‖ / ‖λ_n‖ on Γc, p* = −N·P*N from the recovered stress P*,
    // with a Gauss rule two orders above the pair's on each face: between
    // the nodes is where a linear λ_n departs most from a curved pressure
    const Quadrature<dim - 1> rule = face_gauss(fe_u->degree + 2);
    FaceEvaluator             evaluator(spaces, rule, false);
    FEFaceValues<dim> face_values(*fe_u, rule, update_normal_vectors | update_quadrature_points);
    // (on simplices the Gauss points of the same order: the centroid for P1)
    const Quadrature<dim> barlow = cell_gauss(fe_u->degree);
    FEValues<dim>         barlow_values(
        *fe_u, barlow, update_values | update_gradients | update_quadrature_points);
    std::vector<Tensor<2, dim>> gradients(barlow.size());
    std::vector<Tensor<1, dim>> values(barlow.size());
    StressRecovery<dim>         recovery(dof_handler_u, fe_u->degree, [&](const auto &cell) {
      barlow_values.reinit(cell);
      barlow_values[FEValuesExtractors::Vector(0)].get_function_gradients(u, gradients);
      barlow_values[FEValuesExtractors::Vector(0)].get_function_values(u, values);
      std::vector<std::pair<Point<dim>, Tensor<2, dim>>> samples;
      for (unsigned int q = 0; q < barlow.size(); ++q)
        {
          const Point<dim> &x = barlow_values.quadrature_point(q);
          samples.emplace_back(
              x, stress_at(cell, gradients[q], x, hoop_strain(x, values[q], gradients[q])));
        }
      return samples;
    });
    // the faces that hold the end of the contact zone: the square-root onset
    // fitted to their contact points, integrated finely across its kink
    FaceEvaluator nodes(spaces, contact_quadrature);
    // (the finest simplex rule on triangle faces)
    const Quadrature<dim - 1> edge_rule =
        (dim == 3 && simplex_mesh())
            ? face_gauss(4)
            : Quadrature<dim - 1>(QIterated<dim - 1>(QGauss<1>(2), dim == 2 ? 16 : 8));
    FaceEvaluator     edge_evaluator(spaces, edge_rule, false);
    FEFaceValues<dim> edge_values(*fe_u, edge_rule, update_quadrature_points);
    const double      master_compliance = deformable_master_compliance();
    double            mismatch = 0., norm = 0., area = 0.;
    // the mismatch at the points of a face evaluator against a pressure
    const auto add_mismatch = [&](const FaceEvaluator &at, const auto &pressure) {
      for (unsigned int q = 0; q < at.n_points(); ++q)
        {
          const ContactKinematics<dim> k = at.kinematics(q);
          mismatch += std::pow(pressure(q) - k.contact_pressure, 2) * k.JxW;
          norm += k.contact_pressure * k.contact_pressure * k.JxW;
          area += k.JxW;
        }
    };
    for (const auto &face : contact_faces)
      {
        face_values.reinit(face.cell, face.face_no);
        Tensor<1, dim> normal;
        for (unsigned int q = 0; q < rule.size(); ++q)
          normal += face_values.normal_vector(q);
        normal /= normal.norm();
        const Contact::SquareRootOnset<dim> onset =
            square_root_onset(face, nodes, normal, master_compliance);
        if (onset.valid())
          {
            edge_values.reinit(face.cell, face.face_no);
            edge_evaluator.reinit(face, ghosted_solution);
            add_mismatch(edge_evaluator, [&](const unsigned int q) {
              return onset.pressure(edge_values.quadrature_point(q));
            });
          }
        else
          {
            evaluator.reinit(face, ghosted_solution);
            const auto recovered =
                recovery.at(face.cell, face.face_no, normal, face_values.get_quadrature_points());
            add_mismatch(evaluator, [&](const unsigned int q) {
              const Tensor<1, dim> &N = face_values.normal_vector(q);
              return -(recovered[q] * N) * N;
            });
          }
      }
    mismatch = Utilities::MPI::sum(mismatch, mpi_communicator);
    norm     = Utilities::MPI::sum(norm, mpi_communicator);
    area     = Utilities::MPI::sum(area, mpi_communicator);
    // Without contact λ_n is round-off (a pressure below negligible_pressure
    // everywhere), and a ratio of round-offs is no error estimate: it read
    // 5e145 on a scene that never touched. Nothing is estimated then (0).
    return norm > negligible_pressure * negligible_pressure * area ? std::sqrt(mismatch / norm)
                                                                   : 0.;
  }

  template <int dim>
  Contact::SquareRootOnset<dim>
  ContactProblem<dim>::square_root_onset(const ContactFace    &face,
                                         FaceEvaluator        &nodes,
                                         const Tensor<1, dim> &normal,
                                         const double          master_compliance) const
  {
    const unsigned int n_points     = face_quadrature(face).size();
    const auto         state        = contact_states.begin() + face.first_point;
    const auto         n_in_contact = static_cast<unsigned int>(
        std::count_if(state, state + n_points, [](const auto &s) { return s.in_contact; }));
    // a face all in contact or all open holds no end of the contact zone
    if (n_in_contact == 0 || n_in_contact == n_points)
      return Contact::SquareRootOnset<dim>();
    std::vector<Point<dim>> points(n_points);
    std::vector<bool>       in_contact(n_points);
    std::vector<double>     pressures(n_points), gaps(n_points);
    bool                    deformable = false;
    nodes.reinit(face, ghosted_solution);
    for (unsigned int q = 0; q < n_points; ++q)
      {
        const ContactPointState<dim> &state = contact_states[face.first_point + q];
        const ContactKinematics<dim>  k     = nodes.kinematics(q);
        points[q]                           = k.position - k.displacement;
        in_contact[q]                       = state.in_contact;
        pressures[q]                        = k.contact_pressure;
        gaps[q]                             = state.pairing.gap(k.position);
        deformable                          = deformable || state.pairing.master_face >= 0;
      }
    const Materials::Interface<dim> &material = material_of(face.cell);
    const double                     compliance =
        (1. - std::pow(material.poissons_ratio(), 2)) / material.youngs_modulus() +
        (deformable ? master_compliance : 0.);
    return Contact::SquareRootOnset<dim>(
        points, in_contact, pressures, gaps, normal, 1. / compliance);
  }

  template <int dim>
  double
  ContactProblem<dim>::deformable_master_compliance() const
  {
    // (1 − ν²)/E of the body that holds the master surface, 0 without one
    double compliance = 0.;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary() &&
              chosen.master_boundaries.count(cell->face(f)->boundary_id()) > 0)
            {
              const Materials::Interface<dim> &material = material_of(cell);
              compliance                                = std::max(compliance,
                                    (1. - std::pow(material.poissons_ratio(), 2)) /
                                        material.youngs_modulus());
            }
    return Utilities::MPI::max(compliance, mpi_communicator);
  }

  // Explicit instantiation of the members defined in this file (the class
  // itself is instantiated once, in contact_problem.cc).
#define SL_INSTANTIATE(dim)                                                                         \
  template void ContactProblem<dim>::estimate_error(StepStatistics &);                              \
  template typename ContactProblem<dim>::EnergyEstimate                                             \
                  ContactProblem<dim>::estimated_energy_error();                                    \
  template double ContactProblem<dim>::residual_indicators(                                         \
      const TrilinosWrappers::MPI::Vector &, Vector<double> &, Vector<double> &);                   \
  template void   ContactProblem<dim>::share_ghost_history();                                       \
  template double ContactProblem<dim>::add_volume_residuals(const TrilinosWrappers::MPI::Vector &,  \
                                                            Vector<double> &) const;                \
  template void   ContactProblem<dim>::add_face_residuals(const TrilinosWrappers::MPI::Vector &,    \
                                                        Vector<double> &);                        \
  template void   ContactProblem<dim>::add_contact_residuals(const TrilinosWrappers::MPI::Vector &, \
                                                           Vector<double> &);                     \
  template double ContactProblem<dim>::pressure_estimate(const TrilinosWrappers::MPI::Vector &)     \
      const;                                                                                        \
  template Tensor<2, dim> ContactProblem<dim>::stress_at(                                           \
      const typename Triangulation<dim>::cell_iterator &,                                           \
      const Tensor<2, dim> &,                                                                       \
      const Point<dim> &,                                                                           \
      double) const;                                                                                \
  template void ContactProblem<dim>::add_boundary_residual(                                         \
      const typename DoFHandler<dim>::active_cell_iterator &,                                       \
      unsigned int,                                                                                 \
      const TrilinosWrappers::MPI::Vector &,                                                        \
      FEFaceValues<dim> &,                                                                          \
      Vector<double> &);

  SL_INSTANTIATE(2)
  SL_INSTANTIATE(3)
#undef SL_INSTANTIATE
} // namespace StabilizedLagrangian
