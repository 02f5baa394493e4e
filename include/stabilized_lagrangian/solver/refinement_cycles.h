#pragma once

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/timer.h>

#include <deal.II/distributed/tria_base.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe.h>

#include <deal.II/lac/trilinos_vector.h>

#include <stabilized_lagrangian/materials/body_response.h>
#include <stabilized_lagrangian/materials/material.h>
#include <stabilized_lagrangian/parameters.h>
#include <stabilized_lagrangian/postprocessing/statistics.h>
#include <stabilized_lagrangian/solver/inf_sup_test.h>
#include <stabilized_lagrangian/solver/load_path.h>

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

/**
 * @file
 * The adaptive refinement cycles (`Adaptive refinement/Cycles`,
 * source/solver/refinement_cycles.cc): the load path solved on each mesh in
 * turn, refinement_cycles.csv, the accuracy targets and cycle_errors.csv.
 */

namespace StabilizedLagrangian
{
  using namespace dealii;

  /**
   * @brief The adaptive refinement cycles: the load path (LoadPath) on the
   * scene's mesh, then on each refinement of it (MeshRefinement), each
   * cycle's output in its own directory and its row in refinement_cycles.csv;
   * with an accuracy target (`Target error`, `Target pressure error`) the
   * cycles stop once it is met and the last one's output moves into the
   * run's directory (target_error.csv); with `Errors against the last cycle`
   * each cycle's displacement is measured against the last one's
   * (cycle_errors.csv).
   *
   * It owns nothing that a checkpoint keeps: the cycle number, the earlier
   * cycles' displacements and records are the problem's, read and written
   * through a View.
   */
  template <int dim> class RefinementCycles
  {
  public:
    /**
     * @brief What the cycles read and write of the problem: views of its
     * members, and the operations only the problem can do.
     */
    struct View
    {
      // --- the input, read
      const Parameters::AdaptiveRefinement &adaptive_refinement;
      MPI_Comm                              communicator;
      const ConditionalOStream             &pcout;
      TimerOutput                          &timer;
      /** `Output/Output directory` (the cycles write into subdirectories) */
      const std::string &run_directory;
      /** the unit of forces as a column name's suffix (N or N_per_mm) */
      std::string force_unit;
      // --- the discretisation and the last load step, read
      const parallel::DistributedTriangulationBase<dim> &triangulation;
      const types::global_dof_index                     &n_u;
      const types::global_dof_index                     &n_multipliers;
      const std::unique_ptr<FiniteElement<dim>>         &fe_u;
      const DoFHandler<dim>                             &dof_handler_u;
      const Quadrature<dim>                             &cell_quadrature;
      const StatisticsWriter                            &statistics;
      const StepStatistics                              &last_step;
      const double                                      &last_normal_force;
      // --- what the cycles write
      /** the adaptive refinement cycle */
      unsigned int &cycle;
      double       &time;
      /** the current cycle's output directory */
      std::string &output_directory;
      /** `Contact/Check inf-sup`: β_h of each cycle's mesh */
      InfSupTest<dim> &inf_sup;
      /**
       * `Errors against the last cycle`: each cycle's displacement at the end
       * of its load path (ghosted, on dof_handler_u), DoFs and error estimate
       */
      std::vector<TrilinosWrappers::MPI::Vector>              &earlier_cycles;
      std::vector<std::pair<types::global_dof_index, double>> &cycle_records;
      /** the load path on each cycle's mesh */
      LoadPath<dim> &load_path;
      /** the bodies' committed material response (the energy norm of cycle_errors.csv) */
      const Materials::BodyResponse<dim> &body_response;
      // --- what only the problem can do
      /** refine the mesh by the criterion (MeshRefinement) and set up after it */
      std::function<void()>                           refine;
      std::function<typename InfSupTest<dim>::View()> inf_sup_view;
      /** the displacement block of the iterate (ghosted) */
      std::function<TrilinosWrappers::MPI::Vector()> ghosted_displacement;
      /** the measure of the model at a point (2πr when axisymmetric) */
      std::function<double(const Point<dim> &)> radial_weight;
    };

    /** @brief The cycles of the problem @p problem views. */
    explicit RefinementCycles(const View &problem);

    /**
     * @brief Solve the load path on each cycle's mesh from @p first_cycle
     * (with @p resume, the first from the state a checkpoint restored);
     * false if a load path could not be solved.
     */
    bool
    run(const unsigned int first_cycle, const bool resume);

    /**
     * @brief The output directory of cycle @p k: the run's for the last cycle,
     * else cycle-k/ below it (with an accuracy target every cycle's, until
     * the target's cycles end).
     */
    std::string
    directory(const unsigned int k) const;

  private:
    /** What the cycles took in all (an accuracy target reports it). */
    struct Totals
    {
      double        wall_time         = 0.;
      unsigned long newton_iterations = 0;
    };
    /** Start refinement_cycles.csv (a fresh run with cycles). */
    void
    start_log(const bool resume) const;
    /** Add the cycle to @p totals and its row to refinement_cycles.csv. */
    void
    record(const double wall_time, Totals &totals) const;
    /**
     * Whether the last load step's estimates meet the accuracy targets (the
     * pressure by pressure_error_bound()).
     */
    bool
    targets_met() const;
    /**
     * The last load step's pressure estimate divided by the smallest
     * effectivity measured against closed forms: what `Target pressure error`
     * is compared with.
     */
    double
    pressure_error_bound() const;
    /**
     * After the cycles of an accuracy target: move the output of cycle @p last
     * into the run's directory, report the cost and write target_error.csv.
     */
    void
    finish_targeted(const unsigned int last, const Totals &totals);
    /**
     * Write cycle_errors.csv into the run's directory: each earlier cycle's
     * displacement against the last one's (earlier_cycles), beside its error
     * estimate.
     */
    void
    write_cycle_errors() const;

    /** the problem's members and operations */
    View problem;
  };
} // namespace StabilizedLagrangian
