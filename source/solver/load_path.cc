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
#include <regex>
#include <sstream>

namespace StabilizedLagrangian
{
  // The load path: load steps, step cuts, the log and run_summary.csv;
  // each step is solved by the loops of nested_loops.cc.

  template <int dim>
  bool
  ContactProblem<dim>::run(const bool resume)
  {
    const bool        root            = Utilities::MPI::this_mpi_process(mpi_communicator) == 0;
    const std::string final_directory = output_parameters.directory;
    run_directory                     = final_directory;
    // nothing is written before the input is known to be good: the mesh and
    // the boundary names are checked by setup()
    setup();
    if (!resume)
      prepare_output_directory();
    const unsigned int first_cycle = resume ? restore_checkpoint() : 0;
    if (root)
      SafeFiles::write_atomically(final_directory + "/parameters.prm", parameters_used);

    // Adaptive refinement (`Adaptive refinement/Cycles`, 0 by default): the
    // load path is solved on each mesh in turn; the last one writes into the
    // output directory.
    const unsigned int n_cycles    = adaptive_refinement.cycles;
    const std::string  cycles_path = final_directory + "/refinement_cycles.csv";
    if (root && n_cycles > 0 && !resume)
      SafeFiles::write_atomically(cycles_path,
                                  "cycle,cells,displacement_dofs,multiplier_dofs,newton_iterations,"
                                  "normal_force_N,wall_time_s\n");
    for (cycle = first_cycle; cycle <= n_cycles; ++cycle)
      {
        const bool resumed = resume && cycle == first_cycle;
        if (cycle > 0 && !resumed)
          {
            TimerOutput::Scope scope(timer, "setup");
            refine_mesh();
            setup_after_refinement();
            time = 0.;
            pcout << "Refinement cycle " << cycle << " of " << n_cycles << "\n";
          }
        output_parameters.directory = cycle < n_cycles
                                          ? final_directory + "/cycle-" + std::to_string(cycle)
                                          : final_directory;
        Timer      cycle_clock;
        const bool converged = solve_load_path(resumed);
        if (root && n_cycles > 0)
          {
            std::ostringstream row;
            row << cycle << ',' << triangulation.n_global_active_cells() << ',' << n_u << ','
                << n_multipliers << ',' << statistics.cumulative_newton_iterations() << ','
                << std::setprecision(10) << last_normal_force << ',' << cycle_clock.wall_time()
                << '\n';
            SafeFiles::append(cycles_path, row.str());
          }
        if (!converged)
          return false;
      }
    return true;
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
    const bool   root         = Utilities::MPI::this_mpi_process(mpi_communicator) == 0;
    const double nominal_step = load_stepping.end_time / load_stepping.n_steps;
    if (!resumed)
      {
        if (root)
          std::filesystem::create_directories(output_parameters.directory);
        statistics.open(output_parameters.directory, dim, root);
        pvd_records.clear();
        active_set.clear();
        controller      = StepController{0, nominal_step, 0};
        path_start_work = work;
      }
    timer.reset();

    pcout << "stabilized_lagrangian: " << dim << "D, " << triangulation.n_global_active_cells()
          << " cells, " << n_u << " displacement DoFs + " << n_multipliers
          << " multiplier DoFs on the contact boundary, "
          << Utilities::MPI::n_mpi_processes(mpi_communicator) << " MPI rank(s), "
          << system_matrix.n_nonzero_elements() << " matrix entries\n";
    const unsigned int hanging_multipliers = Utilities::MPI::sum(
        static_cast<unsigned int>(std::count_if(hanging_constraints.get_lines().begin(),
                                                hanging_constraints.get_lines().end(),
                                                [&](const auto &line) {
                                                  return line.index >= n_u &&
                                                         locally_owned.is_element(line.index);
                                                })),
        mpi_communicator);
    if (hanging_multipliers > 0)
      pcout << "  " << hanging_multipliers
            << " multiplier DoFs at hanging nodes of the contact boundary\n";
    if (!loops.can_change_quantity(Loop::geometry))
      pcout << "  geometry loop runs once per step: flat obstacle and small strain\n";
    if (!friction_law->has_friction())
      pcout << "  friction loop runs once per step: frictionless\n";
    else if (!friction_law->threshold_depends_on_pressure())
      pcout << "  friction loop runs once per step: fixed (Tresca) threshold\n";
    for (const auto &[name, loop] : {std::pair{"geometry", Loop::geometry},
                                     std::pair{"friction", Loop::friction},
                                     std::pair{"status", Loop::status}})
      if (loops.linearised(loop))
        pcout << "  " << name << " loop folded into the generalized Newton\n";

    if (!resumed)
      output_results(0, 0.);

    const double  smallest_step = nominal_step / std::pow(2., load_stepping.max_cuts);
    unsigned int &step          = controller.step;
    double       &step_size     = controller.step_size;
    Timer         wall_clock;
    const double  path_start_time = time;
    WorkCounters  at_step_start   = work;
    // the most contact points in contact in any step, and their number
    unsigned int most_points_in_contact = 0, contact_point_count = 0;
    const auto   work_on_path = [&]() {
      return WorkCounters{work.newton_iterations - path_start_work.newton_iterations,
                          work.assemblies - path_start_work.assemblies,
                          work.jacobians - path_start_work.jacobians};
    };
    // steps whose state breaks the friction law (the first few are named)
    unsigned int friction_law_warnings = 0;
    while (time < load_stepping.end_time * (1. - 1e-12))
      {
        step_size = std::min(step_size, load_stepping.end_time - time);
        const TrilinosWrappers::MPI::Vector       saved_solution = solution;
        const std::vector<ContactPointState<dim>> saved_states   = contact_states;
        const std::vector<ContactFace>            saved_faces    = contact_faces;
        const double                              saved_time     = time;

        StepStatistics stats;
        stats.step      = step + 1;
        stats.step_size = step_size;
        stats.cuts      = controller.consecutive_cuts;
        Timer step_clock;
        time = saved_time + step_size;
        apply_dirichlet_values(time);
        const bool converged = solve_load_step(stats);
        if (!converged)
          {
            solution       = saved_solution;
            contact_states = saved_states;
            contact_faces  = saved_faces;
            time           = saved_time;
            update_ghosts();
            if (!unrecoverable_failure.empty())
              {
                pcout << "ERROR: load step " << step + 1 << " from t = " << time << ": "
                      << unrecoverable_failure
                      << ", which a smaller load step cannot cure. The results of the " << step
                      << " converged steps are in " << output_parameters.directory << ".\n";
                return false;
              }
            // the smallest step is the nominal one halved `Maximum step cuts`
            // times: a run cannot crawl on with ever smaller steps
            if (step_size <= smallest_step * (1. + 1e-12))
              {
                pcout << "ERROR: load step " << step + 1 << " from t = " << time
                      << " did not converge after " << load_stepping.max_cuts
                      << " step cuts (Load stepping/Maximum step cuts), with the step " << step_size
                      << ". The results of the " << step << " converged steps are in "
                      << output_parameters.directory << ".\n";
                return false;
              }
            ++controller.consecutive_cuts;
            step_size /= 2.;
            pcout << "  step did not converge; cutting the step to " << step_size << "\n";
            continue;
          }
        ++step;
        controller.consecutive_cuts = 0;
        stats.failed_newton_iterations =
            work.newton_iterations - at_step_start.newton_iterations - stats.newton_iterations;
        stats.assemblies = work.assemblies - at_step_start.assemblies;
        stats.jacobians  = work.jacobians - at_step_start.jacobians;
        at_step_start    = work;
        material_history.commit();
        stats.time = time;
        {
          TimerOutput::Scope scope(timer, "contact search");
          compute_contact_statistics(stats);
        }
        last_normal_force      = stats.normal_force;
        most_points_in_contact = std::max(most_points_in_contact, stats.points_in_contact);
        contact_point_count    = stats.contact_points;
        output_results(step, time);
        step_start      = ghosted_solution;
        stats.wall_time = step_clock.wall_time();
        statistics.write(stats);
        print_step_line(stats, wall_clock.wall_time());
        if (stats.friction_law_violations > 0 && ++friction_law_warnings <= 3)
          pcout << "WARNING: load step " << step << ": " << stats.friction_law_report
                << " The Newton criterion accepted this state"
                << (solver_parameters.newton_criterion == Parameters::ResidualCriterion::scaled
                        ? ""
                        : " (with `Nonlinear solver/Newton/Residual = scaled` it would not: the "
                          "absolute residual weighs a stick point's slip by r_t)")
                << "; column friction_law_violations of statistics.csv"
                << (friction_law_warnings == 3 ? " (no further warnings)" : "") << ".\n";
        // grow back towards the nominal step after a cut
        step_size               = std::min(2. * step_size, nominal_step);
        const bool checkpointed = output_parameters.checkpoint_interval > 0 &&
                                  step % output_parameters.checkpoint_interval == 0;
        if (checkpointed)
          write_checkpoint();
        // the slowest rank's clock, so that every rank stops at the same step
        const double elapsed = Utilities::MPI::max(run_clock.wall_time(), mpi_communicator);
        // the load path's own pace (setup and earlier cycles left out)
        const double needed = Utilities::MPI::max(wall_clock.wall_time(), mpi_communicator) /
                              (time - path_start_time) * (load_stepping.end_time - path_start_time);
        const double limit = load_stepping.wall_time_limit;
        if (step == 1 && limit > 0. && needed > limit)
          pcout << "WARNING: at the pace of the first load step the load path needs ~" << needed
                << " s, more than `Load stepping/Wall time limit` = " << limit
                << " s: the run will stop at the limit before its end.\n";
        if (step == 1 && limit == 0. && needed > seconds_to_warn_of)
          pcout << "WARNING: at the pace of the first load step the load path needs ~"
                << needed / 3600. << " h. Consider fewer load steps, or a `Load stepping/Wall "
                << "time limit` with checkpoints (`Output/Checkpoint interval`).\n";
        if (limit > 0. && time < load_stepping.end_time * (1. - 1e-12))
          {
            if (elapsed > limit)
              {
                if (output_parameters.checkpoint_interval > 0 && !checkpointed)
                  write_checkpoint();
                pcout << "Stopped at the wall-time limit (Load stepping/Wall time limit = "
                      << load_stepping.wall_time_limit << " s) after load step " << step
                      << " at t = " << time << ", " << elapsed << " s into the run. The results "
                      << "of the " << step << " converged steps are in "
                      << output_parameters.directory
                      << (output_parameters.checkpoint_interval > 0
                              ? "; `--resume` continues from the checkpoint written now.\n"
                              : "; with `Output/Checkpoint interval` > 0 it could be resumed.\n");
                wall_time_limit_reached = true;
                write_run_summary(step, wall_clock.wall_time(), work_on_path());
                return false;
              }
          }
      }
    std::ostringstream mean;
    mean << std::fixed << std::setprecision(2)
         << static_cast<double>(statistics.cumulative_newton_iterations()) / step;
    pcout << "Total Newton iterations: " << statistics.cumulative_newton_iterations()
          << ", mean per load step: " << mean.str()
          << "; in failed (cut) attempts: " << statistics.cumulative_failed_newton_iterations()
          << "; assemblies: " << work.assemblies - path_start_work.assemblies << " ("
          << work.jacobians - path_start_work.jacobians << " with the Jacobian)\n";
    // a scene that runs but cannot be what was meant: the contact surface is
    // not the one that touches the obstacle, or the obstacle faces away
    if (most_points_in_contact <= 1 && contact_point_count > 1)
      pcout << "WARNING: at most " << most_points_in_contact << " of the " << contact_point_count
            << " contact points was in contact in any load step. Is `Contact/Contact boundary "
               "ids` the surface that meets the obstacle, and does the obstacle's normal point "
               "towards the body?\n";
    if (verbose)
      timer.print_wall_time_statistics(mpi_communicator);
    write_run_summary(step, wall_clock.wall_time(), work_on_path());
    return true;
  }

