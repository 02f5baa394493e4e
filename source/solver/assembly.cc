#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <stabilized_lagrangian/solver/contact_problem.h>

#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <sstream>

namespace StabilizedLagrangian
{
  namespace
  {
    /**
     * The floor of the force scale of the scaled Newton criterion, as a fraction
     * of the force E h^(dim−2) U that displaces a node of a cell by the largest
     * displacement U: the residual's round-off is about 1e-16–1e-14 of that
     * force, so with the default tolerance 1e-8 the criterion stays two orders
     * above round-off even when the body does not deform.
     */
    constexpr double force_scale_floor = 1e-4;

    /**
     * The local system of one contact face (doc/formulation.md, "Two deformable
     * bodies"): its unknowns are the slave cell's displacement DoFs, then the
     * DoFs of the partner's faces paired with the face's points (none for a
     * rigid obstacle; their shape functions enter with a minus sign: the gap
     * is (x¹ − x²(ξ))·n), then the face's multipliers.
     */
    template <int dim> struct ContactFaceSystem
    {
      ContactFaceSystem(const FiniteElement<dim> &fe_u, const FiniteElement<dim> &fe_m)
          : fe_m(fe_m)
          , n_u_cell(fe_u.n_dofs_per_cell())
          , u_component(n_u_cell)
      {
        for (unsigned int i = 0; i < n_u_cell; ++i)
          u_component[i] = fe_u.system_to_component_index(i).first;
      }

      /** Start a face: its cell's displacement DoFs and its multipliers. */
      void
      reinit(const std::vector<types::global_dof_index> &u_dofs,
             const std::vector<types::global_dof_index> &face_m_dofs,
             const std::vector<unsigned int>            &face_m_local)
      {
        dofs    = u_dofs;
        m_dofs  = face_m_dofs;
        m_local = face_m_local;
        n_m     = m_dofs.size();
        partner_position.clear();
        face_partner_dofs.clear();
        m_component.resize(n_m);
        for (unsigned int a = 0; a < n_m; ++a)
          m_component[a] = fe_m.system_to_component_index(m_local[a]).first;
        psi.resize(n_m);
      }

      /** Add the partner's DoFs of a point's pairing, once each. */
      void
      add_partner_dofs(const Contact::Partner<dim> &partner, const Contact::Pairing<dim> &pairing)
      {
        for (const auto dof : partner.pairing_dof_indices(pairing))
          if (partner_position.emplace(dof, n_u_cell + face_partner_dofs.size()).second)
            face_partner_dofs.push_back(dof);
      }

      /** Size the system once the partner's DoFs are known. */
      void
      finish_dofs()
      {
        n_d                  = n_u_cell + face_partner_dofs.size();
        const unsigned int n = n_d + n_m;
        matrix.reinit(n, n);
        rhs.reinit(n);
        length_weights.reinit(n);
        dofs.insert(dofs.end(), face_partner_dofs.begin(), face_partner_dofs.end());
        dofs.insert(dofs.end(), m_dofs.begin(), m_dofs.end());
        phi.resize(n_d);
        normal_shape.resize(n_d);
        tangential_shape.resize(n_d);
        slip_derivative.resize(n_d);
      }

      /**
       * The shape functions at point @p q: φ_j of the displacements (slave,
       * then partner), φ_j·n, t_α·φ_j, ∂Δs/∂u_j (plus (∂t_α/∂x φ_j)·Δu when
       * the tangents turn: @p step_increment given), and ψ of the multipliers.
       */
      void
      set_shapes(const FEFaceValues<dim>     &u_values,
                 const FEFaceValues<dim>     &m_values,
                 const unsigned int           q,
                 const Contact::Partner<dim> &partner,
                 const Contact::Pairing<dim> &pairing,
                 const Tensor<1, dim>        *step_increment)
      {
        for (unsigned int i = 0; i < n_d; ++i)
          phi[i] = Tensor<1, dim>();
        for (unsigned int i = 0; i < n_u_cell; ++i)
          phi[i][u_component[i]] = u_values.shape_value(i, q);
        partner.shape_values(pairing, partner_dofs, partner_components, partner_values);
        for (unsigned int r = 0; r < partner_dofs.size(); ++r)
          phi[partner_position[partner_dofs[r]]][partner_components[r]] -= partner_values[r];
        for (unsigned int i = 0; i < n_d; ++i)
          {
            normal_shape[i]     = phi[i] * pairing.normal;
            tangential_shape[i] = pairing.tangential_components(phi[i]);
            slip_derivative[i]  = tangential_shape[i];
            if (step_increment)
              for (unsigned int a = 0; a < dim - 1; ++a)
                slip_derivative[i][a] += (pairing.tangent_gradients[a] * phi[i]) * *step_increment;
          }
        for (unsigned int a = 0; a < n_m; ++a)
          psi[a] = m_values.shape_value(m_local[a], q);
      }

      /**
       * The point's residual: the slave's tractions do work against δu¹, the
       * partner's (opposite) against δu²(ξ); the multiplier rows of seed eq. (5).
       */
      void
      add_residual(const Contact::PointResponse<dim - 1> &point, const double w)
      {
        const double             normal_traction     = point.normal_traction();
        const Tensor<1, dim - 1> tangential_traction = point.tangential_traction();
        const double             pressure_residual   = point.pressure_residual();
        const Tensor<1, dim - 1> semi_residual       = point.semi_multiplier_residual();
        for (unsigned int i = 0; i < n_d; ++i)
          rhs(i) -=
              w * (normal_traction * normal_shape[i] + tangential_traction * tangential_shape[i]);
        for (unsigned int a = 0; a < n_m; ++a)
          {
            rhs(n_d + a) +=
                w * psi[a] *
                (m_component[a] == 0 ? pressure_residual : semi_residual[m_component[a] - 1]);
            length_weights(n_d + a) +=
                w * psi[a] * (m_component[a] == 0 ? 1. : point.semi_multiplier_weight());
          }
      }

      /** The point's Jacobian: matrix(i, j) = ∂ rhs(i) / ∂ x_j. */
      void
      add_jacobian(const Contact::PointResponse<dim - 1> &point,
                   const Contact::Pairing<dim>           &pairing,
                   const double                           w,
                   const bool                             linearise_geometry)
      {
        const double             normal_stiffness     = point.normal_stiffness();
        const Tensor<2, dim - 1> tangential_stiffness = point.tangential_stiffness();
        const double             normal_traction      = point.normal_traction();
        const Tensor<1, dim - 1> tangential_traction  = point.tangential_traction();
        for (unsigned int i = 0; i < n_d; ++i)
          for (unsigned int j = 0; j < n_d; ++j)
            {
              double value = normal_stiffness * normal_shape[i] * normal_shape[j] +
                             tangential_shape[i] * (tangential_stiffness * slip_derivative[j]);
              if (linearise_geometry)
                {
                  // the traction vector turns with n and t_α
                  value -= normal_traction * (phi[i] * (pairing.normal_gradient * phi[j]));
                  for (unsigned int a = 0; a < dim - 1; ++a)
                    value -=
                        tangential_traction[a] * (phi[i] * (pairing.tangent_gradients[a] * phi[j]));
                }
              matrix(i, j) += w * value;
            }
        add_multiplier_blocks(point, w);
      }

      /**
       * The displacement–multiplier couplings and the multiplier block. ∂T/∂λ_n
       * comes from the linearised threshold. The Λ rows keep their weight s/r_t
       * fixed at the iterate (doc/formulation.md): the derivative of the weight,
       * (s'/r_t)(Λ − P_B(ĝ)), vanishes at the solution and, large away from it
       * when r_t is small, only spoils the Newton steps.
       */
      void
      add_multiplier_blocks(const Contact::PointResponse<dim - 1> &point, const double w)
      {
        const double             pressure_coupling   = point.pressure_coupling();
        const Tensor<2, dim - 1> friction_coupling   = point.friction_coupling();
        const double             pressure_compliance = point.pressure_compliance();
        const Tensor<2, dim - 1> semi_block          = point.semi_multiplier_block();
        const Tensor<1, dim - 1> traction_slope = point.tangential_traction_pressure_derivative();
        for (unsigned int i = 0; i < n_d; ++i)
          for (unsigned int b = 0; b < n_m; ++b)
            {
              const unsigned int c = m_component[b];
              // u rows, multiplier columns
              matrix(i, n_d + b) += w * psi[b] *
                                    (c == 0 ? pressure_coupling * normal_shape[i] -
                                                  traction_slope * tangential_shape[i]
                                            : tangential_shape[i] * friction_coupling[c - 1]);
              // multiplier rows, u columns
              matrix(n_d + b, i) += w * psi[b] *
                                    (c == 0 ? pressure_coupling * normal_shape[i]
                                            : friction_coupling[c - 1] * slip_derivative[i]);
            }
        for (unsigned int a = 0; a < n_m; ++a)
          for (unsigned int b = 0; b < n_m; ++b)
            {
              const unsigned int ca = m_component[a], cb = m_component[b];
              double             block = 0.;
              if (ca == 0 && cb == 0)
                block = pressure_compliance;
              else if (ca > 0 && cb > 0)
                block = semi_block[ca - 1][cb - 1];
              matrix(n_d + a, n_d + b) += w * block * psi[a] * psi[b];
            }
      }

      const FiniteElement<dim>                       &fe_m;
      const unsigned int                              n_u_cell;
      unsigned int                                    n_d = 0, n_m = 0;
      std::vector<unsigned int>                       u_component, m_component, m_local;
      std::vector<types::global_dof_index>            dofs, m_dofs, face_partner_dofs;
      std::map<types::global_dof_index, unsigned int> partner_position;
      FullMatrix<double>                              matrix;
      Vector<double>                                  rhs, length_weights;
      // at the current point
      std::vector<Tensor<1, dim>>          phi;
      std::vector<double>                  normal_shape, psi;
      std::vector<Tensor<1, dim - 1>>      tangential_shape, slip_derivative;
      std::vector<types::global_dof_index> partner_dofs;
      std::vector<unsigned int>            partner_components;
      std::vector<double>                  partner_values;
    };
  } // namespace

