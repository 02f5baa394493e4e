// The log of a load path and its summary (RunLog): the banner that opens
// it, a line per converged load step, and at its end the block of the log and
// run_summary.csv (one SummaryRow of named columns): the problem's size, the
// work done on the path (Newton iterations, assemblies, the iterative
// solver's phases), the estimated error, memory, the partition and the
// slowest timer sections.

#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <stabilized_lagrangian/postprocessing/safe_files.h>
#include <stabilized_lagrangian/solver/contact_problem.h>
#include <stabilized_lagrangian/solver/run_log.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <regex>
#include <sstream>

namespace StabilizedLagrangian
{
  namespace
  {
    // the version of the output's names (CSV columns, VTU fields), the first
    // column of run_summary.csv: it grows with every rename, and CHANGELOG.md
    // lists each renamed name with its old one (contrib/run_output.py reads both)
    constexpr unsigned int output_schema_version = 2;
  } // namespace

  template <int dim>
  double
  RunLog<dim>::peak_memory() const
  {
    Utilities::System::MemoryStats memory;
    Utilities::System::get_memory_stats(memory);
    return Utilities::MPI::max(memory.VmHWM / 1024., problem.communicator);
  }

  template <int dim>
  std::map<std::string, double>
  RunLog<dim>::slowest_sections() const
  {
    std::map<std::string, double> slowest;
    for (const auto &[section, seconds] :
         problem.timer.get_summary_data(TimerOutput::total_wall_time))
      slowest[section] = Utilities::MPI::max(seconds, problem.communicator);
    return slowest;
  }

  template <int dim>
  WorkCounters
  RunLog<dim>::work_on_path() const
  {
    return WorkCounters{
        problem.work.newton_iterations - problem.path_start_work.newton_iterations,
        problem.work.assemblies - problem.path_start_work.assemblies,
        problem.work.jacobians - problem.path_start_work.jacobians,
        problem.work.krylov_iterations - problem.path_start_work.krylov_iterations,
        problem.work.iterative_fallbacks - problem.path_start_work.iterative_fallbacks,
        problem.work.amg_setup_seconds - problem.path_start_work.amg_setup_seconds,
        problem.work.schur_seconds - problem.path_start_work.schur_seconds,
        problem.work.krylov_seconds - problem.path_start_work.krylov_seconds,
        problem.work.schur_solve_seconds - problem.path_start_work.schur_solve_seconds};
  }

  template <int dim>
  void
  RunLog<dim>::print_path_banner() const
  {
    problem.pcout << "stabilized_lagrangian: " << dim << "D, "
                  << problem.triangulation.n_global_active_cells() << " cells, " << problem.n_u
                  << " displacement DoFs + " << problem.n_multipliers
                  << " multiplier DoFs on the contact boundary, "
                  << Utilities::MPI::n_mpi_processes(problem.communicator) << " MPI rank(s), "
                  << problem.system_matrix.n_nonzero_elements() << " matrix entries\n";
    const Parameters::LinearSolver &linear = problem.linear_solver_parameters;
    problem.pcout << "  linear solver: "
                  << (problem.iterative_solver
                          ? std::string("iterative (GMRES; algebraic multigrid on the displacement "
                                        "block, Schur complement on the multipliers)")
                          : "direct (" + linear.direct_solver + ")");
    if (linear.automatic)
      problem.pcout << ", by Method = automatic ("
                    << (dim == 3 ? "iterative in 3D from " +
                                       std::to_string(linear.automatic_threshold) + " unknowns on"
                                 : std::string("direct in 2D"))
                    << "): " << problem.n_u + problem.n_multipliers << " unknowns";
    problem.pcout << "\n";
    const unsigned int hanging_multipliers =
        Utilities::MPI::sum(static_cast<unsigned int>(
                                std::count_if(problem.hanging_constraints.get_lines().begin(),
                                              problem.hanging_constraints.get_lines().end(),
                                              [&](const auto &line) {
                                                return line.index >= problem.n_u &&
                                                       problem.locally_owned.is_element(line.index);
                                              })),
                            problem.communicator);
    if (hanging_multipliers > 0)
      problem.pcout << "  " << hanging_multipliers
                    << " multiplier DoFs at hanging nodes of the contact boundary\n";
    if (!problem.loops.can_change_quantity(Loop::geometry))
      problem.pcout << "  geometry loop runs once per step: flat obstacle and small strain\n";
    if (!problem.any_friction)
      problem.pcout << "  friction loop runs once per step: frictionless\n";
    else if (!problem.any_pressure_dependent_threshold)
      problem.pcout << "  friction loop runs once per step: fixed (Tresca) threshold\n";
    for (const auto &[name, loop] : {std::pair{"geometry", Loop::geometry},
                                     std::pair{"friction", Loop::friction},
                                     std::pair{"status", Loop::status}})
      if (problem.loops.linearised(loop))
        problem.pcout << "  " << name << " loop folded into the generalized Newton\n";
  }

