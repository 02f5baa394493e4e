// The size of a run estimated before the mesh is refined (Geometry::SizeCheck):
// cells from the coarse mesh, displacement DoFs from the nodes of the
// element, memory and time per DoF from measured runs.

#include <deal.II/base/utilities.h>

#include <stabilized_lagrangian/geometry/size_estimate.h>
#include <stabilized_lagrangian/plugins.h>

#include <cmath>
#include <iomanip>
#include <sstream>
#include <unistd.h>

namespace StabilizedLagrangian
{
  namespace Geometry
  {
    namespace
    {
      // Peak memory per DoF of a whole run, measured (one rank, Q1/P1):
      // - iterative solver, 3D: 1.1 GB at 176k DoFs (doc/iterative_solver.md,
      //   "Cost per Newton iteration"; 7.9 GB at 1.3M DoFs), 6.3 kB per DoF;
      // - MUMPS, 3D: 5.1 GB at 176k DoFs (the same paragraph), 29 kB per DoF,
      //   growing with the fill (n^(4/3)) beyond;
      // - MUMPS, 2D: 648 MB at 132k DoFs, prm/hertz_cylinder.prm with
      //   `Global refinements = 7` and no local refinement (`/usr/bin/time -v`),
      //   4.9 kB per DoF.
      constexpr double bytes_per_dof_iterative = 6.3e3;
      constexpr double bytes_per_dof_direct_3d = 29e3;
      constexpr double bytes_per_dof_direct_2d = 4.9e3;
      // Assembly and linear solve per Newton iteration and DoF, measured:
      // iterative 3D 10.1 s at 176k DoFs (doc/scaling.md, refinement 3, one
      // rank); MUMPS 3D 48.6 s at 176k (doc/iterative_solver.md, on a quiet
      // machine); MUMPS 2D 1.2 s at 132k (the Hertz cylinder above).
      constexpr double seconds_per_dof_iterative = 5.7e-5;
      constexpr double seconds_per_dof_direct_3d = 2.8e-4;
      constexpr double seconds_per_dof_direct_2d = 9e-6;
      /** Newton iterations of a load step, a few (the Hertz cylinder's one step: 5) */
      constexpr double newton_iterations_per_step = 5.;
      /** A load path estimated to need more than a day is worth a warning. */
      constexpr double seconds_to_warn_of = 24. * 3600.;
      /** So are this many load steps, whatever the mesh (a CSV row and a record each). */
      constexpr unsigned int load_steps_to_warn_of = 100000;

      /** @p x to 2 significant digits: 0.37, 640, 65000, 4.1e+11. */
      std::string
      rounded(const double x)
      {
        std::ostringstream out;
        if (x > 0. && x < 1e6)
          {
            const double unit = std::pow(10., std::floor(std::log10(x)) - 1.);
            out << std::setprecision(7) << std::round(x / unit) * unit;
          }
        else
          out << std::setprecision(2) << x;
        return out.str();
      }

      std::string
      bytes_text(const double bytes)
      {
        return bytes >= 1e12
                   ? rounded(bytes / 1e12) + " TB"
                   : (bytes >= 1e9 ? rounded(bytes / 1e9) + " GB" : rounded(bytes / 1e6) + " MB");
      }

      std::string
      duration_text(const double seconds)
      {
        if (seconds < 60.)
          return rounded(seconds) + " s";
        if (seconds < 3600.)
          return rounded(seconds / 60.) + " min";
        if (seconds < 86400.)
          return rounded(seconds / 3600.) + " h";
        if (seconds < 365. * 86400.)
          return rounded(seconds / 86400.) + " days";
        return rounded(seconds / (365. * 86400.)) + " years";
      }

      /** The physical memory of this node and the ranks of @p communicator on it. */
      std::pair<double, unsigned int>
      node_memory(const MPI_Comm communicator)
      {
        MPI_Comm node;
        MPI_Comm_split_type(communicator, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
        const unsigned int ranks_on_node = Utilities::MPI::n_mpi_processes(node);
        MPI_Comm_free(&node);
        return {static_cast<double>(sysconf(_SC_PHYS_PAGES)) *
                    static_cast<double>(sysconf(_SC_PAGESIZE)),
                ranks_on_node};
      }
    } // namespace

    bool
    SizeCheck::iterative(const double dofs) const
    {
      const Parameters::LinearSolver &linear = run.linear_solver;
      if (linear.automatic)
        return run.dim == 3 && dofs >= static_cast<double>(linear.automatic_threshold);
      return linear.iterative;
    }