  template <int dim>
  void
  ContactProblem<dim>::update_ghosts()
  {
    ghosted_solution = solution;
  }

  template <int dim>
  void
  ContactProblem<dim>::assemble_newton_system(const bool assemble_matrix)
  {
    TimerOutput::Scope scope(timer, "assembly");
    ++work.assemblies;
    if (assemble_matrix)
      {
        ++work.jacobians;
        system_matrix = 0.;
      }
    system_rhs                = 0.;
    internal_force            = 0.;
    contact_residual          = 0.;
    external_force            = 0.;
    multiplier_length_weights = 0.;
    inadmissible_state.clear();
    // the deformable master's pairings, folded into the generalized Newton, are
    // refreshed before the assembly: a new pairing may need a new sparsity pattern
    if (loops.pairs_before_assembly())
      update_pairings(false);
    assemble_volume(assemble_matrix);
    for (const auto &bc : boundary_conditions.neumann)
      bc.traction->check_finite(mpi_communicator);
    assemble_contact(assemble_matrix);
    if (assemble_matrix)
      system_matrix.compress(VectorOperation::add);
    system_rhs.compress(VectorOperation::add);
    internal_force.compress(VectorOperation::add);
    contact_residual.compress(VectorOperation::add);
    external_force.compress(VectorOperation::add);
    multiplier_length_weights.compress(VectorOperation::add);
    // every rank learns that one of them met an inadmissible state (the
    // messages are gathered only then)
    if (Utilities::MPI::max(static_cast<int>(!inadmissible_state.empty()), mpi_communicator) == 1)
      for (const auto &message : Utilities::MPI::all_gather(mpi_communicator, inadmissible_state))
        if (!message.empty())
          inadmissible_state = message;
  }

