#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <deal.II/numerics/vector_tools.h>

#include <stabilized_lagrangian/postprocessing/safe_files.h>
#include <stabilized_lagrangian/solver/contact_problem.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <algorithm>
#include <iomanip>
#include <sstream>

namespace StabilizedLagrangian
{
  // The load path: load steps and step cuts; each step is solved by the
  // loops of nested_loops.cc (NestedLoops). The log's lines and the run's
  // summary (the log's block and run_summary.csv) are RunLog's (run_log.cc).

  template <int dim>
  bool
  ContactProblem<dim>::run(const bool resume)
  {
    const bool root = Utilities::MPI::this_mpi_process(mpi_communicator) == 0;
    run_directory   = output_parameters.directory;
    // nothing is written before the input is known to be good: the mesh and
    // the boundary names are checked by setup()
    setup();
    if (!resume)
      solution_output.prepare_directory(output_directory);
    const unsigned int first_cycle = resume ? checkpoint.restore() : 0;
    // the estimate of the restored (converged) state, which the cycle's row
    // and the summary report if the checkpoint ended the cycle's load path
    if (resume)
      estimate_error(last_step);
    if (root)
      SafeFiles::write_atomically(run_directory + "/parameters.prm", parameters_used);

    // Adaptive refinement (`Adaptive refinement/Cycles`, 0 by default): the
    // load path is solved on each mesh in turn; the last one writes into the
    // output directory. With a target, the cycles stop once it is met.
    const unsigned int n_cycles = adaptive_refinement.cycles;
    start_cycle_log(resume);
    const bool measure_cycles =
        adaptive_refinement.errors_against_last_cycle && n_cycles > 0 && !resume;
    CycleTotals totals;
    for (cycle = first_cycle; cycle <= n_cycles; ++cycle)
      {
        const bool resumed = resume && cycle == first_cycle;
        if (cycle > 0 && !resumed)
          {
            TimerOutput::Scope scope(timer, "setup");
            MeshRefinement<dim>(refinement_view()).refine();
            time = 0.;
            pcout << "Refinement cycle " << cycle << " of " << n_cycles << "\n";
          }
        output_directory = cycle_directory(cycle);
        Timer cycle_clock;
        inf_sup.check(inf_sup_view(), cycle, timer);
        const bool converged = solve_load_path(resumed);
        record_cycle(cycle_clock.wall_time(), totals);
        if (!converged)
          return false;
        if (measure_cycles)
          {
            earlier_cycles.push_back(ghosted_displacement());
            cycle_records.emplace_back(n_u, last_step.estimated_error);
          }
        if (adaptive_refinement.targeted() && targets_met())
          break;
      }
    if (measure_cycles)
      write_cycle_errors(run_directory);
    if (adaptive_refinement.targeted())
      finish_targeted_cycles(std::min(cycle, n_cycles), totals);
    return true;
  }