    SizeEstimate
    SizeCheck::estimate(const double       coarse_cells,
                        const unsigned int refinements,
                        const unsigned int simplices_per_cell,
                        const bool         simplex) const
    {
      SizeEstimate e;
      e.cells = coarse_cells * std::pow(2., run.dim * refinements) * simplices_per_cell;
      // nodes of degree p: p^dim per hypercube, p^dim / dim! per simplex
      // (a triangle mesh has about half as many vertices as cells, a
      // tetrahedral one a sixth), away from the boundary
      const double p = run.displacement_degree;
      const double nodes =
          e.cells * std::pow(p, run.dim) / (simplex ? (run.dim == 2 ? 2. : 6.) : 1.);
      e.dofs                   = run.dim * nodes;
      const bool by_iterations = iterative(e.dofs);
      e.bytes                  = e.dofs * (by_iterations
                                               ? bytes_per_dof_iterative
                                               : (run.dim == 3 ? bytes_per_dof_direct_3d : bytes_per_dof_direct_2d));
      const double per_iteration =
          e.dofs * (by_iterations
                        ? seconds_per_dof_iterative
                        : (run.dim == 3 ? seconds_per_dof_direct_3d : seconds_per_dof_direct_2d));
      e.seconds = per_iteration * newton_iterations_per_step * run.load_steps /
                  Utilities::MPI::n_mpi_processes(run.communicator);
      return e;
    }

    void
    SizeCheck::before_refinement(const double       coarse_cells,
                                 const unsigned int refinements,
                                 const unsigned int simplices_per_cell,
                                 const bool         simplex) const
    {
      const SizeEstimate e     = estimate(coarse_cells, refinements, simplices_per_cell, simplex);
      const unsigned int ranks = Utilities::MPI::n_mpi_processes(run.communicator);
      const auto [physical, ranks_on_node] = node_memory(run.communicator);
      // each rank's share of the memory, as many shares as this node holds ranks
      const double      needed  = e.bytes / ranks * ranks_on_node;
      const double      worst   = Utilities::MPI::max(needed / physical, run.communicator);
      const std::string solver  = iterative(e.dofs) ? "iterative" : "direct";
      const std::string summary = "about " + rounded(e.cells) + " cells, " + rounded(e.dofs) +
                                  " displacement DoFs, " + bytes_text(e.bytes) + " of memory (" +
                                  solver + " linear solver) and " + duration_text(e.seconds) +
                                  " for " + std::to_string(run.load_steps) +
                                  " load step(s) of ~5 Newton iterations";
      if (worst > 1.)
        throw InputError(run.refinement_entry + " = " + std::to_string(refinements) +
                         ": the refined mesh would need " + summary + ", more than the " +
                         bytes_text(physical) + " of memory of this machine" +
                         (ranks > 1 ? " (" + std::to_string(ranks_on_node) + " of the " +
                                          std::to_string(ranks) + " MPI ranks on it)"
                                    : std::string()) +
                         ". Use fewer refinements (each multiplies the cells by " +
                         std::to_string(1u << run.dim) + ") or more machines.");
      *run.pcout << "size estimate of the uniformly refined mesh (local refinements come on "
                    "top): "
                 << summary << " (" << bytes_text(physical) << " of memory on this machine)\n";
      if (e.seconds > seconds_to_warn_of)
        *run.pcout << "WARNING: the run is estimated to need " << duration_text(e.seconds) << " ("
                   << run.refinement_entry << " = " << refinements
                   << ", Load stepping/Number of load steps = " << run.load_steps
                   << "): fewer refinements, fewer load steps or more MPI ranks would shorten "
                      "it.\n";
      else if (run.load_steps > load_steps_to_warn_of)
        *run.pcout << "WARNING: Load stepping/Number of load steps = " << run.load_steps
                   << ": more than " << load_steps_to_warn_of
                   << " load steps, each a row of statistics.csv and a Newton solve; a few "
                      "hundred load steps resolve most load paths.\n";
    }

    std::string
    SizeCheck::refinement_entry(ParameterHandler &prm)
    {
      prm.enter_subsection("Geometry");
      const std::string model = prm.get("Model");
      prm.leave_subsection();
      return "Geometry/" + model + "/Global refinements";
    }
  } // namespace Geometry
} // namespace StabilizedLagrangian
