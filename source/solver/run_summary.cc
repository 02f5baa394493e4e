// The summary of a load path: the block the log ends with and
// run_summary.csv (one SummaryRow of named columns): the problem's size, the
// work done on the path (Newton iterations, assemblies, the iterative
// solver's phases), the estimated error, memory, the partition and the
// slowest timer sections.

#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <stabilized_lagrangian/postprocessing/safe_files.h>
#include <stabilized_lagrangian/solver/contact_problem.h>

#include <cmath>
#include <iomanip>
#include <regex>
#include <sstream>

namespace StabilizedLagrangian
{
  template <int dim>
  double
  ContactProblem<dim>::peak_memory() const
  {
    Utilities::System::MemoryStats memory;
    Utilities::System::get_memory_stats(memory);
    return Utilities::MPI::max(memory.VmHWM / 1024., mpi_communicator);
  }

  template <int dim>
  std::map<std::string, double>
  ContactProblem<dim>::slowest_sections() const
  {
    std::map<std::string, double> slowest;
    for (const auto &[section, seconds] : timer.get_summary_data(TimerOutput::total_wall_time))
      slowest[section] = Utilities::MPI::max(seconds, mpi_communicator);
    return slowest;
  }

  template <int dim>
  void
  ContactProblem<dim>::print_run_summary(const unsigned int n_steps, const double wall_time) const
  {
    const std::map<std::string, double> sections = slowest_sections();
    const double                        memory   = peak_memory();
    std::ostringstream                  block;
    block << std::fixed << std::setprecision(2) << "Run summary\n"
          << "  mesh:       " << triangulation.n_global_active_cells() << " cells, " << n_u
          << " displacement + " << n_multipliers << " multiplier DoFs, "
          << Utilities::MPI::n_mpi_processes(mpi_communicator) << " MPI rank(s)\n"
          << "  load path:  " << n_steps
          << " load step(s); Total Newton iterations: " << statistics.cumulative_newton_iterations()
          << ", mean per load step: "
          << static_cast<double>(statistics.cumulative_newton_iterations()) / n_steps
          << "; in failed (cut) attempts: " << statistics.cumulative_failed_newton_iterations()
          << "; assemblies: " << work.assemblies - path_start_work.assemblies << " ("
          << work.jacobians - path_start_work.jacobians << " with the Jacobian)";
    if (iterative_solver)
      block << "; GMRES iterations: " << work.krylov_iterations - path_start_work.krylov_iterations
            << ", systems left to the direct solver: "
            << work.iterative_fallbacks - path_start_work.iterative_fallbacks;
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
    if (partner->n_faces() > 0)
      block << "  search:     " << partner->n_faces() << " master faces, at most "
            << Utilities::MPI::max(partner->n_held_faces(), mpi_communicator)
            << " held on a rank, gathered anew " << partner_dof_growths << " time(s)\n";
    block << "  error:      estimated " << std::scientific << std::setprecision(2)
          << last_step.estimated_error << " sqrt(N mm) in the energy norm, " << std::fixed
          << 100. * last_step.relative_error() << " % of the solution's (contact part "
          << std::scientific << last_step.estimated_contact_error
          << "; doc/formulation.md, \"Error estimate\")\n";
    pcout << block.str();
  }

  template <int dim>
  WorkCounters
  ContactProblem<dim>::work_on_path() const
  {
    return WorkCounters{work.newton_iterations - path_start_work.newton_iterations,
                        work.assemblies - path_start_work.assemblies,
                        work.jacobians - path_start_work.jacobians,
                        work.krylov_iterations - path_start_work.krylov_iterations,
                        work.iterative_fallbacks - path_start_work.iterative_fallbacks,
                        work.amg_setup_seconds - path_start_work.amg_setup_seconds,
                        work.schur_seconds - path_start_work.schur_seconds,
                        work.krylov_seconds - path_start_work.krylov_seconds,
                        work.schur_solve_seconds - path_start_work.schur_solve_seconds};
  }