  template <int dim>
  void
  ContactProblem<dim>::assemble_volume(const bool assemble_matrix)
  {
    const FiniteElement<dim> &fe = *fe_u;
    FEValues<dim>             fe_values(fe, cell_quadrature, update_gradients | update_JxW_values);
    // F-bar: the gradient at the cell's centre (the one-point Gauss rule)
    FEValues<dim>      centre_values(fe, cell_gauss(1), update_gradients | update_JxW_values);
    FEFaceValues<dim>  neumann_values(fe,
                                     face_gauss(fe_pair->displacement_degree() + 1),
                                     update_values | update_quadrature_points | update_JxW_values);
    const unsigned int n_dofs = fe.n_dofs_per_cell();
    const unsigned int n_q    = cell_quadrature.size();
    FullMatrix<double> cell_matrix(n_dofs, n_dofs);
    Vector<double>     cell_rhs(n_dofs), cell_external(n_dofs);
    std::vector<types::global_dof_index> dofs(n_dofs);
    std::vector<double>                  coefficients(n_dofs);
    std::vector<unsigned int>            component(n_dofs);
    for (unsigned int i = 0; i < n_dofs; ++i)
      component[i] = fe.system_to_component_index(i).first;
    std::vector<Tensor<2, dim>> tangent_times_grad(n_dofs);
    std::vector<Tensor<2, dim>> sample_gradients; // F-bar and mixed

    for (const auto &cell : dof_handler_u.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          cell->get_dof_indices(dofs);
          for (unsigned int i = 0; i < n_dofs; ++i)
            coefficients[i] = ghosted_solution(dofs[i]);
          const Materials::BodyMaterial<dim> &body = body_of(cell);
          cell_matrix                              = 0.;
          cell_rhs                                 = 0.;
          // F-bar and mixed: the volume change each point keeps, projected
          // from the samples (the centre, or the quadrature points)
          std::optional<Materials::VolumeProjection<dim>> projection;
          const FEValues<dim>                            *samples = nullptr;
          if (body.modified_volume())
            {
              projection.emplace(volume_projection(body));
              if (body.volumetric == Materials::BodyMaterial<dim>::Volumetric::f_bar)
                {
                  centre_values.reinit(cell);
                  samples = &centre_values;
                }
              else
                samples = &fe_values;
              sample_gradients.assign(samples->n_quadrature_points, Tensor<2, dim>());
              for (unsigned int k = 0; k < samples->n_quadrature_points; ++k)
                for (unsigned int i = 0; i < n_dofs; ++i)
                  sample_gradients[k][component[i]] += coefficients[i] * samples->shape_grad(i, k);
              projection->reinit(samples->get_quadrature().get_points(),
                                 samples->get_JxW_values(),
                                 sample_gradients);
            }
          for (unsigned int q = 0; q < n_q; ++q)
            {
              Tensor<2, dim> grad_u;
              for (unsigned int i = 0; i < n_dofs; ++i)
                grad_u[component[i]] += coefficients[i] * fe_values.shape_grad(i, q);
              const Point<dim>        &unit = cell_quadrature.point(q);
              Materials::Response<dim> response;
              Tensor<2, dim>           d_kept; // ∂P̃/∂v̄
              try
                {
                  response =
                      material_response(body,
                                        grad_u,
                                        projection ? projection->value(unit) : 0.,
                                        material_history.committed(cell->active_cell_index(), q),
                                        material_history.trial(cell->active_cell_index(), q),
                                        &d_kept);
                }
              catch (const Materials::InadmissibleState &error)
                {
                  std::ostringstream where;
                  where << error.what() << " (in the cell centred at X = " << cell->center() << ")";
                  inadmissible_state = where.str();
                  return;
                }
              const double JxW = fe_values.JxW(q);
              for (unsigned int i = 0; i < n_dofs; ++i)
                cell_rhs(i) += response.stress[component[i]] * fe_values.shape_grad(i, q) * JxW;
              if (!assemble_matrix)
                continue;
              // A : ∇φ_j, where ∇φ_j has only the row component[j] (with F-bar
              // and mixed also ∂P̃/∂v̄ ⊗ ∂v̄/∂u_j through the samples)
              for (unsigned int j = 0; j < n_dofs; ++j)
                {
                  const Tensor<1, dim> &g = fe_values.shape_grad(j, q);
                  for (unsigned int k = 0; k < dim; ++k)
                    for (unsigned int l = 0; l < dim; ++l)
                      tangent_times_grad[j][k][l] = response.tangent[k][l][component[j]] * g;
                  if (projection)
                    {
                      double kept_derivative = 0.;
                      for (unsigned int k = 0; k < samples->n_quadrature_points; ++k)
                        kept_derivative += projection->sample_weight(unit, k) *
                                           (projection->sample_derivative(k)[component[j]] *
                                            samples->shape_grad(j, k));
                      tangent_times_grad[j] += kept_derivative * d_kept;
                    }
                }
              for (unsigned int i = 0; i < n_dofs; ++i)
                {
                  const Tensor<1, dim> gi = fe_values.shape_grad(i, q) * JxW;
                  for (unsigned int j = 0; j < n_dofs; ++j)
                    cell_matrix(i, j) += tangent_times_grad[j][component[i]] * gi;
                }
            }

          // the force scale of the scaled Newton criterion: internal forces
          // without the Dirichlet constraints, so their rows hold the reactions
          hanging_constraints.distribute_local_to_global(cell_rhs, dofs, internal_force);
          add_neumann_loads(cell, dofs, neumann_values, cell_rhs, cell_external);
          add_to_global_system(cell_matrix, cell_rhs, dofs, assemble_matrix);
        }
  }