  template <int dim>
  void
  RunLog<dim>::print_step_line(const StepStatistics &s,
                               const double          elapsed,
                               const double          start_time) const
  {
    // at the pace of this process's load path (a resumed run began at the
    // checkpoint's time, not at 0)
    const double remaining =
        elapsed / (problem.time - start_time) * (problem.end_time - problem.time);
    // formatted apart, so that the log's stream keeps its own precision
    std::ostringstream line;
    line << "step " << std::setw(3) << s.step << "  t = " << std::setw(8) << std::setprecision(6)
         << s.time << "  geometry " << s.geometry_iterations << "  friction "
         << s.friction_iterations << "  status " << s.status_iterations << "  Newton "
         << std::setw(3) << s.newton_iterations
         << (s.failed_newton_iterations > 0
                 ? " (+" + std::to_string(s.failed_newton_iterations) + " in failed attempts)"
                 : std::string())
         << (s.adaptive_stops > 0
                 ? " (" + std::to_string(s.adaptive_stops) + " loop(s) stopped adaptively)"
                 : std::string())
         << "  residual " << std::scientific << std::setprecision(2) << s.final_residual << ' '
         << problem.force_unit << ", scaled " << s.final_scaled << std::defaultfloat << "  contact "
         << s.points_in_contact << "/" << s.contact_points << " (stick " << s.points_stick
         << ", slip " << s.points_slip << ")  elapsed " << std::fixed << std::setprecision(1)
         << elapsed << " s, remaining ~" << remaining << " s\n";
    problem.pcout << line.str() << std::flush;
  }