  template <int dim>
  void
  ContactProblem<dim>::start_cycle_log(const bool resume) const
  {
    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0 && adaptive_refinement.cycles > 0 &&
        !resume)
      SafeFiles::write_atomically(run_directory + "/refinement_cycles.csv",
                                  "cycle,cells,displacement_dofs,multiplier_dofs,newton_iterations,"
                                  "normal_force_" +
                                      force_unit(true) +
                                      ",estimated_error_sqrtNmm,estimated_relative_error,"
                                      "estimated_pressure_error,wall_time_s" +
                                      std::string(inf_sup.checked() ? ",inf_sup_beta\n" : "\n"));
    if (adaptive_refinement.errors_against_last_cycle && resume)
      pcout << "WARNING: `Adaptive refinement/Errors against the last cycle` is not measured "
               "on a resumed run (the earlier cycles' displacements are not in the "
               "checkpoint).\n";
  }

  template <int dim>
  std::string
  ContactProblem<dim>::cycle_directory(const unsigned int k) const
  {
    // with a target, which cycle is the last is known only once it is solved
    // (finish_targeted_cycles() moves its output up)
    const bool last = k == adaptive_refinement.cycles && !adaptive_refinement.targeted();
    return last ? run_directory : run_directory + "/cycle-" + std::to_string(k);
  }

  template <int dim>
  void
  ContactProblem<dim>::record_cycle(const double wall_time, CycleTotals &totals) const
  {
    totals.wall_time += wall_time;
    totals.newton_iterations += statistics.cumulative_newton_iterations();
    if (Utilities::MPI::this_mpi_process(mpi_communicator) != 0 || adaptive_refinement.cycles == 0)
      return;
    std::ostringstream row;
    row << cycle << ',' << triangulation.n_global_active_cells() << ',' << n_u << ','
        << n_multipliers << ',' << statistics.cumulative_newton_iterations() << ','
        << std::setprecision(10) << last_normal_force << ',' << last_step.estimated_error << ','
        << last_step.relative_error() << ',' << last_step.estimated_pressure_error << ','
        << wall_time;
    if (inf_sup.checked())
      row << ',' << inf_sup.latest_beta();
    row << '\n';
    SafeFiles::append(run_directory + "/refinement_cycles.csv", row.str());
  }

  template <int dim>
  bool
  ContactProblem<dim>::targets_met() const
  {
    const auto met = [](const double target, const double estimate) {
      return target == 0. || estimate <= target;
    };
    return met(adaptive_refinement.target_error, last_step.relative_error()) &&
           met(adaptive_refinement.target_pressure_error, last_step.estimated_pressure_error);
  }

  template <int dim>
  void
  ContactProblem<dim>::finish_targeted_cycles(const unsigned int last, const CycleTotals &totals)
  {
    const bool met = targets_met();
    // the output directory holds the last cycle's output, as without a target
    const std::string from = cycle_directory(last);
    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      {
        for (const auto &entry : std::filesystem::directory_iterator(from))
          std::filesystem::rename(entry.path(),
                                  run_directory + "/" + entry.path().filename().string());
        std::filesystem::remove(from);
      }
    output_directory = run_directory;
    std::ostringstream report;
    report << "Accuracy target " << (met ? "met" : "NOT met") << " at cycle " << last << " of "
           << adaptive_refinement.cycles << ": " << triangulation.n_global_active_cells()
           << " cells, " << n_u << " displacement DoFs; estimated relative error "
           << std::setprecision(3) << last_step.relative_error() << " (target "
           << adaptive_refinement.target_error << "), pressure "
           << last_step.estimated_pressure_error << " (target "
           << adaptive_refinement.target_pressure_error << "); the cycles took " << std::fixed
           << std::setprecision(1) << totals.wall_time << " s and " << totals.newton_iterations
           << " Newton iterations in all\n";
    pcout << (met ? "" : "WARNING: ") << report.str();
    if (adaptive_refinement.target_pressure_error > 0. && last_step.points_in_contact == 0)
      pcout << "WARNING: no contact point is in contact at the end of the load path: there is "
               "no contact pressure, so `Target pressure error` was met vacuously (the estimated "
               "pressure error is reported as 0).\n";
    if (Utilities::MPI::this_mpi_process(mpi_communicator) != 0)
      return;
    std::ostringstream file;
    file << "target_error,target_pressure_error,met,cycle,cells,displacement_dofs,"
            "multiplier_dofs,estimated_relative_error,estimated_pressure_error,"
            "newton_iterations,wall_time_s\n"
         << adaptive_refinement.target_error << ',' << adaptive_refinement.target_pressure_error
         << ',' << (met ? 1 : 0) << ',' << last << ',' << triangulation.n_global_active_cells()
         << ',' << n_u << ',' << n_multipliers << ',' << std::setprecision(8)
         << last_step.relative_error() << ',' << last_step.estimated_pressure_error << ','
         << totals.newton_iterations << ',' << totals.wall_time << '\n';
    SafeFiles::write_atomically(run_directory + "/target_error.csv", file.str());
  }

  namespace
  {
    /** A load path projected to need more than a day is worth a warning. */
    constexpr double seconds_to_warn_of = 24. * 3600.;
  } // namespace

  template <int dim>
  bool
  ContactProblem<dim>::solve_load_path(const bool resumed)
  {
    LoadStepController steps(
        load_stepping.end_time, load_stepping.n_steps, load_stepping.max_cuts, controller);
    if (!resumed)
      start_load_path(steps);
    timer.reset();
    RunLog<dim>(run_log_view()).print_path_banner();
    if (!resumed)
      commit_converged_step(0, 0.);

    PathLog path(time, work);
    while (steps.before_end(time))
      {
        const double             step_size  = steps.next_step_size(time);
        const double             step_begin = time;
        const RunState::Snapshot saved      = state_list.snapshot();
        StepStatistics           stats;
        stats.step      = steps.step() + 1;
        stats.step_size = step_size;
        stats.cuts      = steps.consecutive_cuts();
        Timer step_clock;
        time = step_begin + step_size;
        load_step_attempt(step_begin, time);
        partner->set_time(step_begin, time);
        extrapolate_last_step(step_size);
        apply_dirichlet_values(time);
        if (!nested_loops.solve_load_step(stats) || !newton.plausible_converged_state())
          {
            saved.restore();
            update_ghosts();
            // the same step again, with the friction threshold folded
            const bool fold = contact_start.fold_friction && !contact_start.friction_folded;
            contact_start   = ContactStart();
            contact_start.friction_folded = fold;
            if (fold)
              continue;
            if (!cut_load_step(steps))
              return false;
            continue;
          }
        steps.accept();
        contact_start = ContactStart();
        record_load_step(stats, path, step_clock);
        const bool checkpointed = output_parameters.checkpoint_interval > 0 &&
                                  steps.step() % output_parameters.checkpoint_interval == 0;
        if (checkpointed)
          checkpoint.write();
        if (stop_at_wall_time_limit(steps, path, checkpointed))
          return false;
      }
    RunLog<dim>(run_log_view()).finish_load_path(steps.step(), path);
    return true;
  }

  template <int dim>
  void
  ContactProblem<dim>::start_load_path(LoadStepController &steps)
  {
    const bool root = Utilities::MPI::this_mpi_process(mpi_communicator) == 0;
    if (root)
      std::filesystem::create_directories(output_directory);
    statistics.open(output_directory, dim, root, statistics_supports());
    solution_output.set_records({});
    active_set.clear();
    cumulative_slip.clear();
    steps.restart();
    path_start_work = work;
    last_step_size  = 0.;
  }

  template <int dim>
  bool
  ContactProblem<dim>::cut_load_step(LoadStepController &steps)
  {
    const unsigned int step = steps.step();
    if (!unrecoverable_failure.empty())
      {
        pcout << "ERROR: load step " << step + 1 << " from t = " << time << ": "
              << unrecoverable_failure
              << ", which a smaller load step cannot cure. The results of the " << step
              << " converged steps are in " << output_directory << ".\n";
        return false;
      }
    const double failed_size = steps.step_size();
    if (!steps.cut())
      {
        pcout << "ERROR: load step " << step + 1 << " from t = " << time
              << " did not converge after " << steps.max_cuts()
              << " step cuts (Load stepping/Maximum step cuts), with the step " << failed_size
              << ". The results of the " << step << " converged steps are in " << output_directory
              << ".\n";
        return false;
      }
    pcout << "  step did not converge; cutting the step to " << steps.step_size() << "\n";
    return true;
  }

  template <int dim>
  void
  ContactProblem<dim>::record_load_step(StepStatistics &stats,
                                        PathLog        &path,
                                        const Timer    &step_clock)
  {
    stats.failed_newton_iterations =
        work.newton_iterations - path.at_step_start.newton_iterations - stats.newton_iterations;
    stats.assemblies   = work.assemblies - path.at_step_start.assemblies;
    stats.jacobians    = work.jacobians - path.at_step_start.jacobians;
    path.at_step_start = work;
    material_history.commit();
    stats.time = time;
    {
      TimerOutput::Scope scope(timer, "contact search");
      compute_contact_statistics(stats);
    }
    estimate_error(stats);
    last_step                   = stats;
    last_normal_force           = stats.normal_force;
    path.most_points_in_contact = std::max(path.most_points_in_contact, stats.points_in_contact);
    path.contact_point_count    = stats.contact_points;
    commit_converged_step(stats.step, time);
    for (const auto index : locally_owned)
      last_increment(index) = solution(index) - step_start(index);
    last_increment.compress(VectorOperation::insert);
    last_step_size  = stats.step_size;
    step_start      = ghosted_solution;
    stats.wall_time = step_clock.wall_time();
    statistics.write(stats);
    RunLog<dim>(run_log_view()).print_step_line(stats, path.wall_clock.wall_time());
    if (stats.friction_law_violations > 0 && ++path.friction_law_warnings <= 3)
      pcout << "WARNING: load step " << stats.step << ": " << stats.friction_law_report
            << " The Newton criterion accepted this state"
            << (solver_parameters.newton_criterion == Parameters::ResidualCriterion::scaled
                    ? ""
                    : " (with `Nonlinear solver/Newton/Residual = scaled` it would not: the "
                      "absolute residual weighs a stick point's slip by r_t)")
            << "; column friction_law_violations of statistics.csv"
            << (path.friction_law_warnings == 3 ? " (no further warnings)" : "") << ".\n";
  }

  template <int dim>
  bool
  ContactProblem<dim>::stop_at_wall_time_limit(const LoadStepController &steps,
                                               const PathLog            &path,
                                               const bool                checkpointed)
  {
    const unsigned int step = steps.step();
    // the slowest rank's clock, so that every rank stops at the same step
    const double elapsed = Utilities::MPI::max(run_clock.wall_time(), mpi_communicator);
    // the load path's own pace (setup and earlier cycles left out)
    const double needed = Utilities::MPI::max(path.wall_clock.wall_time(), mpi_communicator) /
                          (time - path.start_time) * (steps.end_time() - path.start_time);
    const double limit = load_stepping.wall_time_limit;
    if (step == 1 && limit > 0. && needed > limit)
      pcout << "WARNING: at the pace of the first load step the load path needs ~" << needed
            << " s, more than `Load stepping/Wall time limit` = " << limit
            << " s: the run will stop at the limit before its end.\n";
    if (step == 1 && limit == 0. && needed > seconds_to_warn_of)
      pcout << "WARNING: at the pace of the first load step the load path needs ~" << needed / 3600.
            << " h. Consider fewer load steps, or a `Load stepping/Wall "
            << "time limit` with checkpoints (`Output/Checkpoint interval`).\n";
    const bool stop = limit > 0. && steps.before_end(time) && elapsed > limit;
    if (!stop)
      return false;
    if (output_parameters.checkpoint_interval > 0 && !checkpointed)
      checkpoint.write();
    pcout << "Stopped at the wall-time limit (Load stepping/Wall time limit = " << limit
          << " s) after load step " << step << " at t = " << time << ", " << elapsed
          << " s into the run. The results of the " << step << " converged steps are in "
          << output_directory
          << (output_parameters.checkpoint_interval > 0
                  ? "; `--resume` continues from the checkpoint written now.\n"
                  : "; with `Output/Checkpoint interval` > 0 it could be resumed.\n");
    wall_time_limit_reached = true;
    RunLog<dim>(run_log_view()).write_run_summary(step, path.wall_clock.wall_time());
    return true;
  }

  template <int dim>
  void
  ContactProblem<dim>::extrapolate_last_step(const double step_size)
  {
    if (!solver_parameters.extrapolate || last_step_size <= 0.)
      return;
    // u⁰_{n+1} = u_n + (Δt_{n+1}/Δt_n)(u_n − u_{n−1}), multipliers included
    solution.add(step_size / last_step_size, last_increment);
    update_ghosts();
  }

  template <int dim>
  void
  ContactProblem<dim>::apply_dirichlet_values(const double t)
  {
    std::map<types::global_dof_index, double> values;
    for (const auto &condition : boundary_conditions)
      condition->add_prescribed_values(boundary_view(), t, values);
    double largest_prescribed = 0.;
    for (const auto &entry : values)
      largest_prescribed = std::max(largest_prescribed, std::abs(entry.second));
    bounds.add_prescribed_displacement(Utilities::MPI::max(largest_prescribed, mpi_communicator));
    // The increment is not added to the iterate here: the step's first Newton
    // iteration, the tangent predictor (predictor_step()), applies it.
    TrilinosWrappers::MPI::Vector increment(locally_owned, mpi_communicator);
    for (const auto &[index, value] : values)
      if (locally_owned.is_element(index))
        increment(index) = value - solution(index);
    increment.compress(VectorOperation::insert);
    hanging_constraints.distribute(increment);
    // After an extrapolation, what is left of the Dirichlet increment of a
    // steady motion is round-off: it is added to the iterate directly.
    if (solver_parameters.extrapolate && last_step_size > 0. &&
        increment.linfty_norm() <= 1e-10 * last_increment.linfty_norm())
      {
        solution += increment;
        update_ghosts();
        increment = 0.;
      }
    dirichlet_increment_nonzero = increment.linfty_norm() > 0.;
    dirichlet_increment.reinit(locally_owned, locally_relevant, mpi_communicator);
    dirichlet_increment = increment;
  }

  // Explicit instantiation of the members defined in this file (the class
  // itself is instantiated once, in contact_problem.cc).
