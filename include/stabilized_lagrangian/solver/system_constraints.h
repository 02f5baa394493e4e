#pragma once

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe.h>

#include <deal.II/grid/tria.h>

#include <deal.II/lac/affine_constraints.h>

#include <stabilized_lagrangian/boundary_conditions/interface.h>
#include <stabilized_lagrangian/contact/partner.h>
#include <stabilized_lagrangian/discretization/fe_pair.h>

#include <array>
#include <memory>
#include <set>
#include <string>
#include <vector>

/**
 * @file
 * The constraints of the Newton system on one mesh: the hanging nodes of the
 * displacement and of the multipliers on Γc, the multiplier of a coarse-mesh
 * pair, the boundary conditions' homogeneous constraints on the Newton
 * update, the axis of an axisymmetric model, and Λ_α = 0 where the slip along
 * a plane obstacle's tangent is prescribed.
 */

namespace StabilizedLagrangian
{
  using namespace dealii;

  /**
   * @brief The hanging-node and Newton constraints of the monolithic system
   * (displacements first, then the multipliers of Γc, then what the boundary
   * conditions add), made on the locally relevant DoFs. It owns nothing: it
   * writes the two AffineConstraints of a View, and the vertices of the point
   * conditions into the boundary conditions (Interface::find_dofs()).
   */
  template <int dim> class SystemConstraints
  {
  public:
    /** What the constraints read of the problem, and (named so) what they write. */
    struct View
    {
      const Triangulation<dim> &triangulation;
      const DoFHandler<dim>    &displacement_dofs;
      const DoFHandler<dim>    &multiplier_dofs;
      const FiniteElement<dim> &fe_u;
      const FiniteElement<dim> &fe_m;
      /** the pair's name (`Contact/Finite element pair`), for its errors */
      const std::string &fe_pair_name;
      /** whether the multiplier lives on the parents of the contact faces */
      const bool                             multiplier_on_coarser_mesh;
      const IndexSet                        &locally_owned;
      const IndexSet                        &locally_relevant;
      const IndexSet                        &locally_owned_u;
      const types::global_dof_index          n_u;
      const types::global_dof_index          n_multipliers;
      const std::set<types::boundary_id>    &contact_boundaries;
      const Contact::Partner<dim>           &partner;
      const bool                             any_friction;
      const bool                             axisymmetric;
      const MPI_Comm                         communicator;
      const BoundaryConditions::Problem<dim> boundary;
      /** the boundary condition plug-ins: their constraints, and where they find their vertices */
      const std::vector<std::unique_ptr<BoundaryConditions::Interface<dim>>> &boundary_conditions;
      /** written: hanging nodes only (displacement, and multiplier continuity on Γc) */
      AffineConstraints<double> &hanging_constraints;
      /** written: the hanging nodes and the homogeneous Dirichlet constraints of the Newton update
       */
      AffineConstraints<double> &newton_constraints;
    };

    /** @brief The constraints of the mesh and DoFs @p view shows. */
    explicit SystemConstraints(const View &view)
        : view(view)
    {
    }

    /**
     * @brief Make the hanging-node and the Newton constraints (collective),
     * after the point conditions have found their vertices.
     */
    void
    make() const;

    /** @brief u_i = 0 on the Dirichlet boundaries (the Newton update's constraints). */
    void
    add_homogeneous_dirichlet(AffineConstraints<double> &constraints) const;

  private:
    /** Multiplier continuity at hanging vertices of Γc (3D), in the monolithic numbering. */
    void
    add_multiplier_hanging_nodes(AffineConstraints<double> &constraints) const;
    /** The multiplier of a coarse-mesh pair: multilinear on the parents of the contact faces. */
    void
    add_multiplier_coarsening(AffineConstraints<double> &constraints) const;
    /** Axisymmetric: u_r = 0 at the DoFs on the axis r = 0. */
    void
    add_axis(AffineConstraints<double> &constraints) const;
    /**
     * Λ_α = 0 at the vertices of Γc whose displacement along the (fixed) tangent
     * t_α of a plane obstacle is prescribed: there the stick condition leaves
     * Λ_α undetermined (the Dirichlet reaction carries the friction) and the
     * Newton system would be singular. On a symmetry plane, 0 is the symmetric value.
     */
    void
    add_prescribed_slip(AffineConstraints<double> &constraints) const;
    /**
     * The vertices of the point loads and point Dirichlet conditions: the
     * vertex of the mesh nearest to each Point, refused when it is not at the
     * point (to 1e-6 of the body's size) or hangs.
     */
    void
    find_point_dofs() const;
    /** The DoFs of the vertex at @p point, per component (@p section names it in errors). */
    std::array<types::global_dof_index, dim>
    vertex_dofs(const Point<dim> &point, const std::string &section) const;
    /** Whether face @p f of @p cell lies on the contact boundary Γc. */
    template <typename CellIterator>
    bool
    is_contact_face(const CellIterator &cell, const unsigned int f) const
    {
      return cell->face(f)->at_boundary() &&
             view.contact_boundaries.count(cell->face(f)->boundary_id()) > 0;
    }

    const View view;
  };
} // namespace StabilizedLagrangian