  template <int dim>
  void
  RunLog<dim>::print_run_summary(const unsigned int n_steps, const double wall_time) const
  {
    const std::map<std::string, double> sections  = slowest_sections();
    const double                        memory    = peak_memory();
    const WorkCounters                  path_work = work_on_path();
    std::ostringstream                  block;
    block << std::fixed << std::setprecision(2) << "Run summary\n"
          << "  mesh:       " << problem.triangulation.n_global_active_cells() << " cells, "
          << problem.n_u << " displacement + " << problem.n_multipliers << " multiplier DoFs, "
          << Utilities::MPI::n_mpi_processes(problem.communicator) << " MPI rank(s)\n"
          << "  load path:  " << n_steps << " load step(s); Total Newton iterations: "
          << problem.statistics.cumulative_newton_iterations() << ", mean per load step: "
          << static_cast<double>(problem.statistics.cumulative_newton_iterations()) / n_steps
          << "; in failed (cut) attempts: "
          << problem.statistics.cumulative_failed_newton_iterations()
          << "; assemblies: " << path_work.assemblies << " (" << path_work.jacobians
          << " with the Jacobian)";
    if (problem.iterative_solver)
      block << "; GMRES iterations: " << path_work.krylov_iterations
            << ", systems left to the direct solver: " << path_work.iterative_fallbacks;
    block << "\n"
          << "  wall time:  " << std::setprecision(1) << wall_time << " s";
    std::string separator = ": ";
    for (const auto &[section, seconds] : sections)
      {
        block << separator << section << ' ' << seconds << " s ("
              << static_cast<int>(std::round(100. * seconds / std::max(wall_time, 1e-300)))
              << " %)";
        separator = ", ";
      }
    block << "\n  memory:     peak " << static_cast<long>(std::round(memory))
          << " MiB resident on the largest rank\n";
    if (problem.partner.n_faces() > 0)
      block << "  search:     " << problem.partner.n_faces() << " master faces, at most "
            << Utilities::MPI::max(problem.partner.n_held_faces(), problem.communicator)
            << " held on a rank, gathered anew " << problem.partner_dof_growths << " time(s)\n";
    // The pressure estimate is the calibrated one (effectivity 0.8-1.9 against
    // Hertz); the energy-norm estimate bounds the error from above, 3-7 times
    // it on the same scenes (doc/error_estimator.md): a guide for refinement.
    const StepStatistics &last = problem.last_step;
    if (last.estimated_pressure_error > 0.)
      block << "  error:      contact pressure about " << std::fixed << std::setprecision(2)
            << 100. * last.estimated_pressure_error
            << " % (relative L2 error estimated from the recovered pressure; within a factor 2 "
               "of the true one on the Hertz scenes, doc/error_estimator.md)\n";
    block << "  estimate:   energy norm " << std::scientific << std::setprecision(2)
          << last.estimated_error << " sqrt(N mm), " << std::fixed << 100. * last.relative_error()
          << " % of the solution's (contact part " << std::scientific
          << last.estimated_contact_error
          << "): an upper bound, 3 to 7 times the true error on the Hertz scenes, that guides "
             "the refinement; not an error bar (doc/formulation.md, \"Error estimate\")\n";
    problem.pcout << block.str();
  }

  template <int dim>
  void
  RunLog<dim>::finish_load_path(const unsigned int n_steps, const PathLog &path) const
  {
    print_run_summary(n_steps, path.wall_clock.wall_time());
    // a scene that runs but cannot be what was meant: the contact surface is
    // not the one that touches the obstacle, or the obstacle faces away
    if (path.most_points_in_contact <= 1 && path.contact_point_count > 1)
      problem.pcout
          << "WARNING: at most " << path.most_points_in_contact << " of the "
          << path.contact_point_count
          << " contact points was in contact in any load step. Is `Contact/Contact boundary "
             "ids` the surface that meets the obstacle, and does the obstacle's normal point "
             "towards the body?\n";
    if (problem.verbose)
      problem.timer.print_wall_time_statistics(problem.communicator);
    write_run_summary(n_steps, path.wall_clock.wall_time());
  }

