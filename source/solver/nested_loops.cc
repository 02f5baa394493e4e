#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <deal.II/numerics/vector_tools.h>

#include <stabilized_lagrangian/contact/stabilized_lagrangian.h>
#include <stabilized_lagrangian/postprocessing/safe_files.h>
#include <stabilized_lagrangian/solver/contact_problem.h>
#include <stabilized_lagrangian/solver/linear_solver.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <fstream>
#include <algorithm>
#include <iomanip>
#include <limits>
#include <regex>
#include <sstream>

namespace StabilizedLagrangian
{
  // The nested fixed points of seed §2.2 (doc/formulation.md, "Nested loops"):
  //   geometry loop → friction loop → status loop → Newton.

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
    geometry_loop_needed           = master_surface || !(obstacle->is_flat() && !finite_strain());
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
    if (!geometry_loop_needed)
      pcout << "  geometry loop runs once per step: flat obstacle and small strain\n";
    if (!friction_law->has_friction())
      pcout << "  friction loop runs once per step: frictionless\n";
    else if (!friction_law->threshold_depends_on_pressure())
      pcout << "  friction loop runs once per step: fixed (Tresca) threshold\n";
    for (const auto &[loop, method] : {std::pair{"geometry", solver_parameters.geometry_method},
                                       std::pair{"friction", solver_parameters.friction_method},
                                       std::pair{"status", solver_parameters.status_method}})
      if (folded(method))
        pcout << "  " << loop << " loop folded into the generalized Newton\n";

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

  template <int dim>
  bool
  ContactProblem<dim>::solve_load_step(StepStatistics &stats)
  {
    return geometry_loop(stats);
  }

  template <int dim>
  double
  ContactProblem<dim>::relative_displacement_change(
      const TrilinosWrappers::MPI::Vector &previous) const
  {
    double change = 0., size = 0.;
    for (const auto index : locally_owned_u)
      {
        change = std::max(change, std::abs(solution(index) - previous(index)));
        size   = std::max(size, std::abs(solution(index)));
      }
    change = Utilities::MPI::max(change, mpi_communicator);
    size   = Utilities::MPI::max(size, mpi_communicator);
    return size > 0. ? change / size : change;
  }

  template <int dim>
  bool
  ContactProblem<dim>::geometry_loop(StepStatistics &stats)
  {
    // folded into Newton, the pairing is re-evaluated at every iterate
    const bool iterate = geometry_loop_needed && !folded(solver_parameters.geometry_method);
    for (unsigned int k = 1; k <= solver_parameters.geometry_max_iterations; ++k)
      {
        stats.geometry_iterations = k;
        {
          TimerOutput::Scope scope(timer, "contact search");
          update_pairings(true);
        }
        const TrilinosWrappers::MPI::Vector previous = solution;
        if (!friction_loop(stats, k))
          return false;
        if (!iterate)
          return true;
        if (relative_displacement_change(previous) <= solver_parameters.geometry_tolerance)
          return true;
      }
    // the pairing re-evaluated at every Newton iterate instead
    pcout << "  geometry loop: no convergence in " << solver_parameters.geometry_max_iterations
          << " iterations (Nonlinear solver/Geometry loop/Maximum iterations); the pairing is "
             "folded into the generalized Newton for this load step\n";
    ++stats.folded_loops;
    ++stats.geometry_iterations;
    return with_loop_folded(solver_parameters.geometry_method, [&]() {
      return friction_loop(stats, solver_parameters.geometry_max_iterations + 1);
    });
  }

