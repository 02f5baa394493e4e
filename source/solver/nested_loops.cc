// The nested fixed points of seed §2.2 (NestedLoops; doc/formulation.md,
// "Nested loops"): geometry loop → friction loop → status loop → Newton, and
// the view of the problem they read.

#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <stabilized_lagrangian/solver/contact_problem.h>
#include <stabilized_lagrangian/solver/nested_loops.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

namespace StabilizedLagrangian
{
  unsigned int
  first_equal(const std::vector<std::vector<unsigned char>> &seen,
              const std::vector<unsigned char>              &statuses,
              const unsigned int                             end,
              const MPI_Comm                                 communicator)
  {
    // collective: equal on every rank
    for (unsigned int i = 0; i < end; ++i)
      if (Utilities::MPI::min(seen[i] == statuses ? 1u : 0u, communicator) == 1)
        return i;
    return end;
  }

  template <int dim>
  NestedLoops<dim>::NestedLoops(const View &problem)
      : problem(problem)
  {
  }

  template <int dim>
  bool
  NestedLoops<dim>::solve_load_step(StepStatistics &stats)
  {
    // an attempt whose fixed friction thresholds could not hold the loads
    // (fold_friction_for_slipping_contact()) is repeated with s = μ λ_n
    // linearised (seed §2.3)
    if (problem.contact_start.friction_folded)
      {
        ++stats.folded_loops;
        return fold_for_this_step(Loop::friction, [&]() { return geometry_loop(stats); });
      }
    return geometry_loop(stats);
  }

  template <int dim>
  double
  NestedLoops<dim>::relative_displacement_change(
      const TrilinosWrappers::MPI::Vector &previous) const
  {
    double change = 0., size = 0.;
    for (const auto index : problem.locally_owned_u)
      {
        change = std::max(change, std::abs(problem.solution(index) - previous(index)));
        size   = std::max(size, std::abs(problem.solution(index)));
      }
    change = Utilities::MPI::max(change, problem.communicator);
    // a diverged iterate may not enlarge its own yardstick (SceneBounds)
    size = problem.bounds.displacement_scale(Utilities::MPI::max(size, problem.communicator));
    return size > 0. ? change / size : change;
  }

  template <int dim>
  bool
  NestedLoops<dim>::geometry_loop(StepStatistics &stats)
  {
    // folded into Newton, the pairing is re-evaluated at every iterate
    const bool iterate = problem.loops.iterates(Loop::geometry);
    for (unsigned int k = 1; k <= problem.parameters.geometry_max_iterations; ++k)
      {
        stats.geometry_iterations = k;
        {
          TimerOutput::Scope scope(problem.timer, "contact search");
          problem.update_pairings();
        }
        const TrilinosWrappers::MPI::Vector previous = problem.solution;
        if (!friction_loop(stats, k))
          return false;
        if (!iterate)
          return true;
        const double change = relative_displacement_change(previous);
        if (change <= problem.parameters.geometry_tolerance ||
            (k > 1 && loop_stops_adaptively(previous, change, "geometry", stats)))
          return true;
      }
    // the pairing re-evaluated at every Newton iterate instead
    problem.pcout
        << "  geometry loop: no convergence in " << problem.parameters.geometry_max_iterations
        << " iterations (Nonlinear solver/Geometry loop/Maximum iterations); the pairing is "
           "folded into the generalized Newton for this load step\n";
    ++stats.folded_loops;
    ++stats.geometry_iterations;
    return fold_for_this_step(Loop::geometry, [&]() {
      return friction_loop(stats, problem.parameters.geometry_max_iterations + 1);
    });
  }

  template <int dim>
  bool
  NestedLoops<dim>::friction_loop(StepStatistics &stats, const unsigned int k)
  {
    if (!problem.loops.iterates(Loop::friction))
      {
        ++stats.friction_iterations;
        return status_loop(stats, k, 1);
      }
    for (unsigned int j = 1; j <= problem.parameters.friction_max_iterations; ++j)
      {
        ++stats.friction_iterations;
        const TrilinosWrappers::MPI::Vector previous = adaptive_reference();
        if (!status_loop(stats, k, j))
          return false;
        const double change = update_friction_thresholds();
        if (change <= problem.parameters.friction_tolerance ||
            (j > 1 && loop_stops_adaptively(previous, change, "friction", stats)))
          return true;
      }
    // The fixed point on s = μ λ_n does not contract on this step: the
    // generalized Newton linearises the threshold instead (seed §2.3), which
    // converges where the fixed point cycles.
    problem.pcout
        << "  friction loop: no convergence in " << problem.parameters.friction_max_iterations
        << " iterations (Nonlinear solver/Friction loop/Maximum iterations); the friction "
           "threshold is folded into the generalized Newton for this load step\n";
    ++stats.folded_loops;
    ++stats.friction_iterations;
    return fold_for_this_step(Loop::friction, [&]() {
      return status_loop(stats, k, problem.parameters.friction_max_iterations + 1);
    });
  }

  template <int dim>
  bool
  NestedLoops<dim>::loop_stops_adaptively(const TrilinosWrappers::MPI::Vector &previous,
                                          const double                         relative_change,
                                          const char                          *loop,
                                          StepStatistics                      &stats)
  {
    // Adaptive stopping of a loop of the nest (doc/formulation.md, "Adaptive
    // stopping"): the change its last iteration made to the displacement
    // stands for the error left by stopping it, as the last update does for
    // Newton. A loop's first iteration is not tested (its callers start at
    // the second): its change carries the load increment or the outer
    // loop's update, not this loop's error.
    if (!problem.parameters.adaptive_stopping)
      return false;
    TrilinosWrappers::MPI::Vector change = problem.solution;
    change -= previous;
    const double energy = problem.newton.displacement_energy(change);
    if (!problem.newton.below_discretisation_error(energy, relative_change))
      return false;
    ++stats.adaptive_stops;
    if (problem.log_newton)
      problem.pcout << "  " << loop << " loop stops adaptively: last change " << energy
                    << " sqrt(N mm), relative " << relative_change
                    << ", estimated discretisation error " << problem.newton.last_estimate().error
                    << " sqrt(N mm), relative " << problem.newton.last_estimate().relative()
                    << "\n";
    return true;
  }

