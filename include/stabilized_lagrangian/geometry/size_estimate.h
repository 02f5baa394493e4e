#pragma once

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <stabilized_lagrangian/parameters.h>

#include <string>

namespace StabilizedLagrangian
{
  namespace Geometry
  {
    using namespace dealii;

    /**
     * @brief What a run will need, estimated from the mesh before its uniform
     * refinement: orders of magnitude from measured runs (size_estimate.cc).
     */
    struct SizeEstimate
    {
      double cells   = 0.; ///< of the refined mesh
      double dofs    = 0.; ///< displacement DoFs (the multipliers live on a surface)
      double bytes   = 0.; ///< memory of all ranks together
      double seconds = 0.; ///< wall time of the load path, on the ranks of the run
    };

    /**
     * @brief The check of a run's size before the mesh is refined and the DoFs
     * are distributed (issue 50): the estimate is printed on one line; a run
     * whose memory would exceed the machine's is refused with an InputError
     * naming the refinement entry; a run estimated to need more than a day,
     * or with a huge number of load steps, gets a warning before its first step.
     */
    class SizeCheck
    {
    public:
      /** The run's figures the estimate needs, known before the mesh. */
      struct Run
      {
        unsigned int dim;
        unsigned int displacement_degree;
        /** `Geometry/<model>/Global refinements`, named by the messages */
        std::string               refinement_entry;
        Parameters::LinearSolver  linear_solver;
        unsigned int              load_steps;
        MPI_Comm                  communicator;
        const ConditionalOStream *pcout;
      };

      explicit SizeCheck(const Run &run)
          : run(run)
      {
      }

      /**
       * @brief The estimate for @p coarse_cells cells refined @p refinements
       * times, each then split into @p simplices_per_cell simplices (1: none),
       * of which @p simplex says whether they are simplices.
       */
      SizeEstimate
      estimate(const double       coarse_cells,
               const unsigned int refinements,
               const unsigned int simplices_per_cell,
               const bool         simplex) const;

      /**
       * @brief Estimate the run on @p coarse_cells cells refined @p refinements
       * times (see estimate()), print it, and refuse (InputError) or warn.
       * Collective over the run's communicator.
       */
      void
      before_refinement(const double       coarse_cells,
                        const unsigned int refinements,
                        const unsigned int simplices_per_cell,
                        const bool         simplex) const;

      /** The refinement entry of the geometry chosen in @p prm: `Geometry/<model>/Global
       * refinements`. */
      static std::string
      refinement_entry(ParameterHandler &prm);

    private:
      Run run;

      /** Whether the run uses the iterative linear solver for @p dofs unknowns. */
      bool
      iterative(const double dofs) const;
    };
  } // namespace Geometry
} // namespace StabilizedLagrangian
