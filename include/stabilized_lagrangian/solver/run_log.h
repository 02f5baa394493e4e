#pragma once

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <deal.II/distributed/tria_base.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <stabilized_lagrangian/contact/partner.h>
#include <stabilized_lagrangian/parameters.h>
#include <stabilized_lagrangian/postprocessing/statistics.h>
#include <stabilized_lagrangian/solver/chosen_parameters.h>
#include <stabilized_lagrangian/solver/inf_sup_test.h>
#include <stabilized_lagrangian/solver/iterative_solver.h>
#include <stabilized_lagrangian/solver/loop_policy.h>
#include <stabilized_lagrangian/solver/newton_solver.h>

#include <map>
#include <string>

/**
 * @file
 * The log of a load path and its summary (source/solver/run_log.cc): the
 * banner that opens it, a line per converged load step, the block that ends
 * it and run_summary.csv.
 */

namespace StabilizedLagrangian
{
  using namespace dealii;

  /** @brief What the log and run_summary.csv gather along a load path. */
  struct PathLog
  {
    PathLog(const double start_time, const WorkCounters &work)
        : start_time(start_time)
        , at_step_start(work)
    {
    }
    Timer        wall_clock;
    double       start_time;
    WorkCounters at_step_start;
    /** the most contact points in contact in any step, and their number */
    unsigned int most_points_in_contact = 0, contact_point_count = 0;
    /** steps whose state breaks the friction law (the first few are named) */
    unsigned int friction_law_warnings = 0;
  };

  /**
   * @brief The log of a load path and its summary: the sizes of the problem
   * and the loops that run once or are folded into Newton, one line per
   * converged load step, the block that ends the log (mesh and DoFs, load
   * steps and Newton iterations, the wall time and its split, the peak
   * memory, the error estimate) and run_summary.csv (one SummaryRow of named
   * columns).
   *
   * It owns nothing: it is made per use from a View of the problem, and
   * computes nothing but what it writes.
   */
  template <int dim> class RunLog
  {
  public:
    /** What the log reads of the problem: views of its members, now. */
    struct View
    {
      MPI_Comm                  communicator;
      const ConditionalOStream &pcout;
      const TimerOutput        &timer;
      /** print the timer's statistics at the end of a load path (rank 0 prints) */
      bool               verbose;
      const std::string &output_directory;
      // --- the discretisation
      const parallel::DistributedTriangulationBase<dim> &triangulation;
      types::global_dof_index                            n_u;
      types::global_dof_index                            n_multipliers;
      const IndexSet                                    &locally_owned;
      const IndexSet                                    &locally_relevant;
      const AffineConstraints<double>                   &hanging_constraints;
      const TrilinosWrappers::SparseMatrix              &system_matrix;
      // --- the methods
      const LoopPolicy &loops;
      bool              any_friction;                     ///< some zone has friction
      bool              any_pressure_dependent_threshold; ///< some zone's s depends on λ_n
      /** r_n, r_t, pointwise or weighted conditions */
      const ChosenParameters         &chosen;
      const Parameters::LinearSolver &linear_solver_parameters;
      /** null with the direct solver */
      const LinearSolvers::BlockIterativeSolver *iterative_solver;
      const Contact::Partner<dim>               &partner;
      /** how often the ghosts grew by the partner's DoFs on this mesh */
      unsigned int           partner_dof_growths;
      const InfSupTest<dim> &inf_sup;
      // --- the load path
      double                  time;
      double                  end_time;   ///< `Load stepping/End time`
      std::string             force_unit; ///< N, or N/mm in plane strain
      const StatisticsWriter &statistics;
      /** the statistics of the last converged load step */
      const StepStatistics &last_step;
      /** the work since the start of the run, and when the load path began */
      const WorkCounters &work;
      const WorkCounters &path_start_work;
    };

    /** @brief The log of the problem @p problem views. */
    explicit RunLog(const View &problem)
        : problem(problem)
    {
    }

    /** @brief The sizes of the problem and the loops that run once or are folded into Newton. */
    void
    print_path_banner() const;

    /**
     * @brief The line of the converged load step @p stats, @p elapsed seconds
     * into the load path this process began at time @p start_time, with the
     * time it projects for the rest at that pace.
     */
    void
    print_step_line(const StepStatistics &stats,
                    const double          elapsed,
                    const double          start_time) const;

    /**
     * @brief The end of a completed load path of @p n_steps steps: the summary
     * block, a warning if hardly any point came into contact, the timer's
     * statistics and run_summary.csv.
     */
    void
    finish_load_path(const unsigned int n_steps, const PathLog &path) const;

    /**
     * @brief run_summary.csv of the load path after @p n_steps steps and
     * @p wall_time seconds, in the output directory (rank 0 writes; collective).
     */
    void
    write_run_summary(const unsigned int n_steps, const double wall_time) const;

  private:
    /**
     * Print the block that ends a run's log: mesh and DoFs, load steps and
     * Newton iterations, the wall time and its split, the peak memory and the
     * error estimate.
     */
    void
    print_run_summary(const unsigned int n_steps, const double wall_time) const;
    /** Collective: the wall time of each timer section on the slowest rank (s). */
    std::map<std::string, double>
    slowest_sections() const;
    /** Collective: the largest peak resident memory of the ranks (MiB). */
    double
    peak_memory() const;
    /** The work done since the load path began, failed attempts included. */
    WorkCounters
    work_on_path() const;

    /** the problem's members */
    View problem;
  };
} // namespace StabilizedLagrangian