  template <int dim>
  bool
  ContactProblem<dim>::friction_loop(StepStatistics &stats, const unsigned int k)
  {
    if (!friction_law->has_friction() || !friction_law->threshold_depends_on_pressure() ||
        folded(solver_parameters.friction_method))
      {
        ++stats.friction_iterations;
        return status_loop(stats, k, 1);
      }
    for (unsigned int j = 1; j <= solver_parameters.friction_max_iterations; ++j)
      {
        ++stats.friction_iterations;
        if (!status_loop(stats, k, j))
          return false;
        if (update_friction_thresholds() <= solver_parameters.friction_tolerance)
          return true;
      }
    // The fixed point on s = μ λ_n does not contract on this step: the
    // generalized Newton linearises the threshold instead (seed §2.3), which
    // converges where the fixed point cycles.
    pcout << "  friction loop: no convergence in " << solver_parameters.friction_max_iterations
          << " iterations (Nonlinear solver/Friction loop/Maximum iterations); the friction "
             "threshold is folded into the generalized Newton for this load step\n";
    ++stats.folded_loops;
    ++stats.friction_iterations;
    return with_loop_folded(solver_parameters.friction_method, [&]() {
      return status_loop(stats, k, solver_parameters.friction_max_iterations + 1);
    });
  }

  template <int dim>
  bool
  ContactProblem<dim>::with_loop_folded(Parameters::LoopMethod      &method,
                                        const std::function<bool()> &solve)
  {
    const Parameters::LoopMethod chosen = method;
    method                              = Parameters::LoopMethod::newton;
    const bool converged                = solve();
    method                              = chosen;
    return converged;
  }

  template <int dim>
  bool
  ContactProblem<dim>::status_loop(StepStatistics    &stats,
                                   const unsigned int k,
                                   const unsigned int j)
  {
    if (folded(solver_parameters.status_method))
      {
        // the statuses are those of the converged iterate by construction
        ++stats.status_iterations;
        return newton_loop(stats, k, j, 1);
      }
    // the statuses each iteration started from: with s and the pairing
    // frozen, statuses seen before lead to the same Newton solution, so a
    // repeat is a cycle that never ends
    std::vector<std::vector<unsigned char>> seen{contact_statuses()};
    std::string                             reason;
    for (unsigned int i = 1; i <= solver_parameters.status_max_iterations; ++i)
      {
        ++stats.status_iterations;
        if (!newton_loop(stats, k, j, i))
          return false;
        const unsigned int changes              = update_statuses();
        stats.inner_loops.back().status_changes = changes;
        if (changes == 0)
          return true;
        seen.push_back(contact_statuses());
        const unsigned int repeated = first_equal(seen, seen.back(), seen.size() - 1);
        if (repeated < seen.size() - 1)
          {
            reason = "the statuses after iteration " + std::to_string(i) +
                     " repeat those after iteration " + std::to_string(repeated) + " (a cycle)";
            break;
          }
      }
    if (reason.empty())
      reason = "no convergence in " + std::to_string(solver_parameters.status_max_iterations) +
               " iterations (Nonlinear solver/Status loop/Maximum iterations)";
    // The active-set fixed point cycles or stalls: the semismooth Newton on
    // the statuses (a primal-dual active set method) converges locally
    // superlinearly where the fixed point cycles, so it takes over for the step.
    pcout << "  status loop: " << reason
          << "; the statuses are folded into the generalized Newton for this load step\n";
    ++stats.folded_loops;
    ++stats.status_iterations;
    return with_loop_folded(solver_parameters.status_method, [&]() {
      return newton_loop(stats, k, j, static_cast<unsigned int>(seen.size()));
    });
  }

  template <int dim>
  std::vector<unsigned char>
  ContactProblem<dim>::contact_statuses() const
  {
    std::vector<unsigned char> statuses(contact_states.size());
    for (unsigned int p = 0; p < contact_states.size(); ++p)
      statuses[p] = contact_states[p].in_contact;
    return statuses;
  }

  template <int dim>
  std::vector<unsigned char>
  ContactProblem<dim>::point_statuses()
  {
    std::vector<unsigned char> statuses;
    statuses.reserve(contact_states.size());
    for_each_contact_point([&](ContactPointState<dim> &state, const ContactKinematics<dim> &k) {
      statuses.push_back(static_cast<unsigned char>(point_response(state, k).status()));
    });
    return statuses;
  }