  template <int dim>
  void
  ContactProblem<dim>::compute_volume_fields(const TrilinosWrappers::MPI::Vector &u) const
  {
    if (std::none_of(materials.begin(), materials.end(), [](const auto &body) {
          return body.modified_volume();
        }))
      return;
    FEValues<dim> centre_values(*fe_u, cell_gauss(1), update_gradients | update_JxW_values);
    FEValues<dim> cell_values(*fe_u, cell_quadrature, update_gradients | update_JxW_values);
    const FEValuesExtractors::Vector displacement(0);
    std::vector<Tensor<2, dim>>      gradients(cell_quadrature.size()), centre(1);
    centre_gradients.assign(triangulation.n_active_cells(), Tensor<2, dim>());
    kept_volume_coefficients.assign(triangulation.n_active_cells(), {});
    for (const auto &cell : dof_handler_u.active_cell_iterators())
      if (!cell->is_artificial())
        {
          const auto &body = body_of(cell);
          if (!body.modified_volume())
            continue;
          centre_values.reinit(cell);
          centre_values[displacement].get_function_gradients(u, centre);
          centre_gradients[cell->active_cell_index()] = centre[0];
          Materials::VolumeProjection<dim> projection = volume_projection(body);
          if (body.volumetric == Materials::BodyMaterial<dim>::Volumetric::f_bar)
            projection.reinit(centre_values.get_quadrature().get_points(),
                              centre_values.get_JxW_values(),
                              centre);
          else
            {
              cell_values.reinit(cell);
              cell_values[displacement].get_function_gradients(u, gradients);
              projection.reinit(
                  cell_quadrature.get_points(), cell_values.get_JxW_values(), gradients);
            }
          kept_volume_coefficients[cell->active_cell_index()] = projection.coefficients();
        }
  }