  template <int dim>
  void
  ContactProblem<dim>::write_run_summary(const unsigned int  n_steps,
                                         const double        wall_time,
                                         const WorkCounters &path_work) const
  {
    // the slowest rank's time per phase
    const std::map<std::string, double> times =
        timer.get_summary_data(TimerOutput::total_wall_time);
    std::map<std::string, double> slowest;
    for (const auto &[section, seconds] : times)
      slowest[section] = Utilities::MPI::max(seconds, mpi_communicator);
    if (Utilities::MPI::this_mpi_process(mpi_communicator) != 0)
      return;
    std::ostringstream file;
    file << "dimension,cells,displacement_dofs,multiplier_dofs,mpi_ranks,r_n,r_t,load_steps,"
            "newton_iterations,mean_newton_iterations_per_step,failed_attempt_newton_iterations,"
            "assemblies,jacobian_assemblies,wall_time_s";
    for (const auto &entry : slowest)
      file << ',' << std::regex_replace(entry.first, std::regex(" "), "_") << "_s";
    file << '\n'
         << dim << ',' << triangulation.n_global_active_cells() << ',' << n_u << ','
         << n_multipliers << ',' << Utilities::MPI::n_mpi_processes(mpi_communicator) << ','
         << contact_parameters.r_n << ',' << contact_parameters.r_t << ',' << n_steps << ','
         << statistics.cumulative_newton_iterations() << ','
         << static_cast<double>(statistics.cumulative_newton_iterations()) / n_steps << ','
         << statistics.cumulative_failed_newton_iterations() << ',' << path_work.assemblies << ','
         << path_work.jacobians << ',' << wall_time;
    for (const auto &entry : slowest)
      file << ',' << entry.second;
    file << '\n';
    SafeFiles::write_atomically(output_parameters.directory + "/run_summary.csv", file.str());
  }

