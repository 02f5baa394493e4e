// The load path on one mesh (LoadPath): load steps and step cuts; each step
// is solved by the loops of nested_loops.cc (NestedLoops). The log's lines and
// the run's summary (the log's block and run_summary.csv) are RunLog's
// (run_log.cc). And the view of the problem the load path reads.

#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <stabilized_lagrangian/solver/contact_problem.h>
#include <stabilized_lagrangian/solver/load_path.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

namespace StabilizedLagrangian
{
  template <int dim>
  LoadPath<dim>::LoadPath(const View &problem)
      : problem(problem)
  {
  }

  namespace
  {
    /** A load path projected to need more than a day is worth a warning. */
    constexpr double seconds_to_warn_of = 24. * 3600.;
  } // namespace

  template <int dim>
  bool
  LoadPath<dim>::solve(const bool resumed)
  {
    LoadStepController steps(problem.load_stepping.end_time,
                             problem.load_stepping.n_steps,
                             problem.load_stepping.max_cuts,
                             problem.controller);
    if (!resumed)
      start(steps);
    problem.timer.reset();
    RunLog<dim>(problem.run_log_view()).print_path_banner();
    if (!resumed)
      problem.commit_converged_step(0, 0.);

    PathLog path(problem.time, problem.work);
    while (steps.before_end(problem.time))
      {
        const double             step_size  = steps.next_step_size(problem.time);
        const double             step_begin = problem.time;
        const RunState::Snapshot saved      = problem.state_list.snapshot();
        StepStatistics           stats;
        stats.step      = steps.step() + 1;
        stats.step_size = step_size;
        stats.cuts      = steps.consecutive_cuts();
        Timer step_clock;
        problem.time = step_begin + step_size;
        problem.load_step_attempt(step_begin, problem.time);
        problem.partner->set_time(step_begin, problem.time);
        extrapolate_last_step(step_size);
        apply_dirichlet_values(problem.time);
        if (!problem.nested_loops.solve_load_step(stats) ||
            !problem.newton.plausible_converged_state())
          {
            saved.restore();
            problem.update_ghosts();
            // the same step again, with the friction threshold folded
            const bool fold =
                problem.contact_start.fold_friction && !problem.contact_start.friction_folded;
            problem.contact_start                 = ContactStart();
            problem.contact_start.friction_folded = fold;
            if (fold)
              continue;
            if (!cut_load_step(steps))
              return false;
            continue;
          }
        steps.accept();
        problem.contact_start = ContactStart();
        record_load_step(stats, path, step_clock);
        const bool checkpointed = problem.output_parameters.checkpoint_interval > 0 &&
                                  steps.step() % problem.output_parameters.checkpoint_interval == 0;
        if (checkpointed)
          problem.write_checkpoint();
        if (stop_at_wall_time_limit(steps, path, checkpointed))
          return false;
      }
    RunLog<dim>(problem.run_log_view()).finish_load_path(steps.step(), path);
    return true;
  }

  template <int dim>
  void
  LoadPath<dim>::start(LoadStepController &steps)
  {
    const bool root = Utilities::MPI::this_mpi_process(problem.communicator) == 0;
    if (root)
      std::filesystem::create_directories(problem.output_directory);
    problem.statistics.open(problem.output_directory, dim, root, problem.statistics_supports());
    problem.solution_output.set_records({});
    problem.active_set.clear();
    problem.cumulative_slip.clear();
    steps.restart();
    problem.path_start_work = problem.work;
    problem.last_step_size  = 0.;
  }

  template <int dim>
  bool
  LoadPath<dim>::cut_load_step(LoadStepController &steps)
  {
    const unsigned int step = steps.step();
    if (!problem.unrecoverable_failure.empty())
      {
        problem.pcout << "ERROR: load step " << step + 1 << " from t = " << problem.time << ": "
                      << problem.unrecoverable_failure
                      << ", which a smaller load step cannot cure. The results of the " << step
                      << " converged steps are in " << problem.output_directory << ".\n";
        return false;
      }
    const double failed_size = steps.step_size();
    if (!steps.cut())
      {
        problem.pcout << "ERROR: load step " << step + 1 << " from t = " << problem.time
                      << " did not converge after " << steps.max_cuts()
                      << " step cuts (Load stepping/Maximum step cuts), with the step "
                      << failed_size << ". The results of the " << step
                      << " converged steps are in " << problem.output_directory << ".\n";
        return false;
      }
    problem.pcout << "  step did not converge; cutting the step to " << steps.step_size() << "\n";
    return true;
  }

