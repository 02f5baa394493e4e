#pragma once

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_vector.h>

#include <boost/signals2/signal.hpp>

#include <stabilized_lagrangian/boundary_conditions/interface.h>
#include <stabilized_lagrangian/contact/cumulative_slip.h>
#include <stabilized_lagrangian/contact/partner.h>
#include <stabilized_lagrangian/materials/quadrature_history.h>
#include <stabilized_lagrangian/parameters.h>
#include <stabilized_lagrangian/postprocessing/solution_output.h>
#include <stabilized_lagrangian/postprocessing/statistics.h>
#include <stabilized_lagrangian/solver/load_step_controller.h>
#include <stabilized_lagrangian/solver/nested_loops.h>
#include <stabilized_lagrangian/solver/newton_solver.h>
#include <stabilized_lagrangian/solver/run_log.h>
#include <stabilized_lagrangian/solver/run_state.h>
#include <stabilized_lagrangian/solver/scene_bounds.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

/**
 * @file
 * The load path on one mesh (source/solver/load_path.cc): the load steps from
 * rest or from a checkpoint to `Load stepping/End time`, the step cuts, the
 * Dirichlet values and the predictor of a step, and the stop at `Load
 * stepping/Wall time limit`.
 */

namespace StabilizedLagrangian
{
  using namespace dealii;

  /**
   * @brief The load path on the current mesh: each load step's attempt (the
   * state a step cut restores saved, the Dirichlet values applied, the
   * iterate extrapolated with `Predictor = extrapolation`) solved by the
   * nested loops of seed §2.2 (NestedLoops), a failed attempt cut
   * (LoadStepController) or repeated with the friction threshold folded, a
   * converged step committed (its statistics, output, log line, checkpoint),
   * and the stop at `Load stepping/Wall time limit`.
   *
   * It owns the run's wall clock and whether the run stopped at the limit;
   * everything else it reads and writes is the problem's, through a View
   * (where the load stepping stands, the time and the iterate are in the
   * run's state, which a checkpoint keeps).
   */
  template <int dim> class LoadPath
  {
  public:
    /**
     * @brief What the load path reads and writes of the problem: views of its
     * members, and the operations only the problem can do.
     */
    struct View
    {
      // --- the input, read
      const Parameters::LoadStepping    &load_stepping;
      const Parameters::NonlinearSolver &solver_parameters;
      const Parameters::Output          &output_parameters;
      MPI_Comm                           communicator;
      const ConditionalOStream          &pcout;
      TimerOutput                       &timer;
      /** the boundary conditions, whose prescribed values a step applies */
      const std::vector<std::unique_ptr<BoundaryConditions::Interface<dim>>> &boundary_conditions;
      // --- the discretisation and the state of the solver, read
      const IndexSet                               &locally_owned;
      const IndexSet                               &locally_relevant;
      const AffineConstraints<double>              &hanging_constraints;
      const std::unique_ptr<Contact::Partner<dim>> &partner;
      /** why the run must stop rather than cut the load step (empty: it may cut) */
      const std::string  &unrecoverable_failure;
      const WorkCounters &work;
      /** the current cycle's output directory */
      const std::string &output_directory;
      // --- what the load path writes
      double                    &time;
      LoadStepController::State &controller;
      /** the state a step cut restores */
      RunState &state_list;
      /** called at the start of every attempt, once the state is saved */
      boost::signals2::signal<void(double start, double end)> &load_step_attempt;
      /** owned: the monolithic iterate */
      TrilinosWrappers::MPI::Vector       &solution;
      const TrilinosWrappers::MPI::Vector &ghosted_solution;
      /** relevant: the iterate at the step's start */
      TrilinosWrappers::MPI::Vector &step_start;
      /** owned: the last accepted step's change of every unknown, and that step's size */
      TrilinosWrappers::MPI::Vector &last_increment;
      double                        &last_step_size;
      /** relevant: the Dirichlet increment Δū of the step, and whether it is non-zero */
      TrilinosWrappers::MPI::Vector &dirichlet_increment;
      bool                          &dirichlet_increment_nonzero;
      /** the prescribed displacements grow the bounds of an iterate */
      SceneBounds                  &bounds;
      ContactStart                 &contact_start;
      StatisticsWriter             &statistics;
      SolutionOutput<dim>          &solution_output;
      std::vector<Point<dim>>      &active_set;
      CumulativeSlip<dim>          &cumulative_slip;
      Materials::QuadratureHistory &material_history;
      /** the work when the load path began */
      WorkCounters &path_start_work;
      /** the statistics of the last converged step, and its normal force */
      StepStatistics &last_step;
      double         &last_normal_force;
      /** the loops that solve a load step, and their Newton iteration */
      NestedLoops<dim>  &nested_loops;
      NewtonSolver<dim> &newton;
      // --- what only the problem can do
      /** refresh the ghosted copy of the iterate */
      std::function<void()>                             update_ghosts;
      std::function<BoundaryConditions::Problem<dim>()> boundary_view;
      /** the supports statistics.csv has columns for */
      std::function<StatisticsWriter::Supports()> statistics_supports;
      /** sample Γc, commit the step's slip, write the output of a converged step */
      std::function<void(unsigned int step, double time)> commit_converged_step;
      std::function<void(StepStatistics &)>               compute_contact_statistics;
      std::function<void(StepStatistics &)>               estimate_error;
      std::function<void()>                               write_checkpoint;
      /** what the log reads, now */
      std::function<typename RunLog<dim>::View()> run_log_view;
    };

    /** @brief The load path of the problem @p problem views; its wall clock starts now. */
    explicit LoadPath(const View &problem);

    /**
     * @brief The whole load path on the current mesh, from rest, or with
     * @p resumed from the state a checkpoint restored; false if a step could
     * not be solved or the run stopped at the wall-time limit.
     */
    bool
    solve(const bool resumed = false);

    /** @brief Whether the load path stopped at `Load stepping/Wall time limit`. */
    bool
    stopped_at_wall_time_limit() const
    {
      return wall_time_limit_reached;
    }

  private:
    /** Open the output of a load path from rest; the next step is the nominal one. */
    void
    start(LoadStepController &steps);
    /**
     * After a failed attempt (the state restored): cut the step and return
     * true, or report why the path stops and return false.
     */
    bool
    cut_load_step(LoadStepController &steps);
    /** Commit a converged step: its statistics, output and log line. */
    void
    record_load_step(StepStatistics &stats, PathLog &path, const Timer &step_clock);
    /**
     * Warn of a slow pace after the first step; at `Load stepping/Wall time
     * limit`, checkpoint (unless @p checkpointed), report and return true.
     */
    bool
    stop_at_wall_time_limit(const LoadStepController &steps,
                            const PathLog            &path,
                            const bool                checkpointed);
    /**
     * `Nonlinear solver/Predictor = extrapolation`: move the iterate by the
     * last accepted step's change of every unknown, scaled to @p step_size
     * (doc/formulation.md, "Predictor").
     */
    void
    extrapolate_last_step(const double step_size);
    /**
     * The boundary conditions' prescribed values at @p time: the Dirichlet
     * increment Δū of the step, which its first Newton iteration (the tangent
     * predictor) applies.
     */
    void
    apply_dirichlet_values(const double time);

    /** the problem's members and operations */
    View problem;
    /** wall time since the problem was built, for `Load stepping/Wall time limit` */
    Timer run_clock;
    bool  wall_time_limit_reached = false;
  };
} // namespace StabilizedLagrangian