  template <int dim>
  void
  ContactProblem<dim>::add_neumann_loads(const typename DoFHandler<dim>::active_cell_iterator &cell,
                                         const std::vector<types::global_dof_index>           &dofs,
                                         FEFaceValues<dim> &neumann_values,
                                         Vector<double>    &cell_rhs,
                                         Vector<double>    &cell_external)
  {
    bool loaded = false;
    for (const auto &bc : boundary_conditions.neumann)
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == bc.boundary_id)
          {
            if (!loaded)
              cell_external = cell_rhs;
            loaded = true;
            add_neumann_contribution(cell, f, *bc.traction, neumann_values, cell_rhs);
          }
    if (loaded)
      {
        cell_external -= cell_rhs;
        hanging_constraints.distribute_local_to_global(cell_external, dofs, external_force);
      }
  }

  template <int dim>
  void
  ContactProblem<dim>::add_neumann_contribution(
      const typename DoFHandler<dim>::active_cell_iterator &cell,
      const unsigned int                                    face_no,
      Parameters::BoundaryFunction<dim>                    &traction,
      FEFaceValues<dim>                                    &fe_face_values,
      Vector<double>                                       &cell_rhs) const
  {
    fe_face_values.reinit(cell, face_no);
    traction.set_time(time);
    Vector<double> t(dim);
    for (unsigned int q = 0; q < fe_face_values.n_quadrature_points; ++q)
      {
        traction.vector_value(fe_face_values.quadrature_point(q), t);
        for (unsigned int i = 0; i < fe_u->n_dofs_per_cell(); ++i)
          cell_rhs(i) -= t(fe_u->system_to_component_index(i).first) *
                         fe_face_values.shape_value(i, q) * fe_face_values.JxW(q);
      }
  }

  template <int dim>
  void
  ContactProblem<dim>::assemble_contact(const bool assemble_matrix)
  {
    FaceEvaluator          evaluator(*this, contact_quadrature);
    ContactFaceSystem<dim> local(*fe_u, *fe_m);
    // the generalized Newton's linearised pairing (a plane's does not move; a
    // deformable master's pairing is refreshed before the assembly, not linearised)
    const bool         linearise_geometry = loops.pairing_turns();
    const PointRefresh refresh            = loops.at_iterate();
    for (const auto &face : contact_faces)
      {
        evaluator.reinit(face, ghosted_solution);
        local.reinit(evaluator.u_dofs, evaluator.m_dofs, evaluator.m_local);
        for (unsigned int q = 0; q < evaluator.n_points(); ++q)
          local.add_partner_dofs(*partner, contact_states[face.first_point + q].pairing);
        local.finish_dofs();
        for (unsigned int q = 0; q < evaluator.n_points(); ++q)
          {
            ContactPointState<dim> &state = contact_states[face.first_point + q];
            ContactKinematics<dim>  k     = evaluator.kinematics(q);
            evaluate_point_state(state, k, refresh);
            const auto point = point_response(state, k);
            local.set_shapes(*evaluator.u_values,
                             *evaluator.m_values,
                             q,
                             *partner,
                             state.pairing,
                             linearise_geometry ? &k.step_increment : nullptr);
            local.add_residual(point, k.JxW);
            if (assemble_matrix)
              local.add_jacobian(point, state.pairing, k.JxW, linearise_geometry);
          }
        newton_constraints.distribute_local_to_global(
            local.length_weights, local.dofs, multiplier_length_weights);
        hanging_constraints.distribute_local_to_global(local.rhs, local.dofs, contact_residual);
        add_to_global_system(local.matrix, local.rhs, local.dofs, assemble_matrix);
      }
  }

  template <int dim>
  void
  ContactProblem<dim>::add_to_global_system(const FullMatrix<double> &local_matrix,
                                            Vector<double>           &local_rhs,
                                            const std::vector<types::global_dof_index> &dofs,
                                            const bool assemble_matrix)
  {
    if (!assemble_matrix)
      {
        newton_constraints.distribute_local_to_global(local_rhs, dofs, system_rhs);
        return;
      }
    // Tangent predictor: the residual linearised at u + Δū, R(u) + K Δū, where
    // Δū is the Dirichlet increment of the load step (zero off the Dirichlet
    // boundary), so the first solve carries the boundary motion into the body.
    if (dirichlet_predictor)
      for (unsigned int i = 0; i < dofs.size(); ++i)
        for (unsigned int j = 0; j < dofs.size(); ++j)
          local_rhs(i) += local_matrix(i, j) * dirichlet_increment(dofs[j]);
    newton_constraints.distribute_local_to_global(
        local_matrix, local_rhs, dofs, system_matrix, system_rhs);
  }

  template <int dim>
  double
  ContactProblem<dim>::residual_norm() const
  {
    TrilinosWrappers::MPI::Vector scaled(system_rhs);
    scaled.scale(residual_scaling);
    return scaled.linfty_norm();
  }

  template <int dim>
  ScaledResidual
  ContactProblem<dim>::scaled_residual() const
  {
    // largest: force residual, force scale, gap, slip, displacement
    double largest[5] = {0., 0., 0., 0., 0.};
    for (const auto i : locally_owned_u)
      {
        largest[0] = std::max(largest[0], std::abs(system_rhs(i)));
        largest[1] =
            std::max({largest[1], std::abs(internal_force(i)), std::abs(external_force(i))});
        largest[4] = std::max(largest[4], std::abs(solution(i)));
      }
    for (const auto &[row, component] : owned_multiplier_components)
      if (multiplier_length_weights(row) > 0.)
        {
          double &block = largest[component == 0 ? 2 : 3];
          block = std::max(block, std::abs(system_rhs(row)) / multiplier_length_weights(row));
        }
    Utilities::MPI::max(largest, mpi_communicator, largest);
    // Floor of the force scale: where the body moves without deforming (a
    // rigid motion before contact, a free rotation) the forces are round-off,
    // so forces below those that displace a node of the stiffest, smallest
    // cell by a fraction force_scale_floor of the largest displacement count
    // as zero (doc/formulation.md).
    largest[1] = std::max(largest[1], force_scale_floor * nodal_stiffness * largest[4]);
    // a zero residual is converged even where its scale is zero (a body at rest)
    const auto ratio = [](const double value, const double scale) {
      return value == 0.  ? 0.
             : scale > 0. ? value / scale
                          : std::numeric_limits<double>::infinity();
    };
    return ScaledResidual{ratio(largest[0], largest[1]),
                          ratio(largest[2], largest[4]),
                          ratio(largest[3], largest[4])};
  }

  // Explicit instantiation of the members defined in this file (the class
  // itself is instantiated once, in contact_problem.cc).