  template <int dim>
  unsigned int
  ContactProblem<dim>::first_equal(const std::vector<std::vector<unsigned char>> &seen,
                                   const std::vector<unsigned char>              &statuses,
                                   const unsigned int                             end) const
  {
    // collective: equal on every rank
    for (unsigned int i = 0; i < end; ++i)
      if (Utilities::MPI::min(seen[i] == statuses ? 1u : 0u, mpi_communicator) == 1)
        return i;
    return end;
  }

  template <int dim>
  bool
  ContactProblem<dim>::ActiveSetWatch::settling(ContactProblem<dim> &problem)
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
    const std::vector<unsigned char>  statuses = problem.point_statuses();
    const std::vector<unsigned char> &current  = seen.back();
    unsigned int                      changes = 0, sticking = 0;
    for (unsigned int p = 0; p < statuses.size(); ++p)
      {
        changes += (statuses[p] == open) != (current[p] == open);
        sticking += statuses[p] == stick || current[p] == stick;
      }
    changes  = Utilities::MPI::sum(changes, problem.mpi_communicator);
    sticking = Utilities::MPI::sum(sticking, problem.mpi_communicator);
    if (sticking > 0 || changes == 0 || changes > last_changes ||
        problem.first_equal(seen, statuses, seen.size()) < seen.size())
      return false;
    last_changes = changes;
    return true;
  }

  template <int dim>
  bool
  ContactProblem<dim>::newton_loop(StepStatistics    &stats,
                                   const unsigned int k,
                                   const unsigned int j,
                                   const unsigned int i)
  {
    // The first assembly (with the Jacobian) is at the iterate the outer
    // loops hand over; afterwards the residual at each new iterate comes from
    // the line search, and the Jacobian is assembled only when another solve
    // follows.
    assemble_newton_system(true);
    bool   jacobian_current  = true;
    double first_measure     = 0.;
    double previous_residual = std::numeric_limits<double>::infinity();
    // the open/stick/slip statuses of the iterates, when Newton decides them
    const bool     statuses_folded = folded(solver_parameters.status_method);
    ActiveSetWatch watch;
    for (unsigned int iteration = 0;; ++iteration)
      {
        if (!inadmissible_state.empty())
          {
            pcout << "  Newton: " << inadmissible_state << "\n";
            return false;
          }
        const double residual = residual_norm();
        if (!std::isfinite(residual))
          {
            pcout << "  Newton: the residual is not finite\n";
            return false;
          }
        const double scaled = scaled_residual().largest();
        const double measure =
            solver_parameters.newton_criterion == Parameters::ResidualCriterion::scaled ? scaled
                                                                                        : residual;
        if (iteration == 0)
          first_measure = measure;
        if (output_parameters.log_newton)
          log_iterate(iteration);
        const bool   predictor = dirichlet_predictor;
        const double tolerance =
            solver_parameters.newton_tolerance *
            (solver_parameters.newton_criterion == Parameters::ResidualCriterion::relative
                 ? first_measure
                 : 1.);
        if (!predictor && measure <= tolerance)
          {
            stats.inner_loops.push_back(InnerLoopRecord{k, j, i, iteration, residual, scaled, 0});
            stats.newton_iterations += iteration;
            stats.final_residual = residual;
            stats.final_scaled   = scaled;
            return true;
          }
        if (iteration == solver_parameters.newton_max_iterations)
          {
            pcout << "  Newton: residual " << residual << " N (" << measure
                  << " against the criterion's tolerance " << tolerance << ") after " << iteration
                  << " iterations (Nonlinear solver/Newton/Maximum iterations)\n";
            return false;
          }
        if (stats.newton_iterations + iteration >= solver_parameters.max_newton_per_step)
          {
            pcout << "  Newton: " << stats.newton_iterations + iteration
                  << " iterations in this load step (Nonlinear solver/Maximum Newton iterations "
                     "per load step)\n";
            return false;
          }

        // nothing in contact and a rigid motion free: the system is singular,
        // and no smaller load step makes it less so
        if (!free_rigid_motions.empty() && points_in_contact() == 0)
          {
            unrecoverable_failure =
                "the body is not supported: no contact point is in contact (the loads pull it off "
                "the obstacle) and the Dirichlet conditions leave " +
                free_rigid_motions +
                " free. Hold it by a prescribed displacement, or load it towards the obstacle";
            pcout << "  Newton: " << unrecoverable_failure << ".\n";
            return false;
          }
        if (statuses_folded)
          watch.seen.push_back(point_statuses());
        if (!jacobian_current)
          assemble_newton_system(true);
        TrilinosWrappers::MPI::Vector update(locally_owned, mpi_communicator);
        system_rhs *= -1.;
        bool solved;
        {
          TimerOutput::Scope scope(timer, "linear solve");
          solved = direct_solver->solve(system_matrix, update, system_rhs);
        }
        ++work.newton_iterations;
        if (!direct_solver->last_retry().empty())
          pcout << "  Newton: " << direct_solver->last_retry() << "\n";
        if (!solved)
          {
            const std::string &error = direct_solver->last_error();
            pcout << "  Newton: the linear solver failed: " << error << ".\n";
            // a smaller load step has the same matrix size and structure
            if (error.find("memory") != std::string::npos ||
                error.find("work space") != std::string::npos)
              unrecoverable_failure = "the linear solver failed: " + error;
            if (error.find("singular") != std::string::npos)
              pcout << "  The Newton system is singular. Usual "
                       "causes: a rigid-body motion the boundary conditions leave free; a sticking "
                       "contact point whose tangential displacement is prescribed (a Dirichlet "
                       "condition on a node of the contact boundary, with friction: its friction "
                       "multiplier is then undetermined, and `Linear solver/Null pivot detection "
                       "= true` picks one of the equivalent values); a pair that violates the "
                       "inf-sup condition (Q1/P2).\n";
            return false;
          }
        newton_constraints.distribute(update);
        if (predictor)
          {
            // the Dirichlet increment (zero in the update's constrained rows)
            TrilinosWrappers::MPI::Vector increment(locally_owned, mpi_communicator);
            increment = dirichlet_increment;
            update += increment;
            dirichlet_predictor = false;
          }
        // the predictor step is taken whole: it carries the boundary data
        line_search(update,
                    residual,
                    previous_residual,
                    predictor ? 0 : solver_parameters.line_search_steps,
                    statuses_folded ? &watch : nullptr);
        previous_residual = residual;
        jacobian_current  = false;
      }
  }

  template <int dim>
  void
  ContactProblem<dim>::line_search(const TrilinosWrappers::MPI::Vector &update,
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
    // (ActiveSetWatch::settling).
    const TrilinosWrappers::MPI::Vector start = solution;
    double                              step  = 1.;
    for (unsigned int halving = 0;; ++halving)
      {
        solution = start;
        solution.add(step, update);
        update_ghosts();
        assemble_newton_system(false);
        if (output_parameters.log_newton)
          log_trial(step);
        if (halving == max_halvings)
          return;
        if (inadmissible_state.empty())
          {
            if (halving == 0 && watch != nullptr && watch->settling(*this))
              return;
            const double reference = halving == 0 ? previous_residual : residual;
            if (residual_norm() < (1. - 1e-4 * step) * reference)
              return;
          }
        step /= 2.;
      }
  }

  template <int dim>
  void
  ContactProblem<dim>::log_iterate(const unsigned int iteration) const
  {
    const ScaledResidual scaled = scaled_residual();
    std::ostringstream   line;
    line << std::setprecision(6) << "    Newton " << iteration << ": residual " << residual_norm()
         << " N; scaled: force " << scaled.force << ", gap " << scaled.gap << ", slip "
         << scaled.slip << "\n";
    pcout << line.str();
  }

  template <int dim>
  void
  ContactProblem<dim>::log_trial(const double step)
  {
    unsigned int counts[3] = {0, 0, 0}; // open, stick, slip
    for (const unsigned char status : point_statuses())
      ++counts[status];
    std::ostringstream line;
    line << std::setprecision(6) << "      step length " << step << ": residual " << residual_norm()
         << (inadmissible_state.empty() ? "" : " (inadmissible material state)")
         << ", open/stick/slip " << Utilities::MPI::sum(counts[0], mpi_communicator) << "/"
         << Utilities::MPI::sum(counts[1], mpi_communicator) << "/"
         << Utilities::MPI::sum(counts[2], mpi_communicator) << "\n";
    pcout << line.str();
  }

  template <int dim>
  unsigned int
  ContactProblem<dim>::update_statuses()
  {
    TimerOutput::Scope scope(timer, "contact search");
    unsigned int       changes = 0;
    for_each_contact_point([&](ContactPointState<dim> &state, const ContactKinematics<dim> &k) {
      const bool in_contact = status(state, k);
      if (in_contact != state.in_contact)
        {
          ++changes;
          state.in_contact = in_contact;
        }
    });
    return Utilities::MPI::sum(changes, mpi_communicator);
  }

  template <int dim>
  double
  ContactProblem<dim>::update_friction_thresholds()
  {
    TimerOutput::Scope scope(timer, "contact search");
    double             max_change = 0., max_threshold = 0.;
    for_each_contact_point([&](ContactPointState<dim> &state, const ContactKinematics<dim> &k) {
      const double s           = friction_law->threshold(threshold_pressure(k.contact_pressure));
      max_change               = std::max(max_change, std::abs(s - state.friction_threshold));
      max_threshold            = std::max(max_threshold, s);
      state.friction_threshold = s;
    });
    max_change    = Utilities::MPI::max(max_change, mpi_communicator);
    max_threshold = Utilities::MPI::max(max_threshold, mpi_communicator);
    if (max_threshold == 0.)
      return max_change == 0. ? 0. : 1.;
    return max_change / max_threshold;
  }

  // Explicit instantiation of the members defined in this file (the class
  // itself is instantiated once, in contact_problem.cc).
