#pragma once

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>
#include <deal.II/base/quadrature.h>

#include <deal.II/grid/cell_id.h>
#include <deal.II/grid/tria.h>

#include <deal.II/lac/trilinos_vector.h>

#include <stabilized_lagrangian/contact/contact_boundary.h>
#include <stabilized_lagrangian/contact/contact_surface.h>
#include <stabilized_lagrangian/contact/cumulative_slip.h>
#include <stabilized_lagrangian/contact/friction_zones.h>
#include <stabilized_lagrangian/materials/quadrature_history.h>
#include <stabilized_lagrangian/parameters.h>
#include <stabilized_lagrangian/postprocessing/solution_output.h>
#include <stabilized_lagrangian/postprocessing/statistics.h>
#include <stabilized_lagrangian/solver/chosen_parameters.h>
#include <stabilized_lagrangian/solver/load_step_controller.h>
#include <stabilized_lagrangian/solver/newton_solver.h>
#include <stabilized_lagrangian/solver/run_state.h>
#include <stabilized_lagrangian/solver/state_archive.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

/**
 * @file
 * Checkpoint and restart (`Output/Checkpoint interval`, `--resume`): the
 * problem's own entries of the run's state (RunState) and the checkpoint
 * directory that keeps them with the mesh they live on.
 */

namespace StabilizedLagrangian
{
  using namespace dealii;

  /**
   * @brief The checkpoints of a run: it lists the problem's own state in the
   * run's RunState (what a step cut restores and a checkpoint keeps;
   * source/solver/run_state_list.cc), writes the checkpoint directory and
   * restores a run from it (source/solver/checkpoint.cc), rebuilding the mesh
   * by the refinements the run made. It owns nothing: it reads and writes the
   * problem's state through a View.
   */
  template <int dim> class Checkpoint
  {
  public:
    /** What the checkpoint reads of the problem, and (named so) what it writes. */
    struct View
    {
      const MPI_Comm            communicator;
      const ConditionalOStream &pcout;
      /** the run's state list this class adds the problem's entries to */
      RunState &state_list;
      /** the parameters of the run as printed (kept beside the checkpoint) */
      const std::string                    &parameters_used;
      const Parameters::AdaptiveRefinement &adaptive_refinement;
      /** `Load stepping/End time`: a resume must have some of it left */
      const double                 &end_time;
      const ChosenParameters       &chosen;
      const Contact::FrictionZones &contact_zones;
      /** `Output directory`: the run's, where the checkpoint is */
      const std::string &run_directory;
      /** written while a resume continues the output files (then the run's again) */
      std::string &output_directory;
      /** written: the adaptive refinement cycle of a restored checkpoint */
      unsigned int &cycle;
      /** written: refined again by a restore, as refinement_history lists it */
      Triangulation<dim> &triangulation;
      /** written by a restore: the flags each refinement of the run set on this rank */
      std::vector<std::vector<CellId>> &refinement_history;
      const types::global_dof_index    &n_u;
      const types::global_dof_index    &n_multipliers;
      const IndexSet                   &locally_owned;
      const Quadrature<dim - 1>        &contact_quadrature;
      // written by a restore (and a step cut): the entries of the run's state
      double                              &time;
      LoadStepController::State           &controller;
      WorkCounters                        &work;
      WorkCounters                        &path_start_work;
      double                              &last_normal_force;
      double                              &last_step_size;
      TrilinosWrappers::MPI::Vector       &solution;
      const TrilinosWrappers::MPI::Vector &ghosted_solution;
      TrilinosWrappers::MPI::Vector       &step_start;
      TrilinosWrappers::MPI::Vector       &last_increment;
      Materials::QuadratureHistory        &material_history;
      /** Γc: its faces' segments, its points' and its conditions' states */
      ContactBoundary<dim>    &contact;
      std::vector<Point<dim>> &active_set;
      CumulativeSlip<dim>     &cumulative_slip;
      SolutionOutput<dim>     &solution_output;
      StatisticsWriter        &statistics;
      /** refresh the ghosted copy of the solution */
      std::function<void()> update_ghosts;
      /** set up the DoFs and the problem on the refined mesh */
      std::function<void()> setup_after_refinement;
      /** the output directory of refinement cycle k */
      std::function<std::string(unsigned int)> cycle_directory;
      /** the supports statistics.csv has columns for */
      std::function<StatisticsWriter::Supports()> statistics_supports;
    };

    /** @brief The checkpoints of the problem @p view shows. */
    explicit Checkpoint(const View &view)
        : view(view)
    {
    }

    /**
     * @brief Add the problem's own state to the run's state list, in the
     * order it is read back (run_state_list.cc).
     */
    void
    register_run_state();

    /** @brief Write a checkpoint of the current state (every rank), replacing the previous one. */
    void
    write() const;

    /**
     * @brief Rebuild the mesh and restore the state of the checkpoint in the
     * output directory (after setup()); returns the adaptive refinement cycle
     * it was taken in.
     */
    unsigned int
    restore();

  private:
    // --- run_state_list.cc ---
    /** The time, the load stepping, the work counters, the last force and step size. */
    void
    register_load_stepping_state();
    /** The solution, the predictor's last increment, the material history. */
    void
    register_field_state();
    /** The contact faces' segments, the points' and the nodes' states, the slip. */
    void
    register_contact_state();
    /** What the output files continue from: the .pvd records, the CSV files' sizes. */
    void
    register_output_state();

    // --- checkpoint.cc ---
    /** The size of refinement_cycles.csv (rank 0; 0 elsewhere). */
    unsigned long
    cycles_log_bytes() const;
    /** Refine the mesh again as refinement_history lists it, cell by cell. */
    void
    replay_refinements();
    /** Cut the output files back to the checkpoint's rows and continue them. */
    void
    continue_outputs(const unsigned long            cycles_bytes,
                     const StatisticsWriter::State &statistics_state);

    const View view;
  };
} // namespace StabilizedLagrangian
