#pragma once

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/timer.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <stabilized_lagrangian/contact/contact_boundary.h>
#include <stabilized_lagrangian/contact/contact_surface.h>
#include <stabilized_lagrangian/contact/partner.h>
#include <stabilized_lagrangian/parameters.h>

#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

/**
 * @file
 * The numerical inf-sup test of the displacement / multiplier pair
 * (source/solver/inf_sup_test.cc): β_h on a sequence of meshes
 * (`--inf-sup N`), or on each refinement cycle's mesh (`Contact/Check inf-sup`).
 */

namespace StabilizedLagrangian
{
  using namespace dealii;

  /** @brief One row of the numerical inf-sup test (InfSupTest::run). */
  struct InfSupRecord
  {
    double                  contact_mesh_size      = 0.; ///< largest face diameter on Γc
    types::global_dof_index displacement_dofs      = 0;
    types::global_dof_index normal_multiplier_dofs = 0;
    double                  beta                   = 0.; ///< discrete inf-sup constant β_h
  };

  /**
   * @brief The discrete inf-sup constant of the normal trace pairing,
   *
   *   β_h = inf_μ sup_v ∫Γc μ (v·n) / (‖μ‖_{-1/2,h} ‖v‖_1),
   *
   * the square root of the smallest eigenvalue of S x = β² M x with
   * S = B K⁻¹ Bᵀ, B_aj = ∫Γc ψ_a (φ_j·n), K the H¹ Gram matrix of the
   * displacement (Dirichlet DoFs removed) and M the multiplier Gram matrix of
   * the mesh-dependent norm ‖μ‖²_{-1/2,h} = Σ_F h_F ‖μ‖²_{L²(F)}
   * (doc/fe_pairs.md). It owns the β_h of the run's cycles so far
   * (`Contact/Check inf-sup`), and reads the discretisation through a View.
   * One MPI rank.
   */
  template <int dim> class InfSupTest
  {
  public:
    /** The discretisation β_h is computed on: views of the problem's members, now. */
    struct View
    {
      MPI_Comm                  communicator;
      const DoFHandler<dim>    &displacement_dofs;
      const FiniteElement<dim> &displacement_fe;
      const IndexSet           &locally_owned_u;
      const IndexSet           &locally_relevant_u;
      types::global_dof_index   n_displacement_dofs;
      const Quadrature<dim>    &cell_quadrature;
      /** a Gauss rule on the faces exact for B and M */
      const Quadrature<dim - 1> trace_quadrature;
      /** add u_i = 0 on the Dirichlet boundaries (and the axis) to the constraints */
      const std::function<void(AffineConstraints<double> &)> add_dirichlet_constraints;
      /** the multiplier element component (0: λ_n) of each owned multiplier row */
      const std::vector<std::pair<types::global_dof_index, unsigned int>> &multiplier_components;
      /** the hanging-node (and coarser multiplier mesh) constraints */
      const AffineConstraints<double> &hanging_constraints;
      /** Γc: its faces */
      const ContactBoundary<dim>          &contact;
      const ContactSpaces<dim>            &spaces;
      const TrilinosWrappers::MPI::Vector &ghosted_solution;
      const Contact::Partner<dim>         &partner;
      const std::string                   &direct_solver; ///< of K's solves
    };

    /**
     * @brief The test of the pair @p contact names, on @p communicator,
     * reporting to @p pcout.
     */
    InfSupTest(MPI_Comm                   communicator,
               const Parameters::Contact &contact,
               const ConditionalOStream  &pcout);

    /** @brief β_h of the FE pair on the mesh @p view shows. */
    InfSupRecord
    compute(const View &view) const;

    /**
     * @brief β_h on @p n_meshes meshes, printed and written to inf_sup.csv in
     * @p directory; @p mesh(k) makes mesh k (k = 1: the scene's) and returns
     * its view.
     */
    void
    run(unsigned int                                  n_meshes,
        const std::string                            &directory,
        const std::function<View(unsigned int mesh)> &mesh) const;

    /**
     * @brief `Contact/Check inf-sup`: β_h on the mesh of cycle @p cycle, kept,
     * with a warning when it is zero or has fallen below 0.8 of its largest
     * earlier value (timed in @p timer). One MPI rank; a note and nothing
     * else on more.
     */
    void
    check(const View &view, unsigned int cycle, TimerOutput &timer);

    /** @brief Whether check() computes β_h in this run (the check asked for, one rank). */
    bool
    checked() const
    {
      return check_asked && one_rank;
    }

    /** @brief The β_h of the latest check (0 before the first). */
    double
    latest_beta() const
    {
      return betas.empty() ? 0. : betas.back();
    }

  private:
    /** The H¹ Gram matrix K of the displacement, with @p constraints. */
    static void
    assemble_h1_gram(const View                      &view,
                     const AffineConstraints<double> &constraints,
                     TrilinosWrappers::SparseMatrix  &gram_u);
    /**
     * The rows of B, B_aj = ∫Γc ψ_a (φ_j·n), and the multiplier Gram matrix M
     * of the mesh-dependent norm, for the λ_n DoFs numbered by @p normal_row;
     * returns the largest contact face diameter.
     */
    static double
    assemble_trace_pairing(const View                                            &view,
                           const AffineConstraints<double>                       &constraints,
                           const std::map<types::global_dof_index, unsigned int> &normal_row,
                           std::vector<TrilinosWrappers::MPI::Vector>            &trace_rows,
                           FullMatrix<double>                                    &gram_m);
    /** P of μ = P μ_free: the λ_n DoFs as combinations of the unconstrained ones. */
    static FullMatrix<double>
    multiplier_prolongation(const View                                            &view,
                            const std::map<types::global_dof_index, unsigned int> &normal_row);

    MPI_Comm                  communicator;
    const ConditionalOStream &pcout;
    const std::string         fe_pair;     ///< `Contact/Finite element pair`, for messages
    const bool                check_asked; ///< `Contact/Check inf-sup`
    const bool                one_rank;
    /** β_h of each cycle's mesh so far */
    std::vector<double> betas;
  };
} // namespace StabilizedLagrangian