  template <int dim>
  TrilinosWrappers::MPI::Vector
  NestedLoops<dim>::adaptive_reference() const
  {
    return problem.parameters.adaptive_stopping ? problem.solution
                                                : TrilinosWrappers::MPI::Vector();
  }

  template <int dim>
  bool
  NestedLoops<dim>::fold_for_this_step(const Loop loop, const std::function<bool()> &solve)
  {
    const bool chosen    = problem.loops.fold(loop);
    const bool converged = solve();
    problem.loops.fold(loop, chosen);
    return converged;
  }

  template <int dim>
  bool
  NestedLoops<dim>::status_loop(StepStatistics &stats, const unsigned int k, const unsigned int j)
  {
    if (problem.loops.linearised(Loop::status))
      {
        // the statuses are those of the converged iterate by construction
        ++stats.status_iterations;
        return problem.newton.solve(stats, k, j, 1);
      }
    // the statuses each iteration started from: with s and the pairing
    // frozen, statuses seen before lead to the same Newton solution, so a
    // repeat is a cycle that never ends
    std::vector<std::vector<unsigned char>> seen{problem.contact.conditions().contact_statuses()};
    std::string                             reason;
    for (unsigned int i = 1; i <= problem.parameters.status_max_iterations; ++i)
      {
        ++stats.status_iterations;
        const TrilinosWrappers::MPI::Vector previous = adaptive_reference();
        if (!problem.newton.solve(stats, k, j, i))
          return false;
        const unsigned int changes              = update_statuses();
        stats.inner_loops.back().status_changes = changes;
        // the statuses have no relative measure: the energy of the change alone
        if (changes == 0 || (i > 1 && loop_stops_adaptively(previous, 0., "status", stats)))
          return true;
        seen.push_back(problem.contact.conditions().contact_statuses());
        const unsigned int repeated =
            first_equal(seen, seen.back(), seen.size() - 1, problem.communicator);
        if (repeated < seen.size() - 1)
          {
            reason = "the statuses after iteration " + std::to_string(i) +
                     " repeat those after iteration " + std::to_string(repeated) + " (a cycle)";
            break;
          }
      }
    if (reason.empty())
      reason = "no convergence in " + std::to_string(problem.parameters.status_max_iterations) +
               " iterations (Nonlinear solver/Status loop/Maximum iterations)";
    // The active-set fixed point cycles or stalls: the semismooth Newton on
    // the statuses (a primal-dual active set method) converges locally
    // superlinearly where the fixed point cycles, so it takes over for the step.
    problem.pcout << "  status loop: " << reason
                  << "; the statuses are folded into the generalized Newton for this load step\n";
    ++stats.folded_loops;
    ++stats.status_iterations;
    const bool converged = fold_for_this_step(Loop::status, [&]() {
      return problem.newton.solve(stats, k, j, static_cast<unsigned int>(seen.size()));
    });
    // Under a frozen threshold s the residual jumps where a point opens (its
    // traction s P_B and its Λ row switch off while s stays): a point that
    // carried pressure and loses it then has no consistent status (closed,
    // the frozen friction pulls it open; open, it penetrates), and the
    // folded statuses cycle as the fixed point did. With s = μ λ_n
    // linearised (seed §2.3) the traction vanishes with the pressure: the
    // attempt is repeated so (solve_load_step()).
    if (!converged && !problem.contact_start.friction_folded &&
        !problem.loops.linearised(Loop::friction) && problem.any_pressure_dependent_threshold())
      {
        problem.contact_start.fold_friction = true;
        problem.pcout << "  status loop: the folded statuses did not converge under this friction "
                         "iteration's frozen thresholds; the step is repeated with the friction "
                         "threshold folded into the generalized Newton\n";
      }
    return converged;
  }

  template <int dim>
  unsigned int
  NestedLoops<dim>::update_statuses()
  {
    TimerOutput::Scope scope(problem.timer, "contact search");
    return problem.contact.conditions().update_statuses();
  }

  template <int dim>
  double
  NestedLoops<dim>::update_friction_thresholds()
  {
    TimerOutput::Scope scope(problem.timer, "contact search");
    return problem.contact.conditions().update_thresholds();
  }

  template <int dim>
  typename NestedLoops<dim>::View
  ContactProblem<dim>::nested_loops_view()
  {
    return typename NestedLoops<dim>::View{
        solver_parameters,
        output_parameters.log_newton,
        mpi_communicator,
        pcout,
        timer,
        locally_owned_u,
        solution,
        bounds,
        contact,
        loops,
        contact_start,
        newton,
        [this]() { update_pairings(true); },
        [this]() { return contact_zones.any_pressure_dependent_threshold(); }};
  }

  // Explicit instantiation of the members defined in this file.
#define SL_INSTANTIATE(dim)        \
  template class NestedLoops<dim>; \
  template typename NestedLoops<dim>::View ContactProblem<dim>::nested_loops_view();

  SL_INSTANTIATE(2)
  SL_INSTANTIATE(3)
#undef SL_INSTANTIATE
} // namespace StabilizedLagrangian