#define SL_INSTANTIATE(dim)                                                                        \
  template bool        ContactProblem<dim>::run(bool);                                             \
  template void        ContactProblem<dim>::start_cycle_log(bool) const;                           \
  template std::string ContactProblem<dim>::cycle_directory(unsigned int) const;                   \
  template void        ContactProblem<dim>::record_cycle(double, CycleTotals &) const;             \
  template bool        ContactProblem<dim>::targets_met() const;                                   \
  template void ContactProblem<dim>::finish_targeted_cycles(unsigned int, const CycleTotals &);    \
  template bool ContactProblem<dim>::solve_load_path(bool);                                        \
  template void ContactProblem<dim>::start_load_path(LoadStepController &);                        \
  template bool ContactProblem<dim>::cut_load_step(LoadStepController &);                          \
  template void ContactProblem<dim>::record_load_step(StepStatistics &, PathLog &, const Timer &); \
  template bool ContactProblem<dim>::stop_at_wall_time_limit(                                      \
      const LoadStepController &, const PathLog &, bool);                                          \
  template void ContactProblem<dim>::extrapolate_last_step(double);                                \
  template void ContactProblem<dim>::apply_dirichlet_values(double);

  SL_INSTANTIATE(2)
  SL_INSTANTIATE(3)
#undef SL_INSTANTIATE
} // namespace StabilizedLagrangian
