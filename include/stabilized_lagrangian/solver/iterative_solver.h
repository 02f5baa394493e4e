#pragma once

#include <deal.II/base/index_set.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <memory>
#include <string>
#include <vector>

namespace StabilizedLagrangian
{
  namespace LinearSolvers
  {
    using namespace dealii;

    /**
     * @brief GMRES with a block-triangular preconditioner for the Newton
     * systems `Linear solver/Method = iterative` (doc/formulation.md,
     * "Iterative linear solver").
     *
     * The Newton matrix, displacements first and multipliers after them,
     *
     *     J = [ K  B ]      P = [ K̂  B ]
     *         [ C  D ],         [ 0  Ŝ ],    Ŝ = D − C diag(K)⁻¹ B,
     *
     * is solved by right-preconditioned GMRES with P: K̂⁻¹ is one V-cycle of
     * algebraic multigrid (Trilinos ML) on K with the rigid-body modes as its
     * near-null space, Ŝ the Schur complement with K replaced by its
     * diagonal, a sparse matrix on the multipliers only (they live on Γc),
     * factorised by a direct solver. With K̂ = K and Ŝ the exact Schur
     * complement GMRES would converge in two iterations (Murphy, Golub and
     * Wathen 2000); the approximations trade iterations for cost.
     */
    class BlockIterativeSolver
    {
    public:
      /**
       * @param owned the locally owned rows of the Newton matrix
       * @param n_u the number of displacement DoFs (the first block)
       * @param n_components the displacement's components
       * @param near_null_space the AMG's near-null space (the rigid-body
       *   modes), each over the displacement's locally owned DoFs
       * @param higher_order_elements quadratic displacements (the AMG's setting)
       * @param augmentation_factor c in Γ = c diag(C diag(K)⁻¹ B)⁻¹ (0: no augmentation)
       * @param max_iterations GMRES iterations before the solve is declared failed
       */
      BlockIterativeSolver(const IndexSet                         &owned,
                           const types::global_dof_index           n_u,
                           const MPI_Comm                          communicator,
                           const unsigned int                      n_components,
                           const std::vector<std::vector<double>> &near_null_space,
                           const bool                              higher_order_elements,
                           const double                            augmentation_factor,
                           const unsigned int                      max_iterations);
      ~BlockIterativeSolver();

      /**
       * @brief Solve J x = b to |W (b − J x)| ≤ @p relative_tolerance |W b|,
       * W = diag(@p row_weights) (the Newton residual's scaling: 1 on the
       * displacement rows, r_n and r_t on the multipliers').
       * @return false if GMRES did not reach it, or x is not finite
       */
      bool
      solve(const TrilinosWrappers::SparseMatrix &matrix,
            TrilinosWrappers::MPI::Vector        &x,
            const TrilinosWrappers::MPI::Vector  &b,
            const TrilinosWrappers::MPI::Vector  &row_weights,
            const double                          relative_tolerance);

      /** @brief GMRES iterations of the last solve. */
      unsigned int
      last_iterations() const
      {
        return iterations;
      }

      /** @brief Wall time (s, this rank) of the last solve's phases. */
      struct PhaseTimes
      {
        double amg_setup    = 0.; ///< the blocks K̃, B, C, D taken from J and the AMG of K̃
        double schur        = 0.; ///< Ŝ formed and factorised
        double krylov       = 0.; ///< GMRES with the preconditioner's applications
        double schur_solves = 0.; ///< of which the solves with the factorised Ŝ
      };
      const PhaseTimes &
      last_times() const
      {
        return times;
      }

      /** @brief The blocks of Ŝ inverted in place on this rank at the last set-up (0: Ŝ factorised
       * whole). */
      unsigned int
      n_local_blocks() const
      {
        return block_rows.size();
      }

      /** @brief Why the last solve failed, in words. */
      const std::string &
      last_error() const
      {
        return error;
      }

      /** @brief Apply P⁻¹ (the preconditioner's interface for GMRES). */
      void
      vmult(TrilinosWrappers::MPI::Vector &dst, const TrilinosWrappers::MPI::Vector &src) const;

    private:
      /** K̃, B, C, D from @p matrix, then the AMG of K̃ and the factorised Ŝ. */
      void
      set_up(const TrilinosWrappers::SparseMatrix &matrix);

      /**
       * B, C, D and Cᵀ from @p matrix, and K̃'s pattern (K's and Cᵀ C's, made
       * once per pattern of the Newton matrix) with K's values.
       */
      void
      extract_blocks(const TrilinosWrappers::SparseMatrix &matrix);

      /**
       * Γ on the multiplier rows that only constrain the displacement, from
       * C diag(K)⁻¹ Cᵀ with @p inverse_diagonal = diag(K)⁻¹, and K̃ = K + Cᵀ Γ C
       * (doc/iterative_solver.md).
       */
      void
      augment_displacement_block(const TrilinosWrappers::MPI::Vector &inverse_diagonal);

      /** The smoothed-aggregation AMG of K̃ with the near-null space, aggregating whole nodes. */
      void
      initialize_amg();

      /** Ŝ = D − C diag(K̃)⁻¹ B, @p inverse_diagonal = diag(K̃)⁻¹, on the union of the patterns. */
      void
      form_schur_complement(const TrilinosWrappers::MPI::Vector &inverse_diagonal);

      /**
       * Where Ŝ falls apart into small blocks that each rank owns whole (a
       * nodal contact quadrature against a rigid partner: each multiplier
       * couples only with its own node), invert them in place: no serial
       * factorisation, no gather (doc/scaling.md). False on every rank if some
       * rank's Ŝ does not (collective).
       */
      bool
      invert_local_blocks();

      /** Ŝ's blocks (their rows, as local indices among owned_m) and their inverses. */
      std::vector<std::vector<unsigned int>> block_rows;
      std::vector<FullMatrix<double>>        block_inverses;

      const MPI_Comm                communicator;
      const types::global_dof_index n_u;
      IndexSet                      owned_u, owned_m;
      const unsigned int            n_components;
      /** the near-null space, mode after mode (ML's layout), alive as long as the AMG */
      std::vector<double>            near_null_space;
      unsigned int                   n_modes;
      const bool                     higher_order_elements;
      const double                   augmentation_factor;
      const unsigned int             max_iterations;
      TrilinosWrappers::SparseMatrix B, C, D, schur;
      /** Cᵀ, and K̃ = K + Cᵀ Γ C, the displacement block of the augmented system (K is not kept) */
      TrilinosWrappers::SparseMatrix C_transposed, augmented;
      /** Γ: the weights of the multipliers' rows added to the displacement's */
      TrilinosWrappers::MPI::Vector                   augmentation;
      TrilinosWrappers::PreconditionAMG               amg;
      SolverControl                                   schur_control;
      std::unique_ptr<TrilinosWrappers::SolverDirect> schur_factorisation;
      mutable TrilinosWrappers::MPI::Vector           r_u, r_m, y_u, y_m, t_m;
      /** 1 / the row weights of the last solve */
      TrilinosWrappers::MPI::Vector inverse_weights;
      unsigned int                  iterations = 0;
      mutable PhaseTimes            times;
      std::string                   error;
      /** whether K̃, B, C, D have their patterns for the Newton matrix's (set_up() once) */
      bool blocks_ready = false;
    };
  } // namespace LinearSolvers
} // namespace StabilizedLagrangian