  template <int dim>
  void
  ContactProblem<dim>::print_step_line(const StepStatistics &s, const double elapsed) const
  {
    const double remaining = elapsed / time * (load_stepping.end_time - time);
    // formatted apart, so that the log's stream keeps its own precision
    std::ostringstream line;
    line << "step " << std::setw(3) << s.step << "  t = " << std::setw(8) << std::setprecision(6)
         << s.time << "  geometry " << s.geometry_iterations << "  friction "
         << s.friction_iterations << "  status " << s.status_iterations << "  Newton "
         << std::setw(3) << s.newton_iterations
         << (s.failed_newton_iterations > 0
                 ? " (+" + std::to_string(s.failed_newton_iterations) + " in cut attempts)"
                 : std::string())
         << "  residual " << std::scientific << std::setprecision(2) << s.final_residual
         << " N, scaled " << s.final_scaled << std::defaultfloat << "  contact "
         << s.points_in_contact << "/" << s.contact_points << " (stick " << s.points_stick
         << ", slip " << s.points_slip << ")  elapsed " << std::fixed << std::setprecision(1)
         << elapsed << " s, remaining ~" << remaining << " s\n";
    pcout << line.str() << std::flush;
  }

  template <int dim>
  void
  ContactProblem<dim>::apply_dirichlet_values(const double t)
  {
    std::map<types::global_dof_index, double> values;
    for (const auto &bc : boundary_conditions.dirichlet)
      {
        bc.displacement->set_time(t);
        VectorTools::interpolate_boundary_values(
            dof_handler_u, bc.boundary_id, *bc.displacement, values, bc.components);
        bc.displacement->check_finite(mpi_communicator);
      }
    // The increment is not added to the iterate here: the first Newton solve
    // of the step applies it together with the tangent predictor.
    TrilinosWrappers::MPI::Vector increment(locally_owned, mpi_communicator);
    for (const auto &[index, value] : values)
      if (locally_owned.is_element(index))
        increment(index) = value - solution(index);
    increment.compress(VectorOperation::insert);
    hanging_constraints.distribute(increment);
    dirichlet_predictor = increment.linfty_norm() > 0.;
    dirichlet_increment.reinit(locally_owned, locally_relevant, mpi_communicator);
    dirichlet_increment = increment;
  }

  // Explicit instantiation of the members defined in this file (the class
  // itself is instantiated once, in contact_problem.cc).
#define SL_INSTANTIATE(dim)                                                                        \
  template bool ContactProblem<dim>::run(bool);                                                    \
  template bool ContactProblem<dim>::solve_load_path(bool);                                        \
  template void ContactProblem<dim>::write_run_summary(unsigned int, double, const WorkCounters &) \
      const;                                                                                       \
  template void ContactProblem<dim>::print_step_line(const StepStatistics &, double) const;        \
  template void ContactProblem<dim>::apply_dirichlet_values(double);

  SL_INSTANTIATE(2)
  SL_INSTANTIATE(3)
#undef SL_INSTANTIATE
} // namespace StabilizedLagrangian
