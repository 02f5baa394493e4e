#pragma once

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/tensor.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe.h>
#include <deal.II/fe/fe_values.h>

#include <deal.II/grid/tria.h>

#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <stabilized_lagrangian/boundary_conditions/interface.h>
#include <stabilized_lagrangian/contact/contact_boundary.h>
#include <stabilized_lagrangian/contact/contact_edge.h>
#include <stabilized_lagrangian/contact/contact_surface.h>
#include <stabilized_lagrangian/materials/body_response.h>
#include <stabilized_lagrangian/materials/material.h>
#include <stabilized_lagrangian/materials/quadrature_history.h>
#include <stabilized_lagrangian/postprocessing/statistics.h>
#include <stabilized_lagrangian/solver/stress_recovery.h>

#include <array>
#include <functional>
#include <memory>
#include <set>
#include <vector>

/**
 * @file
 * The residual a posteriori error estimate of a converged state
 * (doc/formulation.md, "Error estimate"): the indicators η_K that drive the
 * adaptive refinement, the energy estimate of the adaptive stopping and the
 * pressure estimate of Γc.
 */

namespace StabilizedLagrangian
{
  using namespace dealii;

  /** @brief The energy estimate η and the solution's energy norm, at an iterate. */
  struct EnergyEstimate
  {
    double error       = 0.; ///< η, √(N mm)
    double energy_norm = 0.; ///< (∫ P:∇u)^½, √(N mm)
    /** @brief η against the energy norm (0 for an undeformed body) */
    double
    relative() const
    {
      return energy_norm > 0. ? error / energy_norm : 0.;
    }
  };

