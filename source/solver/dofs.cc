#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>

#include <deal.II/numerics/rtree.h>
#include <deal.II/numerics/vector_tools.h>

#include <stabilized_lagrangian/contact/stabilized_lagrangian.h>
#include <stabilized_lagrangian/contact/master_surface.h>
#include <stabilized_lagrangian/solver/contact_problem.h>

#include <cmath>
#include <limits>

namespace StabilizedLagrangian
{
  namespace
  {
    /**
     * Number the multiplier DoFs of @p dof_handler_m on Γc first, [0, N_Γ),
     * rank after rank; returns N_Γ. The others (on the rest of the skeleton)
     * are never used.
     */
    template <int dim>
    types::global_dof_index
    number_contact_multipliers_first(DoFHandler<dim>          &dof_handler_m,
                                     const ContactSpaces<dim> &spaces,
                                     const MPI_Comm            mpi_communicator)
    {
      std::set<types::global_dof_index> on_contact;
      spaces.for_each_contact_multiplier_dof(
          [&](const types::global_dof_index dof, unsigned int) { on_contact.insert(dof); });

      const IndexSet          owned           = dof_handler_m.locally_owned_dofs();
      types::global_dof_index n_contact_local = 0;
      for (const auto dof : on_contact)
        if (owned.is_element(dof))
          ++n_contact_local;
      const types::global_dof_index n_other_local = owned.n_elements() - n_contact_local;

      types::global_dof_index                 contact_offset = 0, other_offset = 0;
      const std::array<unsigned long long, 2> local  = {{n_contact_local, n_other_local}};
      std::array<unsigned long long, 2>       prefix = {{0, 0}};
      MPI_Exscan(local.data(), prefix.data(), 2, MPI_UNSIGNED_LONG_LONG, MPI_SUM, mpi_communicator);
      if (Utilities::MPI::this_mpi_process(mpi_communicator) > 0)
        {
          contact_offset = prefix[0];
          other_offset   = prefix[1];
        }
      const types::global_dof_index n_multipliers =
          Utilities::MPI::sum(n_contact_local, mpi_communicator);

      std::vector<types::global_dof_index> new_numbers(owned.n_elements());
      types::global_dof_index              next_contact = contact_offset;
      types::global_dof_index              next_other   = n_multipliers + other_offset;
      for (unsigned int k = 0; k < owned.n_elements(); ++k)
        new_numbers[k] =
            on_contact.count(owned.nth_index_in_set(k)) ? next_contact++ : next_other++;
      dof_handler_m.renumber_dofs(new_numbers);
      return n_multipliers;
    }

  } // namespace

  template <int dim>
  void
  ContactProblem<dim>::setup_dofs()
  {
    dof_handler_u.distribute_dofs(*fe_u);
    dof_handler_m.distribute_dofs(*fe_m);
    n_multipliers = number_contact_multipliers_first(dof_handler_m, spaces, mpi_communicator);

    n_u             = dof_handler_u.n_dofs();
    locally_owned_u = dof_handler_u.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dof_handler_u, locally_relevant_u);

    IndexSet contact_block(dof_handler_m.n_dofs());
    contact_block.add_range(0, n_multipliers);
    IndexSet relevant_m;
    DoFTools::extract_locally_relevant_dofs(dof_handler_m, relevant_m);
    const IndexSet owned_multipliers    = dof_handler_m.locally_owned_dofs() & contact_block;
    const IndexSet relevant_multipliers = relevant_m & contact_block;

    locally_owned.clear();
    locally_owned.set_size(n_u + n_multipliers);
    locally_owned.add_indices(locally_owned_u);
    locally_owned.add_indices(owned_multipliers, n_u);
    locally_owned.compress();
    locally_relevant.clear();
    locally_relevant.set_size(n_u + n_multipliers);
    locally_relevant.add_indices(locally_relevant_u);
    locally_relevant.add_indices(relevant_multipliers, n_u);
    partner             = make_partner();
    partner_dof_growths = 0;
    locally_relevant.add_indices(partner->dofs());
    // every rank couples to the DoFs the conditions' constraints link others to
    for (const auto &condition : boundary_conditions)
      condition->find_linked_dofs(boundary_view(), boundary_conditions, locally_relevant);
    locally_relevant.compress();

