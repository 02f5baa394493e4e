#include <stabilized_lagrangian/solver/linear_solver.h>

#include <Amesos.h>
#include <Amesos_BaseSolver.h>
#include <Amesos_Mumps.h>
#include <Epetra_LinearProblem.h>

#include <cmath>

namespace StabilizedLagrangian
{
  namespace LinearSolvers
  {
    DirectSolver::DirectSolver(const std::string &solver_name, const bool null_pivot_detection)
        : solver_name(solver_name)
        , null_pivot_detection(null_pivot_detection)
    {
    }

    DirectSolver::~DirectSolver() = default;

    void
    DirectSolver::reset()
    {
      solver.reset();
      problem.reset();
      factored_matrix = nullptr;
    }

    bool
    DirectSolver::solve(const TrilinosWrappers::SparseMatrix &matrix,
                        TrilinosWrappers::MPI::Vector        &x,
                        const TrilinosWrappers::MPI::Vector  &b)
    {
      // Amesos takes non-const pointers but modifies neither the matrix nor b
      auto &A   = const_cast<Epetra_CrsMatrix &>(matrix.trilinos_matrix());
      auto &rhs = const_cast<Epetra_MultiVector &>(
          static_cast<const Epetra_MultiVector &>(b.trilinos_vector()));
      if (factored_matrix != &matrix)
        {
          reset();
          problem = std::make_unique<Epetra_LinearProblem>(&A, &x.trilinos_vector(), &rhs);
          Amesos factory;
          solver.reset(factory.Create(solver_name.c_str(), *problem));
          if (auto *mumps = dynamic_cast<Amesos_Mumps *>(solver.get());
              mumps && null_pivot_detection)
            mumps->SetICNTL(24, 1);
          if (!solver || solver->SymbolicFactorization() != 0)
            {
              reset();
              return false;
            }
          factored_matrix = &matrix;
        }
      problem->SetLHS(&x.trilinos_vector());
      problem->SetRHS(&rhs);
      if (solver->NumericFactorization() != 0 || solver->Solve() != 0)
        {
          reset();
          return false;
        }
      return std::isfinite(x.linfty_norm());
    }
  } // namespace LinearSolvers
} // namespace StabilizedLagrangian
