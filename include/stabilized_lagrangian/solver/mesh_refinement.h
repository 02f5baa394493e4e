#pragma once

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>
#include <deal.II/base/utilities.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/grid/cell_id.h>
#include <deal.II/grid/tria.h>

#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <stabilized_lagrangian/parameters.h>

#include <functional>
#include <vector>

/**
 * @file
 * The adaptive refinement between two cycles (`Adaptive refinement`): which
 * cells the criterion flags, whether the refined mesh fits in memory, and the
 * refinement itself with what follows the mesh.
 */

namespace StabilizedLagrangian
{
  using namespace dealii;

  /**
   * @brief One refinement of the mesh by the criterion of `Adaptive
   * refinement`: the active set's band, every cell, the Kelly indicators or
   * the error estimate's η_K. It owns nothing: it flags and refines the mesh
   * of a View and writes what follows the mesh (the flags a checkpoint
   * replays, the displacements of the earlier cycles) through it.
   */
  template <int dim> class MeshRefinement
  {
  public:
    /** What the refinement reads of the problem, and (named so) what it writes. */
    struct View
    {
      /** written: flagged and refined (a p4est mesh: refinement is refused on simplices) */
      Triangulation<dim> &triangulation;
      /** written: the flags this rank set, one entry appended per refinement */
      std::vector<std::vector<CellId>> &refinement_history;
      /** written: the displacements of the earlier cycles, carried to the new mesh */
      std::vector<TrilinosWrappers::MPI::Vector> &earlier_cycles;
      const DoFHandler<dim>                      &displacement_dofs;
      /** the displacement DoFs, those of the new mesh after the set-up */
      const IndexSet                       &locally_owned_u;
      const IndexSet                       &locally_relevant_u;
      const unsigned int                    displacement_degree;
      const Parameters::AdaptiveRefinement &parameters;
      /** η_K of the last converged load step (ErrorEstimator) */
      const Vector<float> &error_indicators;
      /** the points in contact of the last converged step (this rank's) */
      const std::vector<Point<dim>> &active_set;
      /** the process's memory before the mesh existed */
      const Utilities::System::MemoryStats &memory_at_start;
      const bool                            iterative_solver; ///< its memory grows linearly
      const MPI_Comm                        communicator;
      const ConditionalOStream             &pcout;
      /** the displacement of the last converged state, ghosted (Kelly) */
      std::function<TrilinosWrappers::MPI::Vector()> ghosted_displacement;
      /** set up the DoFs and the problem on the refined mesh */
      std::function<void()> setup_after_refinement;
      /**
       * the squared pressure mismatch of each cell's faces on Γc, of the last
       * converged state (ErrorEstimator::pressure_indicators)
       */
      std::function<Vector<float>()> pressure_indicators;
    };

    /** @brief A refinement of the mesh @p view shows. */
    explicit MeshRefinement(const View &view)
        : view(view)
    {
    }

    /**
     * @brief Refine the mesh by the criterion of `Adaptive refinement` (after
     * checking that it fits in memory), set up the problem on the new mesh
     * and carry earlier_cycles over to it.
     */
    void
    refine();

  private:
    /** Flag the cells the criterion chooses. */
    void
    flag_cells();
    /**
     * Flag cells by @p indicators (one per active cell) as `Marking` says:
     * the `Refined fraction` of the cells with the largest, or the fewest
     * whose squares carry that fraction of the sum.
     */
    void
    mark_for_refinement(const Vector<float> &indicators);
    /**
     * With a `Target pressure error` (Kelly, estimator): flag the cells under
     * Γc whose faces carry most of the pressure mismatch, and the cells
     * sharing a face with them.
     */
    void
    flag_for_pressure();
    /** Flag the cells near the recorded active set for refinement. */
    void
    refine_around_active_set();
    /** Flag every locally owned cell for refinement. */
    void
    flag_every_cell();
    /**
     * Collective: throw when a mesh @p growth times larger would not fit in
     * the machine's memory (estimated from the peak so far).
     */
    void
    check_memory_for_growth(double growth) const;
    /** Refine the flagged cells, set up the problem and carry earlier_cycles over. */
    void
    execute();

    const View view;
  };
} // namespace StabilizedLagrangian