    const unsigned int u_degree = fe_pair->displacement_degree();
    cell_quadrature             = body_mesh.cell_gauss(u_degree + 1);
    if (contact_parameters.quadrature == Parameters::ContactQuadrature::gauss)
      contact_quadrature =
          body_mesh.face_gauss(std::max(u_degree, fe_pair->multiplier_degree()) + 1);
    else
      // nodal for the multiplier when it is at least as rich as the displacement
      // trace; otherwise enough points to integrate ψ φ·n exactly
      contact_quadrature =
          body_mesh.face_nodes(std::max({fe_pair->multiplier_degree(), u_degree, 1u}));

    SystemConstraints<dim>(constraints_view()).make();

    reinit_system_vectors();
  }

  template <int dim>
  std::unique_ptr<Contact::Partner<dim>>
  ContactProblem<dim>::make_partner() const
  {
    if (chosen.master_boundaries.empty())
      return std::make_unique<Contact::RigidObstacle<dim>>(*obstacle, obstacle_motion);
    // a rank holds the master faces near its slave faces (their DoFs are ghosts)
    double search_distance = contact_parameters.search_distance;
    if (search_distance == 0.)
      {
        for (const auto &cell : triangulation.active_cell_iterators())
          if (cell->is_locally_owned())
            for (const unsigned int f : cell->face_indices())
              if (spaces.is_slave_or_master_face(cell, f))
                search_distance = std::max(search_distance, 2. * cell->face(f)->diameter());
        search_distance = Utilities::MPI::max(search_distance, mpi_communicator);
      }
    auto master_surface =
        std::make_unique<Contact::MasterSurface<dim>>(dof_handler_u,
                                                      chosen.master_boundaries,
                                                      mpi_communicator,
                                                      contact_parameters.replicated_search,
                                                      search_distance);
    if (master_surface->n_faces() == 0)
      throw InputError("Contact/Master boundary ids: the master boundary has no faces.");
    master_surface->gather_faces_near(slave_search_region(nullptr), nullptr);
    return master_surface;
  }

  template <int dim>
  void
  ContactProblem<dim>::reinit_system_vectors()
  {
    system_rhs.reinit(locally_owned, mpi_communicator);
    solution.reinit(locally_owned, mpi_communicator);
    ghosted_solution.reinit(locally_owned, locally_relevant, mpi_communicator);
    step_start.reinit(locally_owned, locally_relevant, mpi_communicator);
    last_increment.reinit(locally_owned, mpi_communicator);
    last_step_size = 0.;
    internal_force.reinit(locally_owned, mpi_communicator);
    contact_residual.reinit(locally_owned, mpi_communicator);
    external_force.reinit(locally_owned, mpi_communicator);
    multiplier_length_weights.reinit(locally_owned, mpi_communicator);
    owned_multiplier_components = locally_owned_multiplier_components();
    residual_scaling.reinit(locally_owned, mpi_communicator);
    residual_scaling = 1.;
    for (const auto &[row, component] : owned_multiplier_components)
      residual_scaling(row) = (component == 0) ? chosen.r_n : chosen.r_t;
    residual_scaling.compress(VectorOperation::insert);
  }

  template <int dim>
  std::vector<BoundingBox<dim>>
  ContactProblem<dim>::slave_search_region(const TrilinosWrappers::MPI::Vector *u) const
  {
    std::vector<std::pair<BoundingBox<dim>, unsigned int>> boxes;
    for (const auto &cell : dof_handler_u.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int f : cell->face_indices())
          if (spaces.is_contact_face(cell, f))
            {
              const auto              face = cell->face(f);
              std::vector<Point<dim>> vertices;
              for (const unsigned int v : face->vertex_indices())
                {
                  Point<dim> x = face->vertex(v);
                  if (u != nullptr)
                    for (unsigned int d = 0; d < dim; ++d)
                      x[d] += (*u)(face->vertex_dof_index(v, d));
                  vertices.push_back(x);
                }
              boxes.emplace_back(BoundingBox<dim>(vertices), boxes.size());
            }
    if (boxes.empty())
      return {};
    // a few boxes around them all, from the top of an R-tree
    return extract_rtree_level(pack_rtree(boxes), 0);
  }

  template <int dim>
  void
  ContactProblem<dim>::update_partner_configuration()
  {
    if (partner->gather_faces_near(slave_search_region(&ghosted_solution), &ghosted_solution))
      follow_partner_dofs();
    partner->update_configuration(ghosted_solution);
  }

  template <int dim>
  typename SystemConstraints<dim>::View
  ContactProblem<dim>::constraints_view()
  {
    return typename SystemConstraints<dim>::View{triangulation,
                                                 dof_handler_u,
                                                 dof_handler_m,
                                                 *fe_u,
                                                 *fe_m,
                                                 contact_parameters.fe_pair,
                                                 fe_pair->multiplier_on_coarser_mesh(),
                                                 locally_owned,
                                                 locally_relevant,
                                                 locally_owned_u,
                                                 n_u,
                                                 n_multipliers,
                                                 chosen.contact_boundaries,
                                                 *partner,
                                                 contact_zones.any_friction(),
                                                 axisymmetric,
                                                 mpi_communicator,
                                                 boundary_view(),
                                                 boundary_conditions,
                                                 hanging_constraints,
                                                 newton_constraints};
  }

  template <int dim>
  void
  ContactProblem<dim>::follow_partner_dofs()
  {
    TimerOutput::Scope scope(timer, "sparsity pattern");
    locally_relevant.add_indices(partner->dofs());
    locally_relevant.compress();
    SystemConstraints<dim>(constraints_view()).make();
    TrilinosWrappers::MPI::Vector owned(locally_owned, mpi_communicator);
    for (auto *vector : {&ghosted_solution, &step_start, &dirichlet_increment})
      if (vector->size() > 0)
        {
          for (const auto index : locally_owned)
            owned(index) = (*vector)(index);
          owned.compress(VectorOperation::insert);
          vector->reinit(locally_owned, locally_relevant, mpi_communicator);
          *vector = owned;
        }
    sparsity_stale = true;
    ++partner_dof_growths;
  }

  template <int dim>
  std::vector<std::pair<types::global_dof_index, unsigned int>>
  ContactProblem<dim>::locally_owned_multiplier_components() const
  {
    std::map<types::global_dof_index, unsigned int> components;
    spaces.for_each_contact_multiplier_dof(
        [&](const types::global_dof_index dof, const unsigned int i) {
          if (locally_owned.is_element(n_u + dof))
            components[n_u + dof] = fe_m->system_to_component_index(i).first;
        });
    return {components.begin(), components.end()};
  }

  template <int dim>
  void
  ContactProblem<dim>::setup_sparsity()
  {
    TimerOutput::Scope                   scope(timer, "sparsity pattern");
    DynamicSparsityPattern               dsp(locally_relevant);
    std::vector<types::global_dof_index> u_dofs(fe_u->n_dofs_per_cell());
    for (const auto &cell : dof_handler_u.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          cell->get_dof_indices(u_dofs);
          newton_constraints.add_entries_local_to_global(u_dofs, dsp, false);
        }
    FaceEvaluator<dim>                   evaluator(spaces, contact_quadrature);
    const std::vector<ContactFace<dim>> &faces = contact.faces();
    sparsity_master_faces.assign(faces.size(), {});
    for (unsigned int c = 0; c < faces.size(); ++c)
      {
        const ContactFace<dim> &face = faces[c];
        evaluator.reinit(face, ghosted_solution);
        std::vector<types::global_dof_index> local_dofs = evaluator.u_dofs;
        local_dofs.insert(local_dofs.end(), evaluator.m_dofs.begin(), evaluator.m_dofs.end());
        // the partner's faces near the pairings (none for a rigid obstacle)
        std::set<unsigned int> near;
        for (unsigned int q = 0; q < evaluator.n_points(); ++q)
          for (const unsigned int m : partner->faces_near(contact.point(face, q).pairing))
            near.insert(m);
        sparsity_master_faces[c].assign(near.begin(), near.end());
        for (const unsigned int m : near)
          {
            const auto master_dofs = partner->face_dof_indices(m);
            local_dofs.insert(local_dofs.end(), master_dofs.begin(), master_dofs.end());
          }
        std::sort(local_dofs.begin(), local_dofs.end());
        local_dofs.erase(std::unique(local_dofs.begin(), local_dofs.end()), local_dofs.end());
        newton_constraints.add_entries_local_to_global(local_dofs, dsp, false);
      }
    SparsityTools::distribute_sparsity_pattern(
        dsp, locally_owned, mpi_communicator, locally_relevant);
    // the factorisation refers to the old matrix: release it first
    direct_solver.reset();
    system_matrix.reinit(locally_owned, locally_owned, dsp, mpi_communicator);
    direct_solver =
        std::make_unique<LinearSolvers::DirectSolver>(linear_solver_parameters.direct_solver,
                                                      linear_solver_parameters.null_pivot_detection,
                                                      linear_solver_parameters.workspace_increase);
    // Method = automatic: iterative on the 3D meshes from the threshold on
    const bool iterative = linear_solver_parameters.iterative ||
                           (linear_solver_parameters.automatic && dim == 3 &&
                            n_u + n_multipliers >= linear_solver_parameters.automatic_threshold);
    iterative_solver.reset();
    if (iterative)
      {
        iterative_solver = std::make_unique<LinearSolvers::BlockIterativeSolver>(
            locally_owned,
            n_u,
            mpi_communicator,
            dim,
            rigid_body_modes(),
            fe_pair->displacement_degree() > 1,
            linear_solver_parameters.schur_augmentation,
            linear_solver_parameters.maximum_iterations);
      }
    sparsity_ready = true;
    sparsity_stale = false;
  }

  template <int dim>
  std::vector<std::vector<double>>
  ContactProblem<dim>::rigid_body_modes() const
  {
    const unsigned int n_modes =
        (axisymmetric || !linear_solver_parameters.rigid_body_modes) ? dim : (dim == 2 ? 3 : 6);
    std::vector<std::vector<double>>     modes(n_modes,
                                           std::vector<double>(locally_owned_u.n_elements()));
    const std::vector<Point<dim>>       &unit_points = fe_u->get_unit_support_points();
    std::vector<types::global_dof_index> indices(fe_u->n_dofs_per_cell());
    for (const auto &cell : dof_handler_u.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const Mapping<dim> &mapping =
              cell->reference_cell().template get_default_linear_mapping<dim>();
          cell->get_dof_indices(indices);
          for (unsigned int i = 0; i < indices.size(); ++i)
            if (locally_owned_u.is_element(indices[i]))
              {
                const unsigned int k = locally_owned_u.index_within_set(indices[i]);
                const unsigned int c = fe_u->system_to_component_index(i).first;
                const Point<dim>   x = mapping.transform_unit_to_real_cell(cell, unit_points[i]);
                modes[c][k]          = 1.;
                if (n_modes == dim)
                  continue;
                // the rotation about each axis a: a × x
                for (unsigned int axis = 0; axis < n_modes - dim; ++axis)
                  {
                    Tensor<1, 3> a, position, rotation;
                    a[dim == 2 ? 2 : axis] = 1.;
                    for (unsigned int d = 0; d < dim; ++d)
                      position[d] = x[d];
                    rotation             = cross_product_3d(a, position);
                    modes[dim + axis][k] = rotation[c];
                  }
              }
        }
    return modes;
  }

  template <int dim>
  bool
  ContactProblem<dim>::pairings_left_sparsity() const
  {
    // a pairing left them when its partner's face is not among those coupled
    // (a rigid obstacle's pairings have no face)
    const std::vector<ContactFace<dim>> &faces = contact.faces();
    int                                  left  = sparsity_master_faces.size() != faces.size();
    for (unsigned int c = 0; c < faces.size() && left == 0; ++c)
      for (unsigned int q = 0; q < faces[c].points(contact_quadrature).size(); ++q)
        {
          const auto &coupled = sparsity_master_faces[c];
          const int   m       = contact.point(faces[c], q).pairing.master_face;
          if (m >= 0 &&
              !std::binary_search(coupled.begin(), coupled.end(), static_cast<unsigned int>(m)))
            left = 1;
        }
    return Utilities::MPI::max(left, mpi_communicator) == 1;
  }

  // Explicit instantiation of the members defined in this file (the class
  // itself is instantiated once, in contact_problem.cc).
#define SL_INSTANTIATE(dim)                                                                     \
  template void                                   ContactProblem<dim>::setup_dofs();            \
  template std::unique_ptr<Contact::Partner<dim>> ContactProblem<dim>::make_partner() const;    \
  template void                                   ContactProblem<dim>::reinit_system_vectors(); \
  template std::vector<BoundingBox<dim>>          ContactProblem<dim>::slave_search_region(     \
      const TrilinosWrappers::MPI::Vector *) const;                                    \
  template void ContactProblem<dim>::update_partner_configuration();                            \
  template void ContactProblem<dim>::follow_partner_dofs();                                     \
  template std::vector<std::pair<types::global_dof_index, unsigned int>>                        \
                ContactProblem<dim>::locally_owned_multiplier_components() const;               \
  template void ContactProblem<dim>::setup_sparsity();                                          \
  template bool ContactProblem<dim>::pairings_left_sparsity() const;

  SL_INSTANTIATE(2)
  SL_INSTANTIATE(3)
#undef SL_INSTANTIATE
} // namespace StabilizedLagrangian