#define SL_INSTANTIATE(dim)                                                                       \
  template void ContactProblem<dim>::update_ghosts();                                             \
  template void ContactProblem<dim>::assemble_newton_system(bool);                                \
  template void ContactProblem<dim>::assemble_volume(bool);                                       \
  template void ContactProblem<dim>::compute_volume_fields(const TrilinosWrappers::MPI::Vector &) \
      const;                                                                                      \
  template void ContactProblem<dim>::add_neumann_contribution(                                    \
      const typename DoFHandler<dim>::active_cell_iterator &,                                     \
      unsigned int,                                                                               \
      Parameters::BoundaryFunction<dim> &,                                                        \
      FEFaceValues<dim> &,                                                                        \
      Vector<double> &) const;                                                                    \
  template void ContactProblem<dim>::assemble_contact(bool);                                      \
  template void ContactProblem<dim>::add_neumann_loads(                                           \
      const typename DoFHandler<dim>::active_cell_iterator &,                                     \
      const std::vector<types::global_dof_index> &,                                               \
      FEFaceValues<dim> &,                                                                        \
      Vector<double> &,                                                                           \
      Vector<double> &);                                                                          \
  template void ContactProblem<dim>::add_to_global_system(                                        \
      const FullMatrix<double> &,                                                                 \
      Vector<double> &,                                                                           \
      const std::vector<types::global_dof_index> &,                                               \
      bool);                                                                                      \
  template double         ContactProblem<dim>::residual_norm() const;                             \
  template ScaledResidual ContactProblem<dim>::scaled_residual() const;

  SL_INSTANTIATE(2)
  SL_INSTANTIATE(3)
#undef SL_INSTANTIATE
} // namespace StabilizedLagrangian