  template <int dim>
  void
  LoadPath<dim>::record_load_step(StepStatistics &stats, PathLog &path, const Timer &step_clock)
  {
    stats.failed_newton_iterations = problem.work.newton_iterations -
                                     path.at_step_start.newton_iterations - stats.newton_iterations;
    stats.assemblies   = problem.work.assemblies - path.at_step_start.assemblies;
    stats.jacobians    = problem.work.jacobians - path.at_step_start.jacobians;
    path.at_step_start = problem.work;
    problem.material_history.commit();
    stats.time = problem.time;
    {
      TimerOutput::Scope scope(problem.timer, "contact search");
      problem.compute_contact_statistics(stats);
    }
    problem.estimate_error(stats);
    problem.last_step           = stats;
    problem.last_normal_force   = stats.normal_force;
    path.most_points_in_contact = std::max(path.most_points_in_contact, stats.points_in_contact);
    path.contact_point_count    = stats.contact_points;
    problem.commit_converged_step(stats.step, problem.time);
    for (const auto index : problem.locally_owned)
      problem.last_increment(index) = problem.solution(index) - problem.step_start(index);
    problem.last_increment.compress(VectorOperation::insert);
    problem.last_step_size = stats.step_size;
    problem.step_start     = problem.ghosted_solution;
    stats.wall_time        = step_clock.wall_time();
    problem.statistics.write(stats);
    RunLog<dim>(problem.run_log_view())
        .print_step_line(stats, path.wall_clock.wall_time(), path.start_time);
    if (stats.friction_law_violations > 0 && ++path.friction_law_warnings <= 3)
      problem.pcout
          << "WARNING: load step " << stats.step << ": " << stats.friction_law_report
          << " The Newton criterion accepted this state"
          << (problem.solver_parameters.newton_criterion == Parameters::ResidualCriterion::scaled
                  ? ""
                  : " (with `Nonlinear solver/Newton/Residual = scaled` it would not: the "
                    "absolute residual weighs a stick point's slip by r_t)")
          << "; column friction_law_violations of statistics.csv"
          << (path.friction_law_warnings == 3 ? " (no further warnings)" : "") << ".\n";
  }

  template <int dim>
  bool
  LoadPath<dim>::stop_at_wall_time_limit(const LoadStepController &steps,
                                         const PathLog            &path,
                                         const bool                checkpointed)
  {
    const unsigned int step = steps.step();
    // the slowest rank's clock, so that every rank stops at the same step
    const double elapsed = Utilities::MPI::max(run_clock.wall_time(), problem.communicator);
    // the load path's own pace (setup and earlier cycles left out)
    const double needed = Utilities::MPI::max(path.wall_clock.wall_time(), problem.communicator) /
                          (problem.time - path.start_time) * (steps.end_time() - path.start_time);
    const double limit = problem.load_stepping.wall_time_limit;
    if (step == 1 && limit > 0. && needed > limit)
      problem.pcout << "WARNING: at the pace of the first load step the load path needs ~" << needed
                    << " s, more than `Load stepping/Wall time limit` = " << limit
                    << " s: the run will stop at the limit before its end.\n";
    if (step == 1 && limit == 0. && needed > seconds_to_warn_of)
      problem.pcout << "WARNING: at the pace of the first load step the load path needs ~"
                    << needed / 3600. << " h. Consider fewer load steps, or a `Load stepping/Wall "
                    << "time limit` with checkpoints (`Output/Checkpoint interval`).\n";
    const bool stop = limit > 0. && steps.before_end(problem.time) && elapsed > limit;
    if (!stop)
      return false;
    if (problem.output_parameters.checkpoint_interval > 0 && !checkpointed)
      problem.write_checkpoint();
    problem.pcout << "Stopped at the wall-time limit (Load stepping/Wall time limit = " << limit
                  << " s) after load step " << step << " at t = " << problem.time << ", " << elapsed
                  << " s into the run. The results of the " << step << " converged steps are in "
                  << problem.output_directory
                  << (problem.output_parameters.checkpoint_interval > 0
                          ? "; `--resume` continues from the checkpoint written now.\n"
                          : "; with `Output/Checkpoint interval` > 0 it could be resumed.\n");
    wall_time_limit_reached = true;
    RunLog<dim>(problem.run_log_view()).write_run_summary(step, path.wall_clock.wall_time());
    return true;
  }