#define SL_INSTANTIATE(dim)                                                                        \
  template bool ContactProblem<dim>::run(bool);                                                    \
  template bool ContactProblem<dim>::solve_load_path(bool);                                        \
  template void ContactProblem<dim>::write_run_summary(unsigned int, double, const WorkCounters &) \
      const;                                                                                       \
  template void   ContactProblem<dim>::print_step_line(const StepStatistics &, double) const;      \
  template void   ContactProblem<dim>::apply_dirichlet_values(double);                             \
  template bool   ContactProblem<dim>::solve_load_step(StepStatistics &);                          \
  template double ContactProblem<dim>::relative_displacement_change(                               \
      const TrilinosWrappers::MPI::Vector &) const;                                                \
  template bool ContactProblem<dim>::geometry_loop(StepStatistics &);                              \
  template bool ContactProblem<dim>::friction_loop(StepStatistics &, unsigned int);                \
  template bool ContactProblem<dim>::status_loop(StepStatistics &, unsigned int, unsigned int);    \
  template bool ContactProblem<dim>::with_loop_folded(Parameters::LoopMethod &,                    \
                                                      const std::function<bool()> &);              \
  template std::vector<unsigned char> ContactProblem<dim>::contact_statuses() const;               \
  template std::vector<unsigned char> ContactProblem<dim>::point_statuses();                       \
  template unsigned int               ContactProblem<dim>::first_equal(                            \
      const std::vector<std::vector<unsigned char>> &,                               \
      const std::vector<unsigned char> &,                                            \
      unsigned int) const;                                                           \
  template bool ContactProblem<dim>::newton_loop(                                                  \
      StepStatistics &, unsigned int, unsigned int, unsigned int);                                 \
  template void ContactProblem<dim>::line_search(                                                  \
      const TrilinosWrappers::MPI::Vector &, double, double, unsigned int, ActiveSetWatch *);      \
  template void         ContactProblem<dim>::log_iterate(unsigned int) const;                      \
  template void         ContactProblem<dim>::log_trial(double);                                    \
  template unsigned int ContactProblem<dim>::update_statuses();                                    \
  template double       ContactProblem<dim>::update_friction_thresholds();

  SL_INSTANTIATE(2)
  SL_INSTANTIATE(3)
#undef SL_INSTANTIATE
} // namespace StabilizedLagrangian
