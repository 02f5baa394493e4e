#pragma once

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe.h>
#include <deal.II/fe/fe_values.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <stabilized_lagrangian/boundary_conditions/interface.h>
#include <stabilized_lagrangian/contact/contact_boundary.h>
#include <stabilized_lagrangian/contact/contact_surface.h>
#include <stabilized_lagrangian/contact/partner.h>
#include <stabilized_lagrangian/discretization/fe_pair.h>
#include <stabilized_lagrangian/geometry/body_mesh.h>
#include <stabilized_lagrangian/materials/body_response.h>
#include <stabilized_lagrangian/materials/quadrature_history.h>
#include <stabilized_lagrangian/parameters.h>
#include <stabilized_lagrangian/solver/loop_policy.h>
#include <stabilized_lagrangian/solver/newton_solver.h>
#include <stabilized_lagrangian/solver/scene_bounds.h>

#include <functional>
#include <utility>
#include <memory>
#include <string>
#include <vector>

/**
 * @file
 * The assembly of the monolithic Newton system [u | λ_n, Λ] at the iterate
 * (doc/formulation.md): the bodies' internal forces and tangent, the boundary
 * conditions' loads, the contact terms of Γc.
 */

namespace StabilizedLagrangian
{
  using namespace dealii;

  /**
   * @brief The assembly of the Newton system's residual and (optionally)
   * Jacobian at the current iterate with the contact statuses, thresholds and
   * pairings frozen (or, with the generalized Newton, linearised): the volume
   * terms of the bodies (BodyResponse, with F-bar, mixed and axisymmetric), the
   * boundary conditions' face and DoF terms, the contact terms of the contact
   * conditions on Γc, and the tangent predictor's K Δū; and the measures of
   * the assembled residual the Newton iteration stops on (assembly.cc).
   *
   * It reads the problem and writes the system through a View, built by the
   * problem for each assembly; it keeps nothing between assemblies.
   */
  template <int dim> class SystemAssembler
  {
  public:
    /**
     * @brief What the assembly reads and writes of the problem: views of its
     * members, and the one operation only the problem can do.
     */
    struct View
    {
      // --- the input and the discretisation, read
      MPI_Comm                                                                communicator;
      const LoopPolicy                                                       &loops;
      const std::vector<std::unique_ptr<BoundaryConditions::Interface<dim>>> &boundary_conditions;
      /** what the boundary conditions read of the problem */
      const BoundaryConditions::Problem<dim> boundary_problem;
      /** `Obstacle/Motion`: checked finite at every assembly */
      const std::shared_ptr<Parameters::BoundaryFunction<dim>> &obstacle_translation;
      const std::shared_ptr<Parameters::BoundaryFunction<dim>> &obstacle_rotation;
      const BodyMesh<dim>                                      &body_mesh;
      const Discretization::FEPair<dim>                        &fe_pair;
      const FiniteElement<dim>                                 &fe_u;
      const FiniteElement<dim>                                 &fe_m;
      const DoFHandler<dim>                                    &dof_handler_u;
      const Quadrature<dim>                                    &cell_quadrature;
      const Quadrature<dim - 1>                                &contact_quadrature;
      const bool                                                axisymmetric;
      /** the model and formulation of each cell, and its response */
      const Materials::BodyResponse<dim> &body_response;
      // --- the iterate and the contact, read
      /** relevant: the iterate */
      const TrilinosWrappers::MPI::Vector          &ghosted_solution;
      const ContactSpaces<dim>                     &spaces;
      const std::unique_ptr<Contact::Partner<dim>> &partner;
      const ContactPointLaw<dim>                   &law;
      /** hanging nodes + homogeneous Dirichlet */
      const AffineConstraints<double> &newton_constraints;
      /** hanging nodes only */
      const AffineConstraints<double> &hanging_constraints;
      /** relevant: the Dirichlet increment Δū of the load step */
      const TrilinosWrappers::MPI::Vector &dirichlet_increment;
      /** set by the predictor around its assembly alone: add K Δū */
      const bool &dirichlet_predictor;
      // --- what the measures of the residual read
      const IndexSet &locally_owned_u;
      /** owned: the iterate */
      const TrilinosWrappers::MPI::Vector &solution;
      /** 1, r_n or r_t per owned row */
      const TrilinosWrappers::MPI::Vector &residual_scaling;
      /** the multiplier element component (0: λ_n, 1..: Λ) of each owned multiplier row */
      const std::vector<std::pair<types::global_dof_index, unsigned int>>
          &owned_multiplier_components;
      /** the bodies' size: what an iterate may not exceed */
      const SceneBounds &bounds;
      /** E_max h_min^(dim−2), for the floor of the force scale */
      const double &nodal_stiffness;
      // --- what the assembly writes
      TrilinosWrappers::SparseMatrix &system_matrix;
      TrilinosWrappers::MPI::Vector  &system_rhs;
      /** owned: the nodal internal forces ∫σ:∇φ_i (reactions included) */
      TrilinosWrappers::MPI::Vector &internal_force;
      /** owned: the contact terms of the residual, without constraints (for the reactions) */
      TrilinosWrappers::MPI::Vector &contact_residual;
      /** owned: the nodal external (Neumann, spring, plate) forces */
      TrilinosWrappers::MPI::Vector &external_force;
      /** owned, multiplier rows: the weight that turns the row's residual into a length */
      TrilinosWrappers::MPI::Vector &multiplier_length_weights;
      /** the first material state outside its admissible range the assembly met, or empty */
      std::string &inadmissible_state;
      /** the trial material history of every quadrature point */
      Materials::QuadratureHistory &material_history;
      /** Γc: its points' states are refreshed as the loops fold them in (LoopPolicy) */
      ContactBoundary<dim> &contact;
      /** the counts of assemblies and Jacobians */
      WorkCounters &work;
      // --- what only the problem can do
      /** re-pair the contact points (a deformable master, folded into the generalized Newton) */
      std::function<void()> update_pairings;
    };

    /** @brief An assembler of the system @p view shows. */
    explicit SystemAssembler(const View &view)
        : view(view)
    {
    }

    /**
     * @brief Assemble the residual, and with @p assemble_matrix the Jacobian,
     * at the iterate; every rank learns whether one of them met an
     * inadmissible material state (inadmissible_state).
     */
    void
    assemble(const bool assemble_matrix);

    /**
     * @brief The last assembled residual's max norm in force units (the
     * multiplier rows scaled by r_n, r_t).
     */
    double
    residual_norm() const;

    /**
     * @brief The blocks of the last assembled residual against their scales
     * (doc/formulation.md, "Newton stopping criterion").
     */
    ScaledResidual
    scaled_residual() const;

  private:
    /**
     * The work space of the volume assembly of one cell: the values of the
     * displacement's shape functions, the cell's DoFs and coefficients, and
     * its matrix and residual (assembly.cc).
     */
    struct VolumeScratch;

    /** The bodies' internal forces and tangent, and their boundary loads. */
    void
    assemble_volume(const bool assemble_matrix);
    /**
     * The volume terms of @p cell at the iterate (its DoFs and coefficients in
     * @p scratch) into @p scratch's matrix and residual; false, with the
     * message in inadmissible_state, where a material state is inadmissible.
     */
    bool
    add_cell_terms(const typename DoFHandler<dim>::active_cell_iterator &cell,
                   VolumeScratch                                        &scratch,
                   const bool                                            assemble_matrix);
    /**
     * Add the boundary conditions' face terms (the tractions of the Neumann
     * conditions and the springs) on @p cell's faces to @p scratch's residual
     * (the springs' stiffness to its matrix), and the external force they make
     * to external_force.
     */
    void
    add_boundary_loads(const typename DoFHandler<dim>::active_cell_iterator &cell,
                       VolumeScratch                                        &scratch,
                       const bool                                            assemble_matrix);
    /** The contact terms of every contact face of this rank. */
    void
    assemble_contact(const bool assemble_matrix);
    /** Add a local system to the global one (with the tangent predictor, if pending). */
    void
    add_to_global_system(const FullMatrix<double>                   &local_matrix,
                         Vector<double>                             &local_rhs,
                         const std::vector<types::global_dof_index> &dofs,
                         const bool                                  assemble_matrix);

    const View view;
  };
} // namespace StabilizedLagrangian
