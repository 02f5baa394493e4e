#include <stabilized_lagrangian/solver/linear_solver.h>

#include <Amesos.h>
#include <Amesos_BaseSolver.h>
#include <Amesos_Mumps.h>
#include <Epetra_LinearProblem.h>

#include <dlfcn.h>

#include <deal.II/base/mpi.h>

#include <array>
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

    DirectSolver::DirectSolver(const std::string &solver_name,
                               const bool         null_pivot_detection,
                               const int          workspace_increase)
        : solver_name(solver_name)
        , null_pivot_detection(null_pivot_detection)
        , workspace_margin(workspace_increase)
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

    namespace
    {
      /** MUMPS's INFOG(1) < 0 in words (MUMPS 5 user's guide, §8). */
      std::string
      mumps_error(const int infog1, const int infog2)
      {
        const std::string code = "MUMPS INFOG(1) = " + std::to_string(infog1) +
                                 ", INFOG(2) = " + std::to_string(infog2) + ": ";
        switch (infog1)
          {
          case -6:
            return code + "the matrix is structurally singular";
          case -10:
            return code + "the matrix is numerically singular";
          case -5:
          case -7:
          case -13:
            return code + "the factorisation could not allocate its memory (out of memory)";
          case -8:
          case -9:
          case -11:
          case -14:
          case -15:
          case -17:
          case -20:
            return code + "the factorisation's work space is too small";
          default:
            return code + "the factorisation failed";
          }
      }

      /** Whether INFOG(1) says that a larger work space (ICNTL(14)) would do. */
      bool
      workspace_too_small(const int infog1)
      {
        return infog1 == -8 || infog1 == -9 || infog1 == -11 || infog1 == -14 || infog1 == -15 ||
               infog1 == -17 || infog1 == -20;
      }
    } // namespace

    bool
    DirectSolver::solve(const TrilinosWrappers::SparseMatrix &matrix,
                        TrilinosWrappers::MPI::Vector        &x,
                        const TrilinosWrappers::MPI::Vector  &b)
    {
      // MUMPS estimates its work space at the analysis and adds ICNTL(14)
      // percent (20 by default); pivoting on an indefinite saddle point can
      // need more. Where the factorisation says the space was too small, it is
      // redone with the margin quadrupled, a few times.
      error.clear();
      retry_note.clear();
      for (unsigned int attempt = 0;; ++attempt)
        {
          if (factor_and_solve(matrix, x, b))
            return true;
          const std::array<int, 2> infog = mumps_infog(matrix);
          if (infog[0] >= 0)
            {
              error = solver_name + " failed (a singular system, or a solution that is not finite)";
              return false;
            }
          error = mumps_error(infog[0], infog[1]);
          if (!workspace_too_small(infog[0]) || attempt == 3)
            return false;
          workspace_margin = std::max(4 * workspace_margin, 20);
          retry_note = error + "; factorised again with the work space increase ICNTL(14) = " +
                       std::to_string(workspace_margin) + " percent";
          reset();
        }
    }

    bool
    DirectSolver::factor_and_solve(const TrilinosWrappers::SparseMatrix &matrix,
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
          if (auto *mumps = dynamic_cast<Amesos_Mumps *>(solver.get()))
            {
              if (null_pivot_detection)
                mumps->SetICNTL(24, 1);
              mumps->SetICNTL(14, workspace_margin);
            }
          if (!solver || solver->SymbolicFactorization() != 0)
            return false;
          factored_matrix = &matrix;
        }
      problem->SetLHS(&x.trilinos_vector());
      problem->SetRHS(&rhs);
      if (solver->NumericFactorization() != 0 || solver->Solve() != 0)
        return false;
      return std::isfinite(x.linfty_norm());
    }

    std::array<int, 2>
    DirectSolver::mumps_infog(const TrilinosWrappers::SparseMatrix &matrix)
    {
      // INFOG is defined on the host (rank 0) only
      std::array<int, 2> infog = {{0, 0}};
      if (auto *mumps = dynamic_cast<Amesos_Mumps *>(solver.get()))
        if (dealii::Utilities::MPI::this_mpi_process(matrix.get_mpi_communicator()) == 0)
          infog = {{mumps->GetINFOG()[0], mumps->GetINFOG()[1]}};
      reset();
      return dealii::Utilities::MPI::broadcast(matrix.get_mpi_communicator(), infog, 0);
    }

    const std::string &
    DirectSolver::last_error() const
    {
      return error;
    }

    const std::string &
    DirectSolver::last_retry() const
    {
      return retry_note;
    }
  } // namespace LinearSolvers
} // namespace StabilizedLagrangian
