#include <stabilized_lagrangian/solver/linear_solver.h>

#include <Amesos.h>
#include <Amesos_BaseSolver.h>
#include <Amesos_Mumps.h>
#include <Epetra_LinearProblem.h>

#include <dlfcn.h>

#include <cmath>
#include <cstdlib>

namespace StabilizedLagrangian
{
  namespace LinearSolvers
  {
    std::string
    set_threads(const unsigned int n_threads)
    {
      // The BLAS behind MUMPS is a Debian alternative (OpenBLAS or the
      // reference BLAS) and OpenMP may or may not be linked in: the setters are
      // looked up at run time and called where they exist. OpenBLAS reads
      // OPENBLAS_NUM_THREADS when it is loaded, before main(); the setter
      // overrides it.
      std::string report;
      for (const char *setter : {"openblas_set_num_threads", "omp_set_num_threads"})
        if (void *symbol = dlsym(RTLD_DEFAULT, setter))
          {
            reinterpret_cast<void (*)(int)>(symbol)(static_cast<int>(n_threads));
            report += (report.empty() ? "" : ", ") + std::string(setter);
          }
      std::string overridden;
      for (const char *variable : {"OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS"})
        if (const char *value = std::getenv(variable))
          overridden += std::string(" ") + variable + "=" + value;
      return std::to_string(n_threads) + " BLAS/OpenMP thread(s) per rank (" +
             (report.empty() ? std::string("no threaded BLAS found") : "set by " + report) +
             (overridden.empty() ? std::string(")")
                                 : "; the environment's" + overridden + " is overridden)");
    }

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
