#pragma once

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <array>
#include <memory>
#include <string>

class Amesos_BaseSolver;
class Epetra_LinearProblem;

namespace StabilizedLagrangian
{
  namespace LinearSolvers
  {
    using namespace dealii;

    /**
     * @brief Set the BLAS (OpenBLAS) and OpenMP threads of this process to
     * @p n_threads, whatever the environment says, so that the dense kernels of
     * the direct solver round the same way on every machine of a kind.
     * @return what was set, and which environment variables it overrides, for the log
     */
    std::string
    set_threads(const unsigned int n_threads);

    /**
     * @brief Trilinos Amesos sparse direct solver for the Newton systems.
     *
     * The sparsity pattern of the Newton matrix is fixed for a whole run, so
     * the symbolic factorisation (ordering, elimination tree) is computed once
     * and only the numeric factorisation is redone at each Newton iteration.
     */
    class DirectSolver
    {
    public:
      /**
       * @param solver_name Amesos solver: Amesos_Klu, Amesos_Mumps or Amesos_Superludist
       * @param null_pivot_detection MUMPS only: return one solution of a singular
       * system (null pivots detected, ICNTL(24)) instead of failing
       * @param workspace_increase MUMPS only: percent added to the estimated work
       * space (ICNTL(14)); quadrupled on each retry of a factorisation that ran short
       */
      explicit DirectSolver(const std::string &solver_name,
                            const bool         null_pivot_detection = false,
                            const int          workspace_increase   = 20);
      ~DirectSolver();

      /**
       * @brief Solve J x = b.
       * @return false if the factorisation failed (a singular system) or x is not finite
       */
      bool
      solve(const TrilinosWrappers::SparseMatrix &matrix,
            TrilinosWrappers::MPI::Vector        &x,
            const TrilinosWrappers::MPI::Vector  &b);

      /** @brief Forget the symbolic factorisation (after the sparsity pattern changed). */
      void
      reset();

      /** @brief Why the last solve failed, in words (MUMPS's INFOG where it applies). */
      const std::string &
      last_error() const;

      /** @brief What the last solve had to redo (a larger work space), or empty. */
      const std::string &
      last_retry() const;

    private:
      /** One factorisation (the symbolic one if the matrix is new) and solve. */
      bool
      factor_and_solve(const TrilinosWrappers::SparseMatrix &matrix,
                       TrilinosWrappers::MPI::Vector        &x,
                       const TrilinosWrappers::MPI::Vector  &b);
      /** Collective: MUMPS's INFOG(1), INFOG(2) of the failed factorisation, then reset(). */
      std::array<int, 2>
      mumps_infog(const TrilinosWrappers::SparseMatrix &matrix);

      const std::string                     solver_name;
      const bool                            null_pivot_detection;
      std::unique_ptr<Epetra_LinearProblem> problem;
      std::unique_ptr<Amesos_BaseSolver>    solver;
      const void                           *factored_matrix = nullptr;
      /** ICNTL(14): percent added to MUMPS's estimated work space */
      int         workspace_margin;
      std::string error, retry_note;
    };
  } // namespace LinearSolvers
} // namespace StabilizedLagrangian
