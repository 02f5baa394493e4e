#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_solver.h>

#include <stabilized_lagrangian/solver/linear_solver.h>

#include <cmath>

namespace StabilizedLagrangian
{
  namespace LinearSolvers
  {
    bool
    solve_direct(const TrilinosWrappers::SparseMatrix &matrix,
                 TrilinosWrappers::MPI::Vector        &x,
                 const TrilinosWrappers::MPI::Vector  &b,
                 const std::string                    &solver_name)
    {
      SolverControl                                  control(1, 0.);
      TrilinosWrappers::SolverDirect::AdditionalData data(false, solver_name);
      TrilinosWrappers::SolverDirect                 solver(control, data);
      try
        {
          solver.solve(matrix, x, b);
        }
      catch (const std::exception &)
        {
          return false;
        }
      return std::isfinite(x.linfty_norm());
    }
  } // namespace LinearSolvers
} // namespace StabilizedLagrangian