  template <int dim>
  void
  LoadPath<dim>::extrapolate_last_step(const double step_size)
  {
    if (!problem.solver_parameters.extrapolate || problem.last_step_size <= 0.)
      return;
    // u⁰_{n+1} = u_n + (Δt_{n+1}/Δt_n)(u_n − u_{n−1}), multipliers included
    problem.solution.add(step_size / problem.last_step_size, problem.last_increment);
    problem.update_ghosts();
  }

  template <int dim>
  void
  LoadPath<dim>::apply_dirichlet_values(const double t)
  {
    std::map<types::global_dof_index, double> values;
    for (const auto &condition : problem.boundary_conditions)
      condition->add_prescribed_values(problem.boundary_view(), t, values);
    double largest_prescribed = 0.;
    for (const auto &entry : values)
      largest_prescribed = std::max(largest_prescribed, std::abs(entry.second));
    problem.bounds.add_prescribed_displacement(
        Utilities::MPI::max(largest_prescribed, problem.communicator));
    // The increment is not added to the iterate here: the step's first Newton
    // iteration, the tangent predictor (predictor_step()), applies it.
    TrilinosWrappers::MPI::Vector increment(problem.locally_owned, problem.communicator);
    for (const auto &[index, value] : values)
      if (problem.locally_owned.is_element(index))
        increment(index) = value - problem.solution(index);
    increment.compress(VectorOperation::insert);
    problem.hanging_constraints.distribute(increment);
    // After an extrapolation, what is left of the Dirichlet increment of a
    // steady motion is round-off: it is added to the iterate directly.
    if (problem.solver_parameters.extrapolate && problem.last_step_size > 0. &&
        increment.linfty_norm() <= 1e-10 * problem.last_increment.linfty_norm())
      {
        problem.solution += increment;
        problem.update_ghosts();
        increment = 0.;
      }
    problem.dirichlet_increment_nonzero = increment.linfty_norm() > 0.;
    problem.dirichlet_increment.reinit(
        problem.locally_owned, problem.locally_relevant, problem.communicator);
    problem.dirichlet_increment = increment;
  }

  template <int dim>
  typename LoadPath<dim>::View
  ContactProblem<dim>::load_path_view()
  {
    return typename LoadPath<dim>::View{
        load_stepping,
        solver_parameters,
        output_parameters,
        mpi_communicator,
        pcout,
        timer,
        boundary_conditions,
        locally_owned,
        locally_relevant,
        hanging_constraints,
        partner,
        unrecoverable_failure,
        work,
        output_directory,
        time,
        controller,
        state_list,
        load_step_attempt,
        solution,
        ghosted_solution,
        step_start,
        last_increment,
        last_step_size,
        dirichlet_increment,
        dirichlet_increment_nonzero,
        bounds,
        contact_start,
        statistics,
        solution_output,
        active_set,
        cumulative_slip,
        material_history,
        path_start_work,
        last_step,
        last_normal_force,
        nested_loops,
        newton,
        [this]() { update_ghosts(); },
        [this]() { return boundary_view(); },
        [this]() { return StepStatisticsCollector<dim>(statistics_view()).supports(); },
        [this](const unsigned int step, const double t) { commit_converged_step(step, t); },
        [this](StepStatistics &stats) {
          StepStatisticsCollector<dim>(statistics_view()).collect(stats);
        },
        [this](StepStatistics &stats) { estimate_error(stats); },
        [this]() { checkpoint.write(); },
        [this]() { return run_log_view(); }};
  }

  // Explicit instantiation of the members defined in this file.
#define SL_INSTANTIATE(dim)     \
  template class LoadPath<dim>; \
  template typename LoadPath<dim>::View ContactProblem<dim>::load_path_view();

  SL_INSTANTIATE(2)
  SL_INSTANTIATE(3)
#undef SL_INSTANTIATE
} // namespace StabilizedLagrangian
