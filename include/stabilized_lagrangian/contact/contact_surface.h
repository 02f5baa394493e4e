#pragma once

#include <deal.II/base/point.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/table.h>
#include <deal.II/base/tensor.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe.h>
#include <deal.II/fe/fe_values.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <stabilized_lagrangian/contact/pairing.h>

#include <memory>
#include <set>
#include <vector>

/**
 * @file
 * The contact surface Γc as the loops, the assembly and the output see it:
 * its faces, the state frozen at its points, and the evaluation of the
 * displacement and the multipliers on a face (seed §2.1, the integrals on Γc).
 */

namespace StabilizedLagrangian
{
  using namespace dealii;

  /**
   * @brief State frozen at one contact integration point by the outer loops
   * (doc/formulation.md, "Nested loops"): pairing and normal (geometry loop), friction threshold
   * (friction loop), contact status (status loop).
   */
  template <int dim> struct ContactPointState
  {
    Contact::Pairing<dim> pairing;
    double                friction_threshold = 0.;
    bool                  in_contact         = false;
    /** the contact zone: 0 the default friction law, k the `Contact/Zone` k's */
    unsigned int zone = 0;
  };

  /**
   * @brief Fields of the current iterate at one contact point.
   */
  template <int dim> struct ContactKinematics
  {
    Point<dim>         position;              ///< current position x = X + u
    Tensor<1, dim>     displacement;          ///< u
    Tensor<1, dim>     step_increment;        ///< Δu over the load step
    double             contact_pressure = 0.; ///< λ_n
    Tensor<1, dim - 1> semi_multiplier;       ///< Λ in the tangent basis
    double             JxW = 0.;
  };

  /**
   * @brief The spaces a contact face is evaluated in, read-only: the
   * displacement and multiplier elements, the multiplier numbering and the
   * iterate at the step start. The references follow the problem's members,
   * so a view made once stays valid across refinements.
   */
  template <int dim> struct ContactSpaces
  {
    const std::unique_ptr<FiniteElement<dim>> &fe_u;
    const std::unique_ptr<FiniteElement<dim>> &fe_m;
    const DoFHandler<dim>                     &dof_handler_m;
    /** per face number, fe_m's DoFs on that face, ascending */
    const std::vector<std::vector<unsigned int>> &multiplier_dofs_on_face;
    /** the displacement DoFs, the first block of the monolithic numbering */
    const types::global_dof_index &n_u;
    const types::global_dof_index &n_multipliers;
    /** relevant: the solution at the step start */
    const TrilinosWrappers::MPI::Vector &step_start;
    const bool                          &axisymmetric;
    /** the boundary ids of Γc, and of a second body's master surface (ChosenParameters) */
    const std::set<types::boundary_id> &contact_boundaries;
    const std::set<types::boundary_id> &master_boundaries;

    /** The cell of the multiplier DoFHandler that is @p cell of the displacement one. */
    typename DoFHandler<dim>::active_cell_iterator
    multiplier_cell(const typename DoFHandler<dim>::active_cell_iterator &cell) const
    {
      return typename DoFHandler<dim>::active_cell_iterator(
          &dof_handler_m.get_triangulation(), cell->level(), cell->index(), &dof_handler_m);
    }
    /** Whether face @p f of @p cell lies on the contact boundary Γc. */
    template <typename CellIterator>
    bool
    is_contact_face(const CellIterator &cell, const unsigned int f) const
    {
      return cell->face(f)->at_boundary() &&
             contact_boundaries.count(cell->face(f)->boundary_id()) > 0;
    }
    /** Whether face @p f of @p cell lies on Γc or on the master surface of a second body. */
    template <typename CellIterator>
    bool
    is_slave_or_master_face(const CellIterator &cell, const unsigned int f) const
    {
      return is_contact_face(cell, f) ||
             (cell->face(f)->at_boundary() &&
              master_boundaries.count(cell->face(f)->boundary_id()) > 0);
    }
    /** The multiplier element's DoFs on face @p face of a cell, ascending. */
    const std::vector<unsigned int> &
    multiplier_face_dofs(const unsigned int face) const
    {
      return multiplier_dofs_on_face[face];
    }
    /**
     * Call f(dofs, face) for each contact face of the non-artificial cells,
     * with the multiplier DoFs of its cell (multiplier numbering).
     */
    template <typename Function>
    void
    for_each_contact_multiplier_face(const Function &f) const
    {
      std::vector<types::global_dof_index> dofs(fe_m->n_dofs_per_cell());
      for (const auto &cell : dof_handler_m.active_cell_iterators())
        if (!cell->is_artificial())
          for (const unsigned int face : cell->face_indices())
            if (is_contact_face(cell, face))
              {
                cell->get_dof_indices(dofs);
                f(dofs, face);
              }
    }
    /**
     * Call f(dof, i) for each multiplier DoF on a contact face of the
     * non-artificial cells, in the multiplier DoFHandler's numbering (i: its
     * index in the cell; a DoF of several faces is visited once per face).
     */
    template <typename Function>
    void
    for_each_contact_multiplier_dof(const Function &f) const
    {
      for_each_contact_multiplier_face(
          [&](const std::vector<types::global_dof_index> &dofs, const unsigned int face) {
            for (const unsigned int i : multiplier_face_dofs(face))
              f(dofs[i], i);
          });
    }
    /**
     * The measure of the model at @p x: 2πr (r = x₁) in an axisymmetric model,
     * whose integrals are over the solid of revolution, 1 otherwise (2D: per
     * unit thickness).
     */
    double
    radial_weight(const Point<dim> &x) const
    {
      return axisymmetric ? 2. * numbers::PI * x[0] : 1.;
    }
  };