  template <int dim>
  void
  RunLog<dim>::write_run_summary(const unsigned int n_steps, const double wall_time) const
  {
    const WorkCounters path_work = work_on_path();
    // collective, before rank 0 alone writes
    const std::map<std::string, double> slowest = slowest_sections();
    const double                        memory  = peak_memory();
    const unsigned int                  held =
        Utilities::MPI::max(problem.partner.n_held_faces(), problem.communicator);
    // the partition: owned DoFs (balance) and ghosts (the halo each exchange carries)
    const unsigned int owned        = problem.locally_owned.n_elements();
    const unsigned int ghosts       = problem.locally_relevant.n_elements() - owned;
    const unsigned int owned_min    = Utilities::MPI::min(owned, problem.communicator);
    const unsigned int owned_max    = Utilities::MPI::max(owned, problem.communicator);
    const unsigned int ghosts_max   = Utilities::MPI::max(ghosts, problem.communicator);
    const double       phase_max[4] = {
              Utilities::MPI::max(path_work.amg_setup_seconds, problem.communicator),
              Utilities::MPI::max(path_work.schur_seconds, problem.communicator),
              Utilities::MPI::max(path_work.krylov_seconds, problem.communicator),
              Utilities::MPI::max(path_work.schur_solve_seconds, problem.communicator)};
    const unsigned int schur_blocks = Utilities::MPI::sum(
        problem.iterative_solver ? problem.iterative_solver->n_local_blocks() : 0u,
        problem.communicator);
    if (Utilities::MPI::this_mpi_process(problem.communicator) != 0)
      return;
    SummaryRow table;
    table.add("schema_version", output_schema_version);
    table.add("dimension", dim);
    table.add("cells", problem.triangulation.n_global_active_cells());
    table.add("displacement_dofs", problem.n_u);
    table.add("multiplier_dofs", problem.n_multipliers);
    table.add("mpi_ranks", Utilities::MPI::n_mpi_processes(problem.communicator));
    table.add("r_n", problem.chosen.r_n);
    table.add("r_t", problem.chosen.r_t);
    table.add("load_steps", n_steps);
    table.add("newton_iterations", problem.statistics.cumulative_newton_iterations());
    table.add("mean_newton_iterations_per_step",
              static_cast<double>(problem.statistics.cumulative_newton_iterations()) / n_steps);
    table.add("failed_attempt_newton_iterations",
              problem.statistics.cumulative_failed_newton_iterations());
    table.add("assemblies", path_work.assemblies);
    table.add("jacobian_assemblies", path_work.jacobians);
    table.add("estimated_error_sqrtNmm", problem.last_step.estimated_error);
    table.add("estimated_contact_error_sqrtNmm", problem.last_step.estimated_contact_error);
    table.add("estimated_relative_error", problem.last_step.relative_error());
    table.add("peak_memory_MiB", memory);
    table.add("wall_time_s", wall_time);
    table.add("owned_dofs_min", owned_min);
    table.add("owned_dofs_max", owned_max);
    table.add("ghost_dofs_max", ghosts_max);
    table.add("weighted_complementarity", problem.chosen.weighted_complementarity() ? 1 : 0);
    if (problem.inf_sup.checked())
      table.add("inf_sup_beta", problem.inf_sup.latest_beta());
    // (with `automatic` also on the meshes it left to the direct solver: 0)
    if (problem.linear_solver_parameters.iterative || problem.linear_solver_parameters.automatic)
      {
        table.add("krylov_iterations", path_work.krylov_iterations);
        table.add("iterative_fallbacks", path_work.iterative_fallbacks);
        table.add("amg_setup_s", phase_max[0]);
        table.add("schur_complement_s", phase_max[1]);
        table.add("gmres_s", phase_max[2]);
        table.add("schur_solves_s", phase_max[3]);
        table.add("schur_node_blocks", schur_blocks);
      }
    if (problem.partner.n_faces() > 0)
      {
        table.add("master_faces", problem.partner.n_faces());
        table.add("master_faces_held_max", held);
        table.add("master_search_growths", problem.partner_dof_growths);
      }
    for (const auto &[section, seconds] : slowest)
      table.add(std::regex_replace(section, std::regex(" "), "_") + "_s", seconds);
    SafeFiles::write_atomically(problem.output_directory + "/run_summary.csv", table.csv());
  }

  template <int dim>
  typename RunLog<dim>::View
  ContactProblem<dim>::run_log_view() const
  {
    return typename RunLog<dim>::View{mpi_communicator,
                                      pcout,
                                      timer,
                                      verbose,
                                      output_directory,
                                      triangulation,
                                      n_u,
                                      n_multipliers,
                                      locally_owned,
                                      locally_relevant,
                                      hanging_constraints,
                                      system_matrix,
                                      loops,
                                      contact_zones.any_friction(),
                                      contact_zones.any_pressure_dependent_threshold(),
                                      chosen,
                                      linear_solver_parameters,
                                      iterative_solver.get(),
                                      *partner,
                                      partner_dof_growths,
                                      inf_sup,
                                      time,
                                      load_stepping.end_time,
                                      force_unit(dim, axisymmetric, false),
                                      statistics,
                                      last_step,
                                      work,
                                      path_start_work};
  }

  // Explicit instantiation of the members defined in this file.
#define SL_INSTANTIATE(dim)   \
  template class RunLog<dim>; \
  template typename RunLog<dim>::View ContactProblem<dim>::run_log_view() const;

  SL_INSTANTIATE(2)
  SL_INSTANTIATE(3)
#undef SL_INSTANTIATE
} // namespace StabilizedLagrangian
