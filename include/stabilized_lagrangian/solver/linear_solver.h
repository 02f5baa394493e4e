#pragma once

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <string>

namespace StabilizedLagrangian
{
  namespace LinearSolvers
  {
    using namespace dealii;

    /**
     * @brief Solve J x = b with a Trilinos Amesos sparse direct solver.
     * @param solver_name Amesos solver: Amesos_Klu, Amesos_Mumps or Amesos_Superludist
     * @return false if the factorisation failed (a singular system)
     */
    bool
    solve_direct(const TrilinosWrappers::SparseMatrix &matrix,
                 TrilinosWrappers::MPI::Vector        &x,
                 const TrilinosWrappers::MPI::Vector  &b,
                 const std::string                    &solver_name);
  } // namespace LinearSolvers
} // namespace StabilizedLagrangian
