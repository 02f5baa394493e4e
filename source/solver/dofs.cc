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
     * Multilinear weights of the vertices of a face at vertex @p v of its
     * child @p c (isotropic refinement, children and vertices numbered
     * lexicographically); empty when that vertex is a vertex of the face.
     */
    template <int dim>
    std::vector<double>
    child_vertex_weights(const unsigned int c, const unsigned int v)
    {
      std::array<double, dim - 1> xi;
      bool                        face_vertex = true;
      for (unsigned int d = 0; d < dim - 1; ++d)
        {
          xi[d] = 0.5 * (((c >> d) & 1) + ((v >> d) & 1));
          face_vertex &= (xi[d] == 0. || xi[d] == 1.);
        }
      if (face_vertex)
        return {};
      std::vector<double> weights(GeometryInfo<dim>::vertices_per_face, 1.);
      for (unsigned int k = 0; k < weights.size(); ++k)
        for (unsigned int d = 0; d < dim - 1; ++d)
          weights[k] *= ((k >> d) & 1) ? xi[d] : 1. - xi[d];
      return weights;
    }
  } // namespace

  template <int dim>
  void
  ContactProblem<dim>::setup_dofs()
  {
    fe_u = fe_pair->displacement_element();
    fe_m = fe_pair->multiplier_element(any_friction() ? dim : 1);
    multiplier_dofs_on_face.assign(fe_m->reference_cell().n_faces(), {});
    for (unsigned int face = 0; face < multiplier_dofs_on_face.size(); ++face)
      {
        auto &on_face = multiplier_dofs_on_face[face];
        for (unsigned int j = 0; j < fe_m->n_dofs_per_face(face); ++j)
          on_face.push_back(fe_m->face_to_cell_index(j, face));
        std::sort(on_face.begin(), on_face.end());
      }
    dof_handler_u.distribute_dofs(*fe_u);
    dof_handler_m.distribute_dofs(*fe_m);
    setup_multiplier_numbering();

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
    if (chosen.master_boundaries.empty())
      partner = std::make_unique<Contact::RigidObstacle<dim>>(*obstacle, obstacle_motion);
    else
      {
        // a rank holds the master faces near its slave faces (their DoFs are ghosts)
        double search_distance = contact_parameters.search_distance;
        if (search_distance == 0.)
          {
            for (const auto &cell : triangulation.active_cell_iterators())
              if (cell->is_locally_owned())
                for (const unsigned int f : cell->face_indices())
                  if (is_slave_or_master_face(cell, f))
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
        partner = std::move(master_surface);
        partner->gather_faces_near(slave_search_region(nullptr), nullptr);
      }
    partner_dof_growths = 0;
    locally_relevant.add_indices(partner->dofs());
    // every rank couples to the DoFs the conditions' constraints link others to
    for (const auto &condition : boundary_conditions)
      condition->find_linked_dofs(boundary_view(), boundary_conditions, locally_relevant);
    locally_relevant.compress();

    const unsigned int u_degree = fe_pair->displacement_degree();
    cell_quadrature             = cell_gauss(u_degree + 1);
    if (contact_parameters.quadrature == Parameters::ContactQuadrature::gauss)
      contact_quadrature = face_gauss(std::max(u_degree, fe_pair->multiplier_degree()) + 1);
    else
      // nodal for the multiplier when it is at least as rich as the displacement
      // trace; otherwise enough points to integrate ψ φ·n exactly
      contact_quadrature = face_nodes(std::max({fe_pair->multiplier_degree(), u_degree, 1u}));

    setup_constraints();

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
  void
  ContactProblem<dim>::setup_constraints()
  {
    hanging_constraints.clear();
    hanging_constraints.reinit(locally_relevant);
    DoFTools::make_hanging_node_constraints(dof_handler_u, hanging_constraints);
    add_multiplier_hanging_node_constraints(hanging_constraints);
    if (fe_pair->multiplier_on_coarser_mesh())
      add_multiplier_coarsening_constraints(hanging_constraints);
    // in 3D, chains of hanging nodes may end on another rank's DoFs
    hanging_constraints.make_consistent_in_parallel(
        locally_owned, locally_relevant, mpi_communicator);
    hanging_constraints.close();
    find_point_dofs();
    newton_constraints.clear();
    newton_constraints.reinit(locally_relevant);
    newton_constraints.merge(hanging_constraints);
    add_homogeneous_dirichlet_constraints(newton_constraints);
    for (const auto &condition : boundary_conditions)
      condition->add_linked_constraints(boundary_view(), newton_constraints);
    add_prescribed_slip_constraints(newton_constraints);
    newton_constraints.make_consistent_in_parallel(
        locally_owned, locally_relevant, mpi_communicator);
    newton_constraints.close();
  }

  template <int dim>
  std::vector<BoundingBox<dim>>
  ContactProblem<dim>::slave_search_region(const TrilinosWrappers::MPI::Vector *u) const
  {
    std::vector<std::pair<BoundingBox<dim>, unsigned int>> boxes;
    for (const auto &cell : dof_handler_u.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int f : cell->face_indices())
          if (is_contact_face(cell, f))
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
  void
  ContactProblem<dim>::follow_partner_dofs()
  {
    TimerOutput::Scope scope(timer, "sparsity pattern");
    locally_relevant.add_indices(partner->dofs());
    locally_relevant.compress();
    setup_constraints();
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
  Quadrature<dim - 1>
  ContactProblem<dim>::face_nodes(const unsigned int degree) const
  {
    if (!simplex_mesh() || dim == 2)
      return QGaussLobatto<dim - 1>(degree + 1);
    if (degree > 1)
      throw InputError("Contact/Contact quadrature = Gauss-Lobatto needs degree 1 on tetrahedra "
                       "(P1/P1): the quadratic nodal weights of a triangle vanish at its "
                       "vertices. Use Contact quadrature = Gauss with " +
                       contact_parameters.fe_pair + ".");
    std::vector<Point<dim - 1>> vertices;
    for (const unsigned int v : ReferenceCells::get_simplex<dim - 1>().vertex_indices())
      vertices.push_back(ReferenceCells::get_simplex<dim - 1>().template vertex<dim - 1>(v));
    return Quadrature<dim - 1>(vertices, std::vector<double>(vertices.size(), 1. / 6.));
  }

  template <int dim>
  void
  ContactProblem<dim>::add_multiplier_hanging_node_constraints(
      AffineConstraints<double> &constraints) const
  {
    // Continuity of the multipliers at the hanging vertices (and edges) of Γc
    // in 3D: the constraints of the trace element on the whole skeleton,
    // restricted to the Γc block and shifted to the monolithic numbering. The
    // skeleton's other DoFs are never used.
    IndexSet relevant_m;
    DoFTools::extract_locally_relevant_dofs(dof_handler_m, relevant_m);
    AffineConstraints<double> skeleton(relevant_m);
    DoFTools::make_hanging_node_constraints(dof_handler_m, skeleton);
    skeleton.close();
    for (const auto &line : skeleton.get_lines())
      {
        if (line.index >= n_multipliers)
          continue;
        // the contact boundary must not end inside a refined face: there a
        // hanging vertex of Γc depends on one off it, which has no multiplier
        AssertThrow(std::all_of(line.entries.begin(),
                                line.entries.end(),
                                [&](const auto &entry) { return entry.first < n_multipliers; }),
                    ExcMessage("Contact/Contact boundary ids: the contact boundary ends inside a "
                               "refined face (some children of the face are on it, some not), "
                               "so a multiplier at a hanging vertex would depend on one off the "
                               "contact boundary. Give all the children of a refined face the "
                               "same boundary id."));
        constraints.add_line(n_u + line.index);
        for (const auto &[column, weight] : line.entries)
          constraints.add_entry(n_u + line.index, n_u + column, weight);
      }
  }

  template <int dim>
  void
  ContactProblem<dim>::add_multiplier_coarsening_constraints(
      AffineConstraints<double> &constraints) const
  {
    // The multiplier is continuous and multilinear on the parent of each
    // contact face: the values at the vertices of the children that are not
    // vertices of the parent are interpolated from the parent's vertices.
    for (const auto &line : constraints.get_lines())
      if (line.index >= n_u)
        throw InputError("Contact/Finite element pair = " + contact_parameters.fe_pair +
                         " needs a contact boundary without hanging nodes.");
    constexpr unsigned int n_face_vertices = GeometryInfo<dim>::vertices_per_face;
    const unsigned int     n_components    = fe_m->n_components();
    for (const auto &cell : dof_handler_m.active_cell_iterators())
      if (!cell->is_artificial())
        for (const unsigned int f : cell->face_indices())
          if (is_contact_face(cell, f))
            {
              if (cell->level() == 0)
                throw InputError("Contact/Finite element pair = " + contact_parameters.fe_pair +
                                 " needs the contact boundary refined at least once.");
              const auto coarse_face = cell->parent()->face(f);
              for (unsigned int c = 0; c < coarse_face->n_children(); ++c)
                for (unsigned int v = 0; v < n_face_vertices; ++v)
                  {
                    const std::vector<double> weights = child_vertex_weights<dim>(c, v);
                    for (unsigned int component = 0; component < n_components && !weights.empty();
                         ++component)
                      {
                        const types::global_dof_index fine =
                            coarse_face->child(c)->vertex_dof_index(v, component);
                        std::vector<types::global_dof_index> coarse(n_face_vertices);
                        for (unsigned int k = 0; k < n_face_vertices; ++k)
                          coarse[k] = coarse_face->vertex_dof_index(k, component);
                        // at the edge of Γc a parent face may be only partly in
                        // Γc: its fine nodes there stay free
                        if (fine >= n_multipliers || constraints.is_constrained(n_u + fine) ||
                            *std::max_element(coarse.begin(), coarse.end()) >= n_multipliers)
                          continue;
                        constraints.add_line(n_u + fine);
                        for (unsigned int k = 0; k < n_face_vertices; ++k)
                          if (weights[k] != 0.)
                            constraints.add_entry(n_u + fine, n_u + coarse[k], weights[k]);
                      }
                  }
            }
  }

  template <int dim>
  void
  ContactProblem<dim>::add_homogeneous_dirichlet_constraints(
      AffineConstraints<double> &constraints) const
  {
    for (const auto &condition : boundary_conditions)
      condition->add_homogeneous_constraints(boundary_view(), constraints);
    if (axisymmetric)
      add_axis_constraints(constraints);
  }

  template <int dim>
  void
  ContactProblem<dim>::add_axis_constraints(AffineConstraints<double> &constraints) const
  {
    // u_r = 0 on the axis r = 0: the faces lying on it, and single vertices
    // that touch it
    std::vector<types::global_dof_index> dofs;
    for (const auto &cell : dof_handler_u.active_cell_iterators())
      if (!cell->is_artificial())
        {
          const double tolerance = 1e-10 * cell->diameter();
          for (const unsigned int f : cell->face_indices())
            {
              const auto face = cell->face(f);
              if (!face->at_boundary())
                continue;
              bool on_axis = true;
              for (const unsigned int v : face->vertex_indices())
                on_axis = on_axis && std::abs(face->vertex(v)[0]) < tolerance;
              if (!on_axis)
                continue;
              dofs.resize(fe_u->n_dofs_per_face(f));
              face->get_dof_indices(dofs);
              for (unsigned int i = 0; i < dofs.size(); ++i)
                if (fe_u->face_system_to_component_index(i, f).first == 0 &&
                    constraints.can_store_line(dofs[i]) && !constraints.is_constrained(dofs[i]))
                  constraints.add_line(dofs[i]);
            }
          for (const unsigned int v : cell->vertex_indices())
            if (std::abs(cell->vertex(v)[0]) < tolerance)
              {
                const types::global_dof_index dof = cell->vertex_dof_index(v, 0);
                if (constraints.can_store_line(dof) && !constraints.is_constrained(dof))
                  constraints.add_line(dof);
              }
        }
  }

  template <int dim>
  void
  ContactProblem<dim>::find_point_dofs()
  {
    for (const auto &condition : boundary_conditions)
      condition->find_dofs(boundary_view(),
                           [this](const Point<dim> &point, const std::string &section) {
                             return vertex_dofs(point, section);
                           });
    // a vertex a point condition prescribes must not be one another links
    for (const auto &condition : boundary_conditions)
      for (const auto &other : boundary_conditions)
        other->check_prescribed_vertex(boundary_view(), *condition);
  }

  template <int dim>
  std::array<types::global_dof_index, dim>
  ContactProblem<dim>::vertex_dofs(const Point<dim> &point, const std::string &section) const
  {
    double size = 0.;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        size = std::max(size, cell->diameter());
    size                       = Utilities::MPI::max(size, mpi_communicator);
    const unsigned int rank    = Utilities::MPI::this_mpi_process(mpi_communicator);
    double             nearest = std::numeric_limits<double>::max();
    std::array<types::global_dof_index, dim> dofs;
    Point<dim>                               vertex;
    for (const auto &cell : dof_handler_u.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int v : cell->vertex_indices())
          if (cell->vertex(v).distance(point) < nearest)
            {
              nearest = cell->vertex(v).distance(point);
              vertex  = cell->vertex(v);
              for (unsigned int c = 0; c < dim; ++c)
                dofs[c] = cell->vertex_dof_index(v, c);
            }
    const double       closest = Utilities::MPI::min(nearest, mpi_communicator);
    const unsigned int owner   = Utilities::MPI::min(
        nearest == closest ? rank : numbers::invalid_unsigned_int, mpi_communicator);
    dofs   = Utilities::MPI::broadcast(mpi_communicator, dofs, owner);
    vertex = Utilities::MPI::broadcast(mpi_communicator, vertex, owner);
    // (1e-6 of the largest cell: a point written with 6 significant digits)
    if (closest > 1e-6 * size)
      {
        std::ostringstream message;
        message << section << "/Point: no vertex of the mesh there; the nearest is (" << vertex
                << "), " << closest << " mm away. The condition acts on a vertex.";
        throw InputError(message.str());
      }
    bool hanging = false;
    for (unsigned int c = 0; c < dim; ++c)
      hanging |= locally_owned_u.is_element(dofs[c]) && hanging_constraints.is_constrained(dofs[c]);
    if (Utilities::MPI::logical_or(hanging, mpi_communicator))
      throw InputError(section +
                       "/Point: the vertex there hangs on a refined neighbour; put the condition "
                       "on a vertex of the coarser cells.");
    return dofs;
  }

  template <int dim>
  void
  ContactProblem<dim>::add_prescribed_slip_constraints(AffineConstraints<double> &constraints) const
  {
    if (!any_friction() || !partner->is_flat())
      return;
    const auto tangents = partner->project(Point<dim>()).tangents;
    // the vertex DoFs of the multiplier element by component (0: λ_n, 1..: Λ)
    std::vector<unsigned int> m_component(fe_m->n_dofs_per_vertex());
    for (unsigned int i = 0; i < m_component.size(); ++i)
      m_component[i] = fe_m->system_to_component_index(i).first;
    for (const auto &cell : dof_handler_u.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int f : cell->face_indices())
          if (is_contact_face(cell, f))
            {
              const auto face   = cell->face(f);
              const auto face_m = multiplier_cell(cell)->face(f);
              for (const unsigned int v : face->vertex_indices())
                for (unsigned int a = 0; a < dim - 1; ++a)
                  {
                    // t_α·u is prescribed when every component it involves is
                    bool prescribed = true;
                    for (unsigned int d = 0; d < dim; ++d)
                      if (std::abs(tangents[a][d]) > 1e-12)
                        {
                          const auto u = face->vertex_dof_index(v, d);
                          prescribed &= constraints.is_constrained(u) &&
                                        !hanging_constraints.is_constrained(u);
                        }
                    if (!prescribed)
                      continue;
                    for (unsigned int i = 0; i < m_component.size(); ++i)
                      if (m_component[i] == a + 1)
                        {
                          const auto m = n_u + face_m->vertex_dof_index(v, i);
                          if (!constraints.is_constrained(m))
                            constraints.add_line(m);
                        }
                  }
            }
  }

  template <int dim>
  void
  ContactProblem<dim>::setup_multiplier_numbering()
  {
    // Number the multiplier DoFs on Γc first, [0, N_Γ), rank after rank; the
    // others (on the rest of the skeleton) are never used.
    std::set<types::global_dof_index> on_contact;
    for_each_contact_multiplier_dof(
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
    n_multipliers = Utilities::MPI::sum(n_contact_local, mpi_communicator);

    std::vector<types::global_dof_index> new_numbers(owned.n_elements());
    types::global_dof_index              next_contact = contact_offset;
    types::global_dof_index              next_other   = n_multipliers + other_offset;
    for (unsigned int k = 0; k < owned.n_elements(); ++k)
      new_numbers[k] = on_contact.count(owned.nth_index_in_set(k)) ? next_contact++ : next_other++;
    dof_handler_m.renumber_dofs(new_numbers);
  }

  template <int dim>
  std::vector<std::pair<types::global_dof_index, unsigned int>>
  ContactProblem<dim>::locally_owned_multiplier_components() const
  {
    std::map<types::global_dof_index, unsigned int> components;
    for_each_contact_multiplier_dof([&](const types::global_dof_index dof, const unsigned int i) {
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
    FaceEvaluator evaluator(spaces, contact_quadrature);
    sparsity_master_faces.assign(contact_faces.size(), {});
    for (unsigned int c = 0; c < contact_faces.size(); ++c)
      {
        const ContactFace &face = contact_faces[c];
        evaluator.reinit(face, ghosted_solution);
        std::vector<types::global_dof_index> local_dofs = evaluator.u_dofs;
        local_dofs.insert(local_dofs.end(), evaluator.m_dofs.begin(), evaluator.m_dofs.end());
        // the partner's faces near the pairings (none for a rigid obstacle)
        std::set<unsigned int> near;
        for (unsigned int q = 0; q < evaluator.n_points(); ++q)
          for (const unsigned int m :
               partner->faces_near(contact_states[face.first_point + q].pairing))
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
    int left = sparsity_master_faces.size() != contact_faces.size();
    for (unsigned int c = 0; c < contact_faces.size() && left == 0; ++c)
      for (unsigned int q = 0; q < face_quadrature(contact_faces[c]).size(); ++q)
        {
          const auto &faces = sparsity_master_faces[c];
          const int   m     = contact_states[contact_faces[c].first_point + q].pairing.master_face;
          if (m >= 0 &&
              !std::binary_search(faces.begin(), faces.end(), static_cast<unsigned int>(m)))
            left = 1;
        }
    return Utilities::MPI::max(left, mpi_communicator) == 1;
  }

  // Explicit instantiation of the members defined in this file (the class
  // itself is instantiated once, in contact_problem.cc).
#define SL_INSTANTIATE(dim)                                                                       \
  template void                          ContactProblem<dim>::setup_dofs();                       \
  template void                          ContactProblem<dim>::setup_constraints();                \
  template std::vector<BoundingBox<dim>> ContactProblem<dim>::slave_search_region(                \
      const TrilinosWrappers::MPI::Vector *) const;                                               \
  template void                ContactProblem<dim>::update_partner_configuration();               \
  template void                ContactProblem<dim>::follow_partner_dofs();                        \
  template Quadrature<dim - 1> ContactProblem<dim>::face_nodes(const unsigned int) const;         \
  template void                ContactProblem<dim>::add_multiplier_hanging_node_constraints(      \
      AffineConstraints<double> &) const;                                          \
  template void ContactProblem<dim>::add_multiplier_coarsening_constraints(                       \
      AffineConstraints<double> &) const;                                                         \
  template void ContactProblem<dim>::add_homogeneous_dirichlet_constraints(                       \
      AffineConstraints<double> &) const;                                                         \
  template void ContactProblem<dim>::add_axis_constraints(AffineConstraints<double> &) const;     \
  template void ContactProblem<dim>::find_point_dofs();                                           \
  template std::array<types::global_dof_index, dim> ContactProblem<dim>::vertex_dofs(             \
      const Point<dim> &, const std::string &) const;                                             \
  template void ContactProblem<dim>::add_prescribed_slip_constraints(AffineConstraints<double> &) \
      const;                                                                                      \
  template void ContactProblem<dim>::setup_multiplier_numbering();                                \
  template std::vector<std::pair<types::global_dof_index, unsigned int>>                          \
                ContactProblem<dim>::locally_owned_multiplier_components() const;                 \
  template void ContactProblem<dim>::setup_sparsity();                                            \
  template bool ContactProblem<dim>::pairings_left_sparsity() const;

  SL_INSTANTIATE(2)
  SL_INSTANTIATE(3)
#undef SL_INSTANTIATE
} // namespace StabilizedLagrangian