  /**
   * @brief The residual error estimate of a state: for each cell K
   *
   *   η_K² = (1/E_K) [ h_K² ‖div P‖²_K + ½ Σ_F h_F ‖⟦P N⟧‖²_F + Σ_{F⊂Γ} h_F ‖P N − t̄‖²_F ]
   *        + η_{C,K}²,
   *
   * η_{C,K}² the contact terms of its faces on Γc (doc/formulation.md, "Error
   * estimate"). It reads the state through a View and owns nothing but its
   * scratch; made where an estimate is asked.
   */
  template <int dim> class ErrorEstimator
  {
  public:
    using TriaCell = typename Triangulation<dim>::cell_iterator;
    using DoFCell  = typename DoFHandler<dim>::active_cell_iterator;

    /**
     * What the estimate reads of the problem: views of its members, and the
     * material evaluations of the committed state (their history and kept
     * volume change live in the problem).
     */
    struct View
    {
      const Triangulation<dim>  &triangulation;
      const DoFHandler<dim>     &displacement_dofs;
      const FiniteElement<dim>  &displacement_fe;
      const Quadrature<dim>     &cell_quadrature;
      const Quadrature<dim - 1> &contact_quadrature;
      const ContactSpaces<dim>  &spaces;
      /** Γc: its faces and their points' states */
      const ContactBoundary<dim>          &contact;
      const TrilinosWrappers::MPI::Vector &ghosted_solution; ///< the iterate, relevant
      /** the evaluation of a contact point's state and the law there */
      const ContactPointLaw<dim>                                             &law;
      const std::set<types::boundary_id>                                     &contact_boundaries;
      const std::set<types::boundary_id>                                     &master_boundaries;
      const std::vector<std::unique_ptr<BoundaryConditions::Interface<dim>>> &boundary_conditions;
      const BoundaryConditions::Problem<dim>                                  boundary_problem;
      const MPI_Comm                                                          communicator;
      const ReferenceCell                                                     cell_shape;
      const bool                                                              simplex;
      const bool                                                              axisymmetric;
      /** a pressure below it is round-off (ContactProblem::negligible_pressure) */
      const double negligible_pressure;
      /** the bodies' materials and the committed state's response (with the F-bar fields) */
      const Materials::BodyResponse<dim> &body_response;
      /** written: the ghost cells' committed history, copied from their owners */
      Materials::QuadratureHistory &ghost_history;
    };

    /** @brief An estimator of the state @p view shows. */
    explicit ErrorEstimator(const View &view)
        : view(view)
    {
    }

    /**
     * @brief The estimate of the converged state @p u (ghosted displacement)
     * of a load step: the totals (η, its contact part, the pressure estimate,
     * the energy norm of the solution) into @p stats; returns η_K of every
     * locally owned cell (0 on the others).
     */
    Vector<float>
    estimate(const TrilinosWrappers::MPI::Vector &u, StepStatistics &stats);

    /**
     * @brief The energy estimate η alone, of the iterate @p u (adaptive
     * stopping): no pressure estimate, no indicators.
     */
    EnergyEstimate
    energy_estimate(const TrilinosWrappers::MPI::Vector &u);

    /**
     * @brief Where the pressure estimate's mismatch is, for a `Target pressure
     * error`: ∫_F (p* − λ_n)² of each locally owned cell's faces on Γc, of the
     * converged state @p u (0 on the cells without such a face).
     */
    Vector<float>
    pressure_indicators(const TrilinosWrappers::MPI::Vector &u);

  private:
    /**
     * The residual terms of every locally owned cell: the volume, face and
     * boundary ones into @p squared, the contact ones into @p contact
     * (squared, N mm); returns ∫ P:∇u over the owned cells.
     */
    double
    residual_indicators(const TrilinosWrappers::MPI::Vector &u,
                        Vector<double>                      &squared,
                        Vector<double>                      &contact);
    /** Copy the committed material history of the ghost cells from their owners. */
    void
    share_ghost_history();
    /** The material of a cell. */
    const Materials::Interface<dim> &
    material_of(const TriaCell &cell) const
    {
      return view.body_response.material_of(cell);
    }
    /** The hoop strain u_r / r of an axisymmetric model, 0 otherwise (on the axis ∂u_r/∂r). */
    double
    hoop_strain(const Point<dim> &x, const Tensor<1, dim> &u, const Tensor<2, dim> &grad_u) const
    {
      return view.body_response.hoop_strain(x, u, grad_u);
    }
    /** The Gauss rule of the faces with @p n points per direction. */
    Quadrature<dim - 1>
    face_gauss(const unsigned int n) const
    {
      return view.cell_shape.face_reference_cell(0).template get_gauss_type_quadrature<dim - 1>(n);
    }
    /**
     * First Piola–Kirchhoff stress of @p cell's material for @p grad_u at
     * @p point, with the history of the cell's quadrature point nearest to it
     * (axisymmetric: @p hoop the hoop strain u_r/r there).
     */
    Tensor<2, dim>
    stress_at(const TriaCell       &cell,
              const Tensor<2, dim> &grad_u,
              const Point<dim>     &point,
              const double          hoop = 0.) const;
    /** Add h_K² ‖div P‖²_K / E to @p squared; return ∫ P:∇u over the owned cells. */
    double
    add_volume_residuals(const TrilinosWrappers::MPI::Vector &u, Vector<double> &squared) const;
    /** Add the stress jumps of the interior faces and the boundary residuals to @p squared. */
    void
    add_face_residuals(const TrilinosWrappers::MPI::Vector &u, Vector<double> &squared);
    /**
     * Add ½ h ‖⟦P N⟧‖² to each owned side of the face between @p a (seen by
     * @p on_a, its gradients @p gradients_a) and @p b (gradients @p gradients_b
     * at the same points).
     */
    void
    add_jump(const TrilinosWrappers::MPI::Vector &u,
             const TriaCell                      &a,
             const FEFaceValuesBase<dim>         &on_a,
             const std::vector<Tensor<2, dim>>   &gradients_a,
             const TriaCell                      &b,
             const std::vector<Tensor<2, dim>>   &gradients_b,
             double                               h,
             Vector<double>                      &squared) const;
    /**
     * Simplex meshes (deal.II 9.4 has no FESubfaceValues for them): the jump
     * across the hanging face @p face of @p fine, with the fine side's face
     * rule and the coarse side's gradients at the same points.
     */
    void
    add_hanging_jump(const TrilinosWrappers::MPI::Vector           &u,
                     const DoFCell                                 &fine,
                     unsigned int                                   face,
                     const typename DoFHandler<dim>::cell_iterator &coarse,
                     FEFaceValues<dim>                             &fine_values,
                     Vector<double>                                &squared) const;
    /**
     * Add h_F ‖P N − t̄‖²_F / E of face @p f on the boundary, in the components
     * no Dirichlet condition prescribes (t̄ the Neumann traction, 0 on a free face).
     */
    void
    add_boundary_residual(const DoFCell                       &cell,
                          unsigned int                         f,
                          const TrilinosWrappers::MPI::Vector &u,
                          FEFaceValues<dim>                   &face_values,
                          Vector<double>                      &squared) const;
    /** Add the contact terms of the faces of Γc to @p contact. */
    void
    add_contact_residuals(const TrilinosWrappers::MPI::Vector &u, Vector<double> &contact) const;
    /**
     * The pressure estimate: the relative L2 mismatch on Γc between the normal
     * traction of the recovered stress (StressRecovery) and λ_n; each face's
     * squared mismatch added to its cell's entry of @p per_cell where given.
     */
    double
    pressure_estimate(const TrilinosWrappers::MPI::Vector &u,
                      Vector<double>                      *per_cell = nullptr) const;
    /** The stress of @p u at the Barlow points of a cell, for StressRecovery. */
    typename StressRecovery<dim>::Sampler
    barlow_sampler(const TrilinosWrappers::MPI::Vector &u) const;
    /**
     * The square-root onset of the pressure fitted to the contact points of
     * @p face (evaluated by @p nodes, the contact quadrature), with the pair's
     * modulus; not valid() unless the face holds the end of the contact zone.
     */
    Contact::SquareRootOnset<dim>
    square_root_onset(const ContactFace<dim> &face,
                      FaceEvaluator<dim>     &nodes,
                      const Tensor<1, dim>   &normal,
                      double                  master_compliance) const;
    /** (1 − ν²)/E of the body holding a deformable master surface; 0 without one. */
    double
    deformable_master_compliance() const;

    const View view;
  };
} // namespace StabilizedLagrangian
