#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <stabilized_lagrangian/solver/contact_face_system.h>
#include <stabilized_lagrangian/solver/contact_problem.h>
#include <stabilized_lagrangian/solver/system_assembler.h>

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
  } // namespace

  /**
   * The work space of the volume assembly of one cell (SystemAssembler::assemble_volume()):
   * the values of the displacement's shape functions, the cell's DoFs and
   * coefficients, and its matrix and residual.
   */
  template <int dim> struct SystemAssembler<dim>::VolumeScratch
  {
    /** @p axisymmetric: the values and points give the hoop strain u_r/r and the weight 2πr */
    VolumeScratch(const FiniteElement<dim>  &fe,
                  const Quadrature<dim>     &cell_quadrature,
                  const Quadrature<dim>     &centre,
                  const Quadrature<dim - 1> &face_quadrature,
                  const bool                 axisymmetric)
        : axisymmetric(axisymmetric)
        , fe_values(fe,
                    cell_quadrature,
                    update_gradients | update_JxW_values |
                        (axisymmetric ? update_values | update_quadrature_points : update_default))
        , centre_values(fe, centre, update_gradients | update_JxW_values)
        , neumann_values(
              fe, face_quadrature, update_values | update_quadrature_points | update_JxW_values)
        , cell_matrix(fe.n_dofs_per_cell(), fe.n_dofs_per_cell())
        , cell_rhs(fe.n_dofs_per_cell())
        , cell_external(fe.n_dofs_per_cell())
        , dofs(fe.n_dofs_per_cell())
        , coefficients(fe.n_dofs_per_cell())
        , component(fe.n_dofs_per_cell())
        , tangent_times_grad(fe.n_dofs_per_cell())
        , hoop_of_shape(fe.n_dofs_per_cell())
        , hoop_times_grad(fe.n_dofs_per_cell())
    {
      for (unsigned int i = 0; i < component.size(); ++i)
        component[i] = fe.system_to_component_index(i).first;
    }

    /** ∇u at quadrature point @p q of the cell. */
    Tensor<2, dim>
    gradient(const unsigned int q) const
    {
      Tensor<2, dim> grad_u;
      for (unsigned int i = 0; i < dofs.size(); ++i)
        grad_u[component[i]] += coefficients[i] * fe_values.shape_grad(i, q);
      return grad_u;
    }

    /** Axisymmetric: the hoop strain u_r/r at @p q, and φ_i,r/r into hoop_of_shape. */
    double
    hoop_strain(const unsigned int q)
    {
      const double radius = fe_values.quadrature_point(q)[0];
      double       hoop   = 0.;
      for (unsigned int i = 0; i < dofs.size(); ++i)
        {
          hoop_of_shape[i] = component[i] == 0 ? fe_values.shape_value(i, q) / radius : 0.;
          hoop += coefficients[i] * hoop_of_shape[i];
        }
      return hoop;
    }

    /**
     * F-bar (@p at_centre) and mixed: the gradients at the samples (the
     * centre, or the quadrature points) into @p projection.
     */
    void
    project_volume(const bool at_centre, Materials::VolumeProjection<dim> &projection)
    {
      samples = at_centre ? &centre_values : &fe_values;
      sample_gradients.assign(samples->n_quadrature_points, Tensor<2, dim>());
      for (unsigned int k = 0; k < samples->n_quadrature_points; ++k)
        for (unsigned int i = 0; i < dofs.size(); ++i)
          sample_gradients[k][component[i]] += coefficients[i] * samples->shape_grad(i, k);
      projection.reinit(
          samples->get_quadrature().get_points(), samples->get_JxW_values(), sample_gradients);
    }

    /** Add P : ∇φ_i (and the hoop stress times φ_i,r/r) at @p q to the residual. */
    void
    add_point_residual(const unsigned int              q,
                       const Materials::Response<dim> &response,
                       const double                    JxW)
    {
      for (unsigned int i = 0; i < dofs.size(); ++i)
        cell_rhs(i) += response.stress[component[i]] * fe_values.shape_grad(i, q) * JxW;
      if (axisymmetric)
        for (unsigned int i = 0; i < dofs.size(); ++i)
          cell_rhs(i) += response.hoop_stress * hoop_of_shape[i] * JxW;
    }

    /**
     * Add ∇φ_i : A : ∇φ_j at @p q (reference point @p unit) to the matrix,
     * with F-bar and mixed (@p projection) also ∂P̃/∂v̄ ⊗ ∂v̄/∂u_j through the
     * samples (@p d_kept = ∂P̃/∂v̄), axisymmetric the hoop rows and columns.
     */
    void
    add_point_tangent(const unsigned int                      q,
                      const Point<dim>                       &unit,
                      const Materials::Response<dim>         &response,
                      const Tensor<2, dim>                   &d_kept,
                      const Materials::VolumeProjection<dim> *projection,
                      const double                            JxW)
    {
      const unsigned int n_dofs = dofs.size();
      // A : ∇φ_j, where ∇φ_j has only the row component[j]
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
                kept_derivative +=
                    projection->sample_weight(unit, k) *
                    (projection->sample_derivative(k)[component[j]] * samples->shape_grad(j, k));
              tangent_times_grad[j] += kept_derivative * d_kept;
            }
          // axisymmetric: ∂P/∂F₃₃ φ_j,r/r, and the hoop row ∂P₃₃/∂F : ∇̃φ_j
          if (axisymmetric)
            {
              tangent_times_grad[j] += hoop_of_shape[j] * response.hoop_column;
              hoop_times_grad[j] =
                  response.hoop_row[component[j]] * g + response.hoop_hoop * hoop_of_shape[j];
            }
        }
      for (unsigned int i = 0; i < n_dofs; ++i)
        {
          const Tensor<1, dim> gi = fe_values.shape_grad(i, q) * JxW;
          for (unsigned int j = 0; j < n_dofs; ++j)
            cell_matrix(i, j) += tangent_times_grad[j][component[i]] * gi;
          if (axisymmetric && hoop_of_shape[i] != 0.)
            for (unsigned int j = 0; j < n_dofs; ++j)
              cell_matrix(i, j) += hoop_of_shape[i] * hoop_times_grad[j] * JxW;
        }
    }

    const bool         axisymmetric;
    FEValues<dim>      fe_values;
    FEValues<dim>      centre_values; ///< F-bar: the gradient at the centre (one-point Gauss)
    FEFaceValues<dim>  neumann_values;
    FullMatrix<double> cell_matrix;
    Vector<double>     cell_rhs, cell_external;
    std::vector<types::global_dof_index> dofs;
    std::vector<double>                  coefficients;
    std::vector<unsigned int>            component;
    std::vector<Tensor<2, dim>>          tangent_times_grad;
    std::vector<double>                  hoop_of_shape, hoop_times_grad; // axisymmetric
    std::vector<Tensor<2, dim>>          sample_gradients;               // F-bar and mixed
    /** F-bar and mixed: the values at the samples (project_volume()) */
    const FEValues<dim> *samples = nullptr;
  };

  template <int dim>
  void
  SystemAssembler<dim>::assemble(const bool assemble_matrix)
  {
    ++view.work.assemblies;
    if (assemble_matrix)
      {
        ++view.work.jacobians;
        view.system_matrix = 0.;
      }
    view.system_rhs                = 0.;
    view.internal_force            = 0.;
    view.contact_residual          = 0.;
    view.external_force            = 0.;
    view.multiplier_length_weights = 0.;
    view.inadmissible_state.clear();
    // the deformable master's pairings, folded into the generalized Newton, are
    // refreshed before the assembly: a new pairing may need a new sparsity pattern
    if (view.loops.pairs_before_assembly())
      view.update_pairings();
    assemble_volume(assemble_matrix);
    for (const auto &condition : view.boundary_conditions)
      condition->check_finite(view.communicator);
    view.obstacle_translation->check_finite(view.communicator);
    if (view.obstacle_rotation)
      view.obstacle_rotation->check_finite(view.communicator);
    assemble_contact(assemble_matrix);
    // the boundary conditions' forces on DoFs (not on faces)
    for (const auto &condition : view.boundary_conditions)
      condition->assemble_global(
          view.boundary_problem, view.newton_constraints, view.system_rhs, view.external_force);
    if (assemble_matrix)
      view.system_matrix.compress(VectorOperation::add);
    view.system_rhs.compress(VectorOperation::add);
    view.internal_force.compress(VectorOperation::add);
    view.contact_residual.compress(VectorOperation::add);
    view.external_force.compress(VectorOperation::add);
    view.multiplier_length_weights.compress(VectorOperation::add);
    // every rank learns that one of them met an inadmissible state (the
    // messages are gathered only then)
    std::string &inadmissible = view.inadmissible_state;
    if (Utilities::MPI::max(static_cast<int>(!inadmissible.empty()), view.communicator) == 1)
      for (const auto &message : Utilities::MPI::all_gather(view.communicator, inadmissible))
        if (!message.empty())
          inadmissible = message;
  }

  template <int dim>
  void
  SystemAssembler<dim>::assemble_volume(const bool assemble_matrix)
  {
    VolumeScratch scratch(view.fe_u,
                          view.cell_quadrature,
                          view.body_mesh.cell_gauss(1),
                          view.body_mesh.face_gauss(view.fe_pair.displacement_degree() + 1),
                          view.axisymmetric);
    for (const auto &cell : view.dof_handler_u.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          scratch.fe_values.reinit(cell);
          cell->get_dof_indices(scratch.dofs);
          for (unsigned int i = 0; i < scratch.dofs.size(); ++i)
            scratch.coefficients[i] = view.ghosted_solution(scratch.dofs[i]);
          if (!add_cell_terms(cell, scratch, assemble_matrix))
            return;
          // the force scale of the scaled Newton criterion: internal forces
          // without the Dirichlet constraints, so their rows hold the reactions
          view.hanging_constraints.distribute_local_to_global(
              scratch.cell_rhs, scratch.dofs, view.internal_force);
          add_boundary_loads(cell, scratch, assemble_matrix);
          add_to_global_system(
              scratch.cell_matrix, scratch.cell_rhs, scratch.dofs, assemble_matrix);
        }
  }

  template <int dim>
  bool
  SystemAssembler<dim>::add_cell_terms(const typename DoFHandler<dim>::active_cell_iterator &cell,
                                       VolumeScratch &scratch,
                                       const bool     assemble_matrix)
  {
    const Quadrature<dim>              &cell_quadrature = view.cell_quadrature;
    const Materials::BodyResponse<dim> &bodies          = view.body_response;
    const FEValues<dim>                &fe_values       = scratch.fe_values;
    const Materials::BodyMaterial<dim> &body            = bodies.body_of(cell);
    scratch.cell_matrix                                 = 0.;
    scratch.cell_rhs                                    = 0.;
    // F-bar and mixed: the volume change each point keeps, projected
    // from the samples (the centre, or the quadrature points)
    std::optional<Materials::VolumeProjection<dim>> projection;
    if (body.modified_volume())
      {
        projection.emplace(bodies.volume_projection(body));
        if (body.volumetric == Materials::BodyMaterial<dim>::Volumetric::f_bar)
          scratch.centre_values.reinit(cell);
        scratch.project_volume(body.volumetric == Materials::BodyMaterial<dim>::Volumetric::f_bar,
                               *projection);
      }
    for (unsigned int q = 0; q < cell_quadrature.size(); ++q)
      {
        const Tensor<2, dim> grad_u = scratch.gradient(q);
        // axisymmetric: φ_i,r / r, the hoop strain of a radial shape function
        const double             hoop = view.axisymmetric ? scratch.hoop_strain(q) : 0.;
        const Point<dim>        &unit = cell_quadrature.point(q);
        Materials::Response<dim> response;
        Tensor<2, dim>           d_kept; // ∂P̃/∂v̄
        try
          {
            response = bodies.material_response(
                body,
                grad_u,
                projection ? projection->value(unit) : 0.,
                view.material_history.committed(cell->active_cell_index(), q),
                view.material_history.trial(cell->active_cell_index(), q),
                &d_kept,
                hoop);
          }
        catch (const Materials::InadmissibleState &error)
          {
            std::ostringstream where;
            where << error.what() << " (in the cell centred at X = " << cell->center() << ")";
            view.inadmissible_state = where.str();
            return false;
          }
        const double JxW =
            fe_values.JxW(q) *
            (view.axisymmetric ? view.spaces.radial_weight(fe_values.quadrature_point(q)) : 1.);
        scratch.add_point_residual(q, response, JxW);
        if (assemble_matrix)
          scratch.add_point_tangent(
              q, unit, response, d_kept, projection ? &*projection : nullptr, JxW);
      }
    return true;
  }

  template <int dim>
  void
  SystemAssembler<dim>::add_boundary_loads(
      const typename DoFHandler<dim>::active_cell_iterator &cell,
      VolumeScratch                                        &scratch,
      const bool                                            assemble_matrix)
  {
    Vector<double> &cell_rhs = scratch.cell_rhs, &cell_external = scratch.cell_external;
    bool            loaded = false;
    for (const unsigned int f : cell->face_indices())
      {
        if (!cell->face(f)->at_boundary())
          continue;
        const types::boundary_id id = cell->face(f)->boundary_id();
        for (const auto &condition : view.boundary_conditions)
          if (condition->acts_on_faces_of(id))
            {
              if (!loaded)
                cell_external = cell_rhs;
              loaded = true;
              condition->assemble_face(view.boundary_problem,
                                       {cell,
                                        f,
                                        scratch.coefficients,
                                        scratch.neumann_values,
                                        scratch.cell_matrix,
                                        cell_rhs,
                                        assemble_matrix});
            }
      }
    if (loaded)
      {
        cell_external -= cell_rhs;
        view.hanging_constraints.distribute_local_to_global(
            cell_external, scratch.dofs, view.external_force);
      }
  }

  template <int dim>
  void
  SystemAssembler<dim>::assemble_contact(const bool assemble_matrix)
  {
    FaceEvaluator<dim>               evaluator(view.spaces, view.contact_quadrature);
    internal::ContactFaceSystem<dim> local(view.fe_u, view.fe_m);
    const Contact::Partner<dim>     &partner    = *view.partner;
    ContactConditions<dim>          &conditions = view.contact.conditions();
    // the generalized Newton's linearised pairing: a curved obstacle's, and a
    // deformable master's (paired anew before the assembly, linearised in it)
    const bool linearise_geometry =
        view.loops.pairing_turns() || view.loops.pairs_before_assembly();
    PointRefresh refresh = view.loops.at_iterate();
    // what the conditions do not refresh themselves, each point refreshes
    refresh = conditions.prepare_assembly(refresh);
    for (const auto &face : view.contact.faces())
      {
        evaluator.reinit(face, view.ghosted_solution);
        local.reinit(evaluator.u_dofs, evaluator.m_dofs, evaluator.m_local);
        for (unsigned int q = 0; q < evaluator.n_points(); ++q)
          local.add_partner_dofs(partner, view.contact.point(face, q).pairing);
        local.finish_dofs();
        conditions.reinit_face(evaluator);
        for (unsigned int q = 0; q < evaluator.n_points(); ++q)
          {
            ContactPointState<dim> &state = view.contact.point(face, q);
            ContactKinematics<dim>  k     = evaluator.kinematics(q);
            view.law.evaluate_point_state(state, k, refresh);
            local.set_shapes(*evaluator.u_values,
                             evaluator.multiplier_shapes(),
                             q,
                             partner,
                             state.pairing,
                             linearise_geometry ? &k.step_increment : nullptr,
                             k.position - state.pairing.master_point);
            conditions.add_point(local, state, k, assemble_matrix, linearise_geometry);
          }
        view.newton_constraints.distribute_local_to_global(
            local.length_weights, local.dofs, view.multiplier_length_weights);
        view.hanging_constraints.distribute_local_to_global(
            local.rhs, local.dofs, view.contact_residual);
        add_to_global_system(local.matrix, local.rhs, local.dofs, assemble_matrix);
      }
  }

  template <int dim>
  void
  SystemAssembler<dim>::add_to_global_system(const FullMatrix<double> &local_matrix,
                                             Vector<double>           &local_rhs,
                                             const std::vector<types::global_dof_index> &dofs,
                                             const bool assemble_matrix)
  {
    if (!assemble_matrix)
      {
        view.newton_constraints.distribute_local_to_global(local_rhs, dofs, view.system_rhs);
        return;
      }
    // Tangent predictor: the residual linearised at u + Δū, R(u) + K Δū, where
    // Δū is the Dirichlet increment of the load step (zero off the Dirichlet
    // boundary), so the first solve carries the boundary motion into the body.
    if (view.dirichlet_predictor)
      for (unsigned int i = 0; i < dofs.size(); ++i)
        for (unsigned int j = 0; j < dofs.size(); ++j)
          local_rhs(i) += local_matrix(i, j) * view.dirichlet_increment(dofs[j]);
    view.newton_constraints.distribute_local_to_global(
        local_matrix, local_rhs, dofs, view.system_matrix, view.system_rhs);
  }

  template <int dim>
  double
  SystemAssembler<dim>::residual_norm() const
  {
    TrilinosWrappers::MPI::Vector scaled(view.system_rhs);
    scaled.scale(view.residual_scaling);
    return scaled.linfty_norm();
  }

  template <int dim>
  ScaledResidual
  SystemAssembler<dim>::scaled_residual() const
  {
    // largest: force residual, force scale, gap, slip, displacement
    double largest[5] = {0., 0., 0., 0., 0.};
    for (const auto i : view.locally_owned_u)
      {
        largest[0] = std::max(largest[0], std::abs(view.system_rhs(i)));
        largest[1] = std::max(
            {largest[1], std::abs(view.internal_force(i)), std::abs(view.external_force(i))});
        largest[4] = std::max(largest[4], std::abs(view.solution(i)));
      }
    for (const auto &[row, component] : view.owned_multiplier_components)
      if (view.multiplier_length_weights(row) > 0.)
        {
          double &block = largest[component == 0 ? 2 : 3];
          block =
              std::max(block, std::abs(view.system_rhs(row)) / view.multiplier_length_weights(row));
        }
    Utilities::MPI::max(largest, view.communicator, largest);
    // Floor of the force scale: where the body moves without deforming (a
    // rigid motion before contact, a free rotation) the forces are round-off,
    // so forces below those that displace a node of the stiffest, smallest
    // cell by a fraction force_scale_floor of the largest displacement count
    // as zero (doc/formulation.md).
    // The displacement yardstick is the iterate's, capped by the scene's
    // extent: a diverged iterate (a node flung far away) may not make its own
    // residual look small.
    largest[4] = view.bounds.displacement_scale(largest[4]);
    largest[1] = std::max(largest[1], force_scale_floor * view.nodal_stiffness * largest[4]);
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

  template class SystemAssembler<2>;
  template class SystemAssembler<3>;

  // --- ContactProblem's part: the entry and the views ---

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
    SystemAssembler<dim>(assembly_view()).assemble(assemble_matrix);
  }

  template <int dim>
  typename SystemAssembler<dim>::View
  ContactProblem<dim>::assembly_view()
  {
    return typename SystemAssembler<dim>::View{mpi_communicator,
                                               loops,
                                               boundary_conditions,
                                               boundary_view(),
                                               obstacle_translation,
                                               obstacle_rotation,
                                               body_mesh,
                                               *fe_pair,
                                               *fe_u,
                                               *fe_m,
                                               dof_handler_u,
                                               cell_quadrature,
                                               contact_quadrature,
                                               axisymmetric,
                                               body_response,
                                               ghosted_solution,
                                               spaces,
                                               partner,
                                               law,
                                               newton_constraints,
                                               hanging_constraints,
                                               dirichlet_increment,
                                               dirichlet_predictor,
                                               locally_owned_u,
                                               solution,
                                               residual_scaling,
                                               owned_multiplier_components,
                                               bounds,
                                               nodal_stiffness,
                                               system_matrix,
                                               system_rhs,
                                               internal_force,
                                               contact_residual,
                                               external_force,
                                               multiplier_length_weights,
                                               inadmissible_state,
                                               material_history,
                                               contact,
                                               work,
                                               [this]() { update_pairings(false); }};
  }

  template <int dim>
  BoundaryConditions::Problem<dim>
  ContactProblem<dim>::boundary_view() const
  {
    return {
        dof_handler_u, *fe_u, mpi_communicator, locally_owned, locally_owned_u, axisymmetric, time};
  }

  // Explicit instantiation of the members defined in this file (the class
  // itself is instantiated once, in contact_problem.cc).
#define SL_INSTANTIATE(dim)                                                                       \
  template void                                ContactProblem<dim>::update_ghosts();              \
  template void                                ContactProblem<dim>::assemble_newton_system(bool); \
  template typename SystemAssembler<dim>::View ContactProblem<dim>::assembly_view();              \
  template BoundaryConditions::Problem<dim>    ContactProblem<dim>::boundary_view() const;

  SL_INSTANTIATE(2)
  SL_INSTANTIATE(3)
#undef SL_INSTANTIATE
} // namespace StabilizedLagrangian
