// The line search of the Newton iteration: non-monotone backtracking along
// a Newton update, the full step of the primal-dual active set method while
// the active set settles (ActiveSetWatch), and the log of each trial.

#include <deal.II/base/mpi.h>

#include <stabilized_lagrangian/solver/newton_solver.h>

#include <iomanip>
#include <sstream>

namespace StabilizedLagrangian
{
  template <int dim>
  bool
  NewtonSolver<dim>::settling(ActiveSetWatch &watch) const
  {
    // Frictionless contact (no point sticks), the contact statuses of a full
    // step are new (no iterate of this Newton loop had them, so the step does
    // not close a cycle among the finitely many active sets) and fewer points
    // open or close than at the last step taken so: the active set settles,
    // as in the active set method on the normal condition, which converges
    // without damping. Coulomb's stick/slip switches have no such result (a
    // full step there wanders among the statuses), and stay with the
    // backtracking.
    const auto                        stick    = static_cast<unsigned char>(Contact::Status::stick);
    const auto                        open     = static_cast<unsigned char>(Contact::Status::open);
    const std::vector<unsigned char>  statuses = problem.contact.conditions().statuses();
    const std::vector<unsigned char> &current  = watch.seen.back();
    unsigned int                      changes = 0, sticking = 0;
    for (unsigned int p = 0; p < statuses.size(); ++p)
      {
        changes += (statuses[p] == open) != (current[p] == open);
        sticking += statuses[p] == stick || current[p] == stick;
      }
    changes  = Utilities::MPI::sum(changes, problem.communicator);
    sticking = Utilities::MPI::sum(sticking, problem.communicator);
    if (sticking > 0 || changes == 0 || changes > watch.last_changes ||
        problem.first_equal(watch.seen, statuses, watch.seen.size()) < watch.seen.size())
      return false;
    watch.last_changes = changes;
    return true;
  }

  template <int dim>
  void
  NewtonSolver<dim>::advance(Progress                            &progress,
                             const TrilinosWrappers::MPI::Vector &update,
                             const double                         residual,
                             const unsigned int                   max_halvings)
  {
    line_search(
        update, residual, progress.previous_residual, max_halvings, progress.active_set_watch());
    progress.previous_residual = residual;
    progress.jacobian_current  = false;
    ++progress.iteration;
  }

  template <int dim>
  void
  NewtonSolver<dim>::line_search(const TrilinosWrappers::MPI::Vector &update,
                                 const double                         residual,
                                 const double                         previous_residual,
                                 const unsigned int                   max_halvings,
                                 ActiveSetWatch                      *watch)
  {
    // Non-monotone backtracking. With frozen statuses the residual is only
    // piecewise smooth (stick/slip in P_B, elastic/plastic switches at the
    // quadrature points), so a full Newton step may raise the residual on the
    // way to convergence; it is kept when the residual is below that of the
    // iterate before the current one. Otherwise (a cycle, or a material point
    // outside its admissible range) the step is halved until the residual
    // decreases, at most max_halvings times.
    //
    // When Newton decides the contact statuses, its full step is that of the
    // primal-dual active set method (Hintermüller, Ito & Kunisch 2002; Hüeber,
    // Stadler & Wohlmuth 2008), whose residual rises while the active set is
    // being found (the iterate solves the equations of a set that is not yet
    // the right one). That step is taken whole while the active set settles
    // (settling()).
    const TrilinosWrappers::MPI::Vector start = problem.solution;
    double                              step  = 1.;
    for (unsigned int halving = 0;; ++halving)
      {
        problem.solution = start;
        problem.solution.add(step, update);
        problem.update_ghosts();
        problem.assemble(false);
        if (problem.log_newton)
          log_trial(step);
        if (halving == max_halvings)
          return;
        if (problem.inadmissible_state.empty())
          {
            if (halving == 0 && watch != nullptr && settling(*watch))
              return;
            const double reference = halving == 0 ? previous_residual : residual;
            if (problem.residual_norm() < (1. - 1e-4 * step) * reference)
              return;
          }
        step /= 2.;
      }
  }

  template <int dim>
  void
  NewtonSolver<dim>::log_trial(const double step) const
  {
    unsigned int counts[3] = {0, 0, 0}; // open, stick, slip
    for (const unsigned char status : problem.contact.conditions().statuses())
      ++counts[status];
    std::ostringstream line;
    line << std::setprecision(6) << "      step length " << step << ": residual "
         << problem.residual_norm()
         << (problem.inadmissible_state.empty() ? "" : " (inadmissible material state)")
         << ", open/stick/slip " << Utilities::MPI::sum(counts[0], problem.communicator) << "/"
         << Utilities::MPI::sum(counts[1], problem.communicator) << "/"
         << Utilities::MPI::sum(counts[2], problem.communicator) << "\n";
    problem.pcout << line.str();
  }

  // Explicit instantiation of the members defined in this file.
#define SL_INSTANTIATE(dim)                                                                   \
  template void NewtonSolver<dim>::advance(                                                   \
      Progress &, const TrilinosWrappers::MPI::Vector &, double, unsigned int);               \
  template void NewtonSolver<dim>::line_search(                                               \
      const TrilinosWrappers::MPI::Vector &, double, double, unsigned int, ActiveSetWatch *); \
  template bool NewtonSolver<dim>::settling(ActiveSetWatch &) const;                          \
  template void NewtonSolver<dim>::log_trial(double) const;

  SL_INSTANTIATE(2)
  SL_INSTANTIATE(3)
#undef SL_INSTANTIATE
} // namespace StabilizedLagrangian
