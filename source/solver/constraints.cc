#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>

#include <deal.II/numerics/rtree.h>
#include <deal.II/numerics/vector_tools.h>

#include <stabilized_lagrangian/contact/stabilized_lagrangian.h>
#include <stabilized_lagrangian/contact/master_surface.h>
#include <stabilized_lagrangian/plugins.h>
#include <stabilized_lagrangian/solver/system_constraints.h>

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
  SystemConstraints<dim>::make() const
  {
    view.hanging_constraints.clear();
    view.hanging_constraints.reinit(view.locally_relevant);
    DoFTools::make_hanging_node_constraints(view.displacement_dofs, view.hanging_constraints);
    add_multiplier_hanging_nodes(view.hanging_constraints);
    if (view.multiplier_on_coarser_mesh)
      add_multiplier_coarsening(view.hanging_constraints);
    // in 3D, chains of hanging nodes may end on another rank's DoFs
    view.hanging_constraints.make_consistent_in_parallel(
        view.locally_owned, view.locally_relevant, view.communicator);
    view.hanging_constraints.close();
    find_point_dofs();
    view.newton_constraints.clear();
    view.newton_constraints.reinit(view.locally_relevant);
    view.newton_constraints.merge(view.hanging_constraints);
    add_homogeneous_dirichlet(view.newton_constraints);
    for (const auto &condition : view.boundary_conditions)
      condition->add_linked_constraints(view.boundary, view.newton_constraints);
    add_prescribed_slip(view.newton_constraints);
    view.newton_constraints.make_consistent_in_parallel(
        view.locally_owned, view.locally_relevant, view.communicator);
    view.newton_constraints.close();
  }

  template <int dim>
  void
  SystemConstraints<dim>::add_multiplier_hanging_nodes(AffineConstraints<double> &constraints) const
  {
    // Continuity of the multipliers at the hanging vertices (and edges) of Γc
    // in 3D: the constraints of the trace element on the whole skeleton,
    // restricted to the Γc block and shifted to the monolithic numbering. The
    // skeleton's other DoFs are never used.
    IndexSet relevant_m;
    DoFTools::extract_locally_relevant_dofs(view.multiplier_dofs, relevant_m);
    AffineConstraints<double> skeleton(relevant_m);
    DoFTools::make_hanging_node_constraints(view.multiplier_dofs, skeleton);
    skeleton.close();
    for (const auto &line : skeleton.get_lines())
      {
        if (line.index >= view.n_multipliers)
          continue;
        // the contact boundary must not end inside a refined face: there a
        // hanging vertex of Γc depends on one off it, which has no multiplier
        AssertThrow(
            std::all_of(line.entries.begin(),
                        line.entries.end(),
                        [&](const auto &entry) { return entry.first < view.n_multipliers; }),
            ExcMessage("Contact/Contact boundary ids: the contact boundary ends inside a "
                       "refined face (some children of the face are on it, some not), "
                       "so a multiplier at a hanging vertex would depend on one off the "
                       "contact boundary. Give all the children of a refined face the "
                       "same boundary id."));
        constraints.add_line(view.n_u + line.index);
        for (const auto &[column, weight] : line.entries)
          constraints.add_entry(view.n_u + line.index, view.n_u + column, weight);
      }
  }

  template <int dim>
  void
  SystemConstraints<dim>::add_multiplier_coarsening(AffineConstraints<double> &constraints) const
  {
    // The multiplier is continuous and multilinear on the parent of each
    // contact face: the values at the vertices of the children that are not
    // vertices of the parent are interpolated from the parent's vertices.
    for (const auto &line : constraints.get_lines())
      if (line.index >= view.n_u)
        throw InputError("Contact/Finite element pair = " + view.fe_pair_name +
                         " needs a contact boundary without hanging nodes.");
    constexpr unsigned int n_face_vertices = GeometryInfo<dim>::vertices_per_face;
    const unsigned int     n_components    = view.fe_m.n_components();
    for (const auto &cell : view.multiplier_dofs.active_cell_iterators())
      if (!cell->is_artificial())
        for (const unsigned int f : cell->face_indices())
          if (is_contact_face(cell, f))
            {
              if (cell->level() == 0)
                throw InputError("Contact/Finite element pair = " + view.fe_pair_name +
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
                        if (fine >= view.n_multipliers ||
                            constraints.is_constrained(view.n_u + fine) ||
                            *std::max_element(coarse.begin(), coarse.end()) >= view.n_multipliers)
                          continue;
                        constraints.add_line(view.n_u + fine);
                        for (unsigned int k = 0; k < n_face_vertices; ++k)
                          if (weights[k] != 0.)
                            constraints.add_entry(
                                view.n_u + fine, view.n_u + coarse[k], weights[k]);
                      }
                  }
            }
  }

  template <int dim>
  void
  SystemConstraints<dim>::add_homogeneous_dirichlet(AffineConstraints<double> &constraints) const
  {
    for (const auto &condition : view.boundary_conditions)
      condition->add_homogeneous_constraints(view.boundary, constraints);
    if (view.axisymmetric)
      add_axis(constraints);
  }

  template <int dim>
  void
  SystemConstraints<dim>::add_axis(AffineConstraints<double> &constraints) const
  {
    // u_r = 0 on the axis r = 0: the faces lying on it, and single vertices
    // that touch it
    std::vector<types::global_dof_index> dofs;
    for (const auto &cell : view.displacement_dofs.active_cell_iterators())
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
              dofs.resize(view.fe_u.n_dofs_per_face(f));
              face->get_dof_indices(dofs);
              for (unsigned int i = 0; i < dofs.size(); ++i)
                if (view.fe_u.face_system_to_component_index(i, f).first == 0 &&
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
  SystemConstraints<dim>::find_point_dofs() const
  {
    for (const auto &condition : view.boundary_conditions)
      condition->find_dofs(view.boundary,
                           [this](const Point<dim> &point, const std::string &section) {
                             return vertex_dofs(point, section);
                           });
    // a vertex a point condition prescribes must not be one another links
    for (const auto &condition : view.boundary_conditions)
      for (const auto &other : view.boundary_conditions)
        other->check_prescribed_vertex(view.boundary, *condition);
  }

  template <int dim>
  std::array<types::global_dof_index, dim>
  SystemConstraints<dim>::vertex_dofs(const Point<dim> &point, const std::string &section) const
  {
    double size = 0.;
    for (const auto &cell : view.triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        size = std::max(size, cell->diameter());
    size                       = Utilities::MPI::max(size, view.communicator);
    const unsigned int rank    = Utilities::MPI::this_mpi_process(view.communicator);
    double             nearest = std::numeric_limits<double>::max();
    std::array<types::global_dof_index, dim> dofs;
    Point<dim>                               vertex;
    for (const auto &cell : view.displacement_dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int v : cell->vertex_indices())
          if (cell->vertex(v).distance(point) < nearest)
            {
              nearest = cell->vertex(v).distance(point);
              vertex  = cell->vertex(v);
              for (unsigned int c = 0; c < dim; ++c)
                dofs[c] = cell->vertex_dof_index(v, c);
            }
    const double       closest = Utilities::MPI::min(nearest, view.communicator);
    const unsigned int owner   = Utilities::MPI::min(
        nearest == closest ? rank : numbers::invalid_unsigned_int, view.communicator);
    dofs   = Utilities::MPI::broadcast(view.communicator, dofs, owner);
    vertex = Utilities::MPI::broadcast(view.communicator, vertex, owner);
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
      hanging |= view.locally_owned_u.is_element(dofs[c]) &&
                 view.hanging_constraints.is_constrained(dofs[c]);
    if (Utilities::MPI::logical_or(hanging, view.communicator))
      throw InputError(section +
                       "/Point: the vertex there hangs on a refined neighbour; put the condition "
                       "on a vertex of the coarser cells.");
    return dofs;
  }

  template <int dim>
  void
  SystemConstraints<dim>::add_prescribed_slip(AffineConstraints<double> &constraints) const
  {
    if (!view.any_friction || !view.partner.is_flat())
      return;
    const auto tangents = view.partner.project(Point<dim>()).tangents;
    // the vertex DoFs of the multiplier element by component (0: λ_n, 1..: Λ)
    std::vector<unsigned int> m_component(view.fe_m.n_dofs_per_vertex());
    for (unsigned int i = 0; i < m_component.size(); ++i)
      m_component[i] = view.fe_m.system_to_component_index(i).first;
    for (const auto &cell : view.displacement_dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int f : cell->face_indices())
          if (is_contact_face(cell, f))
            {
              const auto face = cell->face(f);
              // the same cell of the multiplier DoFHandler
              const typename DoFHandler<dim>::active_cell_iterator cell_m(
                  &view.triangulation, cell->level(), cell->index(), &view.multiplier_dofs);
              const auto face_m = cell_m->face(f);
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
                                        !view.hanging_constraints.is_constrained(u);
                        }
                    if (!prescribed)
                      continue;
                    for (unsigned int i = 0; i < m_component.size(); ++i)
                      if (m_component[i] == a + 1)
                        {
                          const auto m = view.n_u + face_m->vertex_dof_index(v, i);
                          if (!constraints.is_constrained(m))
                            constraints.add_line(m);
                        }
                  }
            }
  }

  template class SystemConstraints<2>;
  template class SystemConstraints<3>;
} // namespace StabilizedLagrangian