  template <int dim>
  void
  ContactProblem<dim>::write_run_summary(const unsigned int  n_steps,
                                         const double        wall_time,
                                         const WorkCounters &path_work) const
  {
    // collective, before rank 0 alone writes
    const std::map<std::string, double> slowest = slowest_sections();
    const double                        memory  = peak_memory();
    const unsigned int held = Utilities::MPI::max(partner->n_held_faces(), mpi_communicator);
    // the partition: owned DoFs (balance) and ghosts (the halo each exchange carries)
    const unsigned int owned        = locally_owned.n_elements();
    const unsigned int ghosts       = locally_relevant.n_elements() - owned;
    const unsigned int owned_min    = Utilities::MPI::min(owned, mpi_communicator);
    const unsigned int owned_max    = Utilities::MPI::max(owned, mpi_communicator);
    const unsigned int ghosts_max   = Utilities::MPI::max(ghosts, mpi_communicator);
    const double       phase_max[4] = {
              Utilities::MPI::max(path_work.amg_setup_seconds, mpi_communicator),
              Utilities::MPI::max(path_work.schur_seconds, mpi_communicator),
              Utilities::MPI::max(path_work.krylov_seconds, mpi_communicator),
              Utilities::MPI::max(path_work.schur_solve_seconds, mpi_communicator)};
    const unsigned int schur_blocks = Utilities::MPI::sum(
        iterative_solver ? iterative_solver->n_local_blocks() : 0u, mpi_communicator);
    if (Utilities::MPI::this_mpi_process(mpi_communicator) != 0)
      return;
    SummaryRow table;
    table.add("dimension", dim);
    table.add("cells", triangulation.n_global_active_cells());
    table.add("displacement_dofs", n_u);
    table.add("multiplier_dofs", n_multipliers);
    table.add("mpi_ranks", Utilities::MPI::n_mpi_processes(mpi_communicator));
    table.add("r_n", chosen.r_n);
    table.add("r_t", chosen.r_t);
    table.add("load_steps", n_steps);
    table.add("newton_iterations", statistics.cumulative_newton_iterations());
    table.add("mean_newton_iterations_per_step",
              static_cast<double>(statistics.cumulative_newton_iterations()) / n_steps);
    table.add("failed_attempt_newton_iterations", statistics.cumulative_failed_newton_iterations());
    table.add("assemblies", path_work.assemblies);
    table.add("jacobian_assemblies", path_work.jacobians);
    table.add("estimated_error_sqrtNmm", last_step.estimated_error);
    table.add("estimated_contact_error_sqrtNmm", last_step.estimated_contact_error);
    table.add("estimated_relative_error", last_step.relative_error());
    table.add("peak_memory_MiB", memory);
    table.add("wall_time_s", wall_time);
    table.add("owned_dofs_min", owned_min);
    table.add("owned_dofs_max", owned_max);
    table.add("ghost_dofs_max", ghosts_max);
    table.add("weighted_complementarity", weighted_complementarity() ? 1 : 0);
    if (inf_sup.checked())
      table.add("inf_sup_beta", inf_sup.latest_beta());
    // (with `automatic` also on the meshes it left to the direct solver: 0)
    if (linear_solver_parameters.iterative || linear_solver_parameters.automatic)
      {
        table.add("krylov_iterations", path_work.krylov_iterations);
        table.add("iterative_fallbacks", path_work.iterative_fallbacks);
        table.add("amg_setup_s", phase_max[0]);
        table.add("schur_complement_s", phase_max[1]);
        table.add("gmres_s", phase_max[2]);
        table.add("schur_solves_s", phase_max[3]);
        table.add("schur_node_blocks", schur_blocks);
      }
    if (partner->n_faces() > 0)
      {
        table.add("master_faces", partner->n_faces());
        table.add("master_faces_held_max", held);
        table.add("master_search_growths", partner_dof_growths);
      }
    for (const auto &[section, seconds] : slowest)
      table.add(std::regex_replace(section, std::regex(" "), "_") + "_s", seconds);
    SafeFiles::write_atomically(output_directory + "/run_summary.csv", table.csv());
  }

  // Explicit instantiation of the members defined in this file (the class
  // itself is instantiated once, in contact_problem.cc).
#define SL_INSTANTIATE(dim)                                                                        \
  template WorkCounters                  ContactProblem<dim>::work_on_path() const;                \
  template double                        ContactProblem<dim>::peak_memory() const;                 \
  template std::map<std::string, double> ContactProblem<dim>::slowest_sections() const;            \
  template void ContactProblem<dim>::print_run_summary(unsigned int, double) const;                \
  template void ContactProblem<dim>::write_run_summary(unsigned int, double, const WorkCounters &) \
      const;

  SL_INSTANTIATE(2)
  SL_INSTANTIATE(3)
#undef SL_INSTANTIATE
} // namespace StabilizedLagrangian
