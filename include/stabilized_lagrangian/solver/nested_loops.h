#pragma once

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <deal.II/lac/trilinos_vector.h>

#include <stabilized_lagrangian/contact/contact_boundary.h>
#include <stabilized_lagrangian/parameters.h>
#include <stabilized_lagrangian/postprocessing/statistics.h>
#include <stabilized_lagrangian/solver/loop_policy.h>
#include <stabilized_lagrangian/solver/newton_solver.h>
#include <stabilized_lagrangian/solver/scene_bounds.h>

#include <functional>
#include <memory>
#include <vector>

/**
 * @file
 * The nested fixed points of seed §2.2 (doc/formulation.md, "Nested loops"):
 * geometry loop → friction loop → status loop → Newton
 * (source/solver/nested_loops.cc).
 */

namespace StabilizedLagrangian
{
  using namespace dealii;

  /**
   * @brief Collective: the first of the first @p end of @p seen equal to
   * @p statuses on every rank of @p communicator, or @p end if none is (a
   * repeat of contact statuses: a cycle of the active set).
   */
  unsigned int
  first_equal(const std::vector<std::vector<unsigned char>> &seen,
              const std::vector<unsigned char>              &statuses,
              const unsigned int                             end,
              const MPI_Comm                                 communicator);

  /**
   * @brief The loops of seed §2.2 around the Newton iteration of a load step:
   * the geometry loop (the pairing), the friction loop (the threshold
   * s = μ λ_n) and the status loop (open/stick/slip), each a fixed point with
   * its own tolerance, `Stopping = adaptive` for each, and the fallback of a
   * fixed point that cycles or does not converge: its quantity folded into
   * the generalized Newton of seed §2.3 for the step (LoopPolicy).
   *
   * It owns nothing that outlives a load step; it reads the problem through a
   * View and calls the problem's NewtonSolver, the one the generalized Newton
   * calls alike.
   */
  template <int dim> class NestedLoops
  {
  public:
    /**
     * @brief What the loops read and write of the problem: views of its
     * members, and the operations only the problem can do.
     */
    struct View
    {
      // --- the input, read
      const Parameters::NonlinearSolver &parameters;
      bool                               log_newton; ///< `Output/Log Newton`
      MPI_Comm                           communicator;
      const ConditionalOStream          &pcout;
      TimerOutput                       &timer;
      // --- the iterate, read (Newton moves it)
      const IndexSet &locally_owned_u;
      /** owned: the monolithic iterate */
      const TrilinosWrappers::MPI::Vector &solution;
      /** the bodies' size: the yardstick of a loop's relative change */
      const SceneBounds &bounds;
      /** Γc: its conditions' statuses and thresholds */
      const ContactBoundary<dim> &contact;
      // --- what the loops write
      /** a loop that cycles is folded into the generalized Newton for one step */
      LoopPolicy &loops;
      /** the fold of the friction loop that repeats the step (ContactStart::fold_friction) */
      ContactStart &contact_start;
      /** the Newton iteration at the loops' iterate */
      NewtonSolver<dim> &newton;
      // --- what only the problem can do
      /** re-pair every contact point, the contact faces' segments first */
      std::function<void()> update_pairings;
      /** whether some zone's threshold depends on the pressure */
      std::function<bool()> any_pressure_dependent_threshold;
    };

    /** @brief The loops on the problem @p problem views. */
    explicit NestedLoops(const View &problem);

    /**
     * @brief Solve a load step by the nested loops (statistics into
     * @p stats): true when they converged; false, with the reason printed,
     * when the step must be cut or repeated.
     */
    bool
    solve_load_step(StepStatistics &stats);

    /**
     * @brief The status loop's update, also where new contact points take the
     * statuses of the iterate: returns the number of changed statuses.
     */
    unsigned int
    update_statuses();

    /**
     * @brief The friction loop's update of the thresholds s = μ λ_n, also
     * where new contact points take those of the iterate: returns the
     * relative change.
     */
    double
    update_friction_thresholds();

  private:
    /** The geometry loop: re-pair, then the friction loop, until the displacement settles. */
    bool
    geometry_loop(StepStatistics &stats);
    /** The friction loop in geometry iteration @p geometry_iteration. */
    bool
    friction_loop(StepStatistics &stats, const unsigned int geometry_iteration);
    /** The status loop in the friction iteration @p friction_iteration of @p geometry_iteration. */
    bool
    status_loop(StepStatistics    &stats,
                const unsigned int geometry_iteration,
                const unsigned int friction_iteration);
    /** The largest change of the displacement since @p previous, relative to its size. */
    double
    relative_displacement_change(const TrilinosWrappers::MPI::Vector &previous) const;
    /**
     * The displacement a loop's change is measured from with `Stopping =
     * adaptive` (a copy of the solution); an empty vector otherwise, which
     * loop_stops_adaptively() does not read.
     */
    TrilinosWrappers::MPI::Vector
    adaptive_reference() const;
    /**
     * `Nonlinear solver/Stopping = adaptive` for a loop of the nest (@p loop
     * names it in the log): NewtonSolver::below_discretisation_error() for
     * the energy of the displacement change of its last iteration,
     * solution − @p previous, and @p relative_change, the measure of its own
     * criterion.
     */
    bool
    loop_stops_adaptively(const TrilinosWrappers::MPI::Vector &previous,
                          const double                         relative_change,
                          const char                          *loop,
                          StepStatistics                      &stats);
    /**
     * Run @p solve with @p loop folded into the generalized Newton, then
     * restore the method chosen: the fallback of a fixed point that cycles or
     * does not converge in its iterations.
     */
    bool
    fold_for_this_step(const Loop loop, const std::function<bool()> &solve);

    /** the problem's members and operations */
    View problem;
  };
} // namespace StabilizedLagrangian