  /** One face of Γc on a locally owned cell, and where its points start. */
  template <int dim> struct ContactFace
  {
    typename DoFHandler<dim>::active_cell_iterator cell;
    unsigned int                                   face_no;
    unsigned int                                   first_point;
    /**
     * The face's own contact quadrature: the rule of `Contact quadrature` on
     * each segment between the projections of the master's vertices (2D,
     * deformable master), so the master's piecewise shape functions are
     * integrated exactly; null: `contact_quadrature` on the whole face.
     */
    std::shared_ptr<const Quadrature<dim - 1>> segments;
    /**
     * With the nodal (Gauss–Lobatto) contact quadrature on a face whose
     * Jacobian is not constant (not a parallelogram): the consistent weights
     * W_q = ∫_F ℓ_q dΓ of its points (ℓ_q the Lagrange polynomial of point q),
     * which replace the lumped weights w_q J(ξ_q) (doc/formulation.md,
     * "Contact quadrature"); null elsewhere, where both agree.
     */
    std::shared_ptr<const std::vector<double>> nodal_weights;
    /**
     * With a dual multiplier basis (FEPair::dual_multiplier()): the face's
     * A = D M⁻¹, ψ_p = Σ_r A_pr φ_r over the face's nodes (ascending base
     * index of the multiplier element); null: the standard basis.
     */
    std::shared_ptr<const FullMatrix<double>> dual_basis;

    /** The contact points of this face: its segments' rule, else @p contact_quadrature. */
    const Quadrature<dim - 1> &
    points(const Quadrature<dim - 1> &contact_quadrature) const
    {
      return segments ? *segments : contact_quadrature;
    }
  };

  /**
   * Evaluation of the fields on one contact face at the points of a face
   * quadrature: used by the assembly, the loops and the output alike.
   */
  template <int dim> class FaceEvaluator
  {
  public:
    /**
     * With @p follow_segments (the contact quadrature), a face with its own
     * quadrature (ContactFace::segments) is evaluated at its points, else at
     * those of @p quadrature, and its consistent nodal weights
     * (ContactFace::nodal_weights) are the points' JxW.
     */
    FaceEvaluator(const ContactSpaces<dim>  &spaces,
                  const Quadrature<dim - 1> &quadrature,
                  const bool                 follow_segments = true);
    /**
     * Evaluate the multipliers in the standard basis even with a dual one:
     * at a node this gives its coefficient λ_j (the output).
     */
    void
    use_nodal_coefficients()
    {
      nodal_coefficients = true;
    }
    void
    reinit(const ContactFace<dim> &face, const TrilinosWrappers::MPI::Vector &ghosted_solution);
    ContactKinematics<dim>
    kinematics(const unsigned int q) const;
    /** Number of points of the face of the last reinit(). */
    unsigned int
    n_points() const
    {
      return u_now.size();
    }

    std::unique_ptr<FEFaceValues<dim>>   u_values;
    std::unique_ptr<FEFaceValues<dim>>   m_values;
    std::vector<types::global_dof_index> u_dofs;
    /** monolithic indices of the multiplier DoFs with support on the face */
    std::vector<types::global_dof_index> m_dofs;
    /** cell-local indices of those DoFs in the multiplier element */
    std::vector<unsigned int> m_local;
    /** the basis function ψ of multiplier @p a (index in m_dofs) at point @p q */
    double
    psi(const unsigned int a, const unsigned int q) const
    {
      return m_shapes(a, q);
    }
    /** all of them, (a, q) */
    const Table<2, double> &
    multiplier_shapes() const
    {
      return m_shapes;
    }

  private:
    /**
     * The multiplier DoFs with support on face @p face_no of the multiplier
     * cell @p m_cell: their monolithic and cell-local indices (m_dofs,
     * m_local) and their coefficients in @p ghosted.
     */
    void
    gather_multipliers(const typename DoFHandler<dim>::active_cell_iterator &m_cell,
                       const unsigned int                                    face_no,
                       const TrilinosWrappers::MPI::Vector                  &ghosted);
    /**
     * ψ_a of each gathered multiplier at the points, into m_shapes: φ_a, or
     * with the face's dual basis @p dual (A = D M⁻¹; null: the standard
     * basis) Σ_r A_pr φ_(r, c).
     */
    void
    evaluate_multiplier_shapes(const FullMatrix<double> *dual);
    /** The displacement at the points in @p ghosted and at the step's start. */
    void
    evaluate_displacements(const TrilinosWrappers::MPI::Vector &ghosted);

    const ContactSpaces<dim> &spaces;
    const Quadrature<dim - 1> quadrature;
    const bool                follow_segments;
    /** the quadrature u_values and m_values were built for (null: `quadrature`) */
    const Quadrature<dim - 1> *current = nullptr;
    /** the consistent nodal weights of the face of the last reinit(), if any */
    const std::vector<double>  *weights = nullptr;
    std::vector<Tensor<1, dim>> u_now, u_start;
    std::vector<double>         m_coefficients;
    Table<2, double>            m_shapes;
    bool                        nodal_coefficients = false;
  };
} // namespace StabilizedLagrangian
