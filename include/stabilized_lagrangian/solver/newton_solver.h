#pragma once

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <stabilized_lagrangian/contact/contact_boundary.h>
#include <stabilized_lagrangian/parameters.h>
#include <stabilized_lagrangian/postprocessing/statistics.h>
#include <stabilized_lagrangian/solver/error_estimator.h>
#include <stabilized_lagrangian/solver/iterative_solver.h>
#include <stabilized_lagrangian/solver/linear_solver.h>
#include <stabilized_lagrangian/solver/loop_policy.h>
#include <stabilized_lagrangian/solver/scene_bounds.h>

#include <algorithm>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

/**
 * @file
 * The Newton iteration of a load step (doc/formulation.md, "Stopping
 * criteria", "Adaptive stopping"): one object that the nested loops of seed
 * §2.2 and the generalized Newton of seed §2.3 both call, reading the problem
 * through a view.
 */

namespace StabilizedLagrangian
{
  using namespace dealii;

  /**
   * @brief The blocks of the Newton residual, each against its own scale
   * (doc/formulation.md, "Newton stopping criterion"): dimensionless.
   */
  struct ScaledResidual
  {
    double force = 0.; ///< force rows against the largest nodal internal or external force
    double gap   = 0.; ///< λ_n rows as lengths (a gap) against the largest displacement
    double slip  = 0.; ///< Λ rows as lengths (a stick point's slip) against it

    /** @brief The largest block: what the `scaled` criterion compares with the tolerance. */
    double
    largest() const
    {
      return std::max({force, gap, slip});
    }
  };

  /**
   * @brief Work done since the start of the run, failed attempts included:
   * what a comparison of algorithms must count.
   */
  struct WorkCounters
  {
    unsigned long newton_iterations   = 0; ///< Newton iterations (one linear solve each)
    unsigned long assemblies          = 0; ///< residual assemblies, with or without the Jacobian
    unsigned long jacobians           = 0; ///< assemblies with the Jacobian
    unsigned long krylov_iterations   = 0; ///< GMRES iterations (Linear solver/Method = iterative)
    unsigned long iterative_fallbacks = 0; ///< systems GMRES left to the direct solver
    /** wall time (s, this rank) of the iterative solver's phases
     * (LinearSolvers::BlockIterativeSolver::PhaseTimes) */
    double amg_setup_seconds   = 0.;
    double schur_seconds       = 0.;
    double krylov_seconds      = 0.;
    double schur_solve_seconds = 0.;
  };

  /**
   * @brief How a step starts a contact that would hold a body and has not
   * started yet (the Newton system singular without it; doc/formulation.md,
   * "What a converged state must satisfy"); cleared when a step converges or
   * is cut.
   */
  struct ContactStart
  {
    /**
     * |g_n| at most this also counts as touching, for one Newton solve: set
     * by close_nearest_points() when nothing touches (a body lowered until
     * it touches)
     */
    double approach_gap = 0.;
    /** whether this step has lowered the body onto its partner */
    bool approach_used = false;
    /**
     * the pressure the friction threshold sees where λ_n is still zero, for
     * one Newton solve: set when points in contact hold nothing
     * tangentially because their threshold μ λ_n is zero
     */
    double provisional_pressure = 0.;
    /** whether this step has used provisional_pressure */
    bool provisional_used = false;
    /**
     * the friction loop's fixed thresholds left every point in contact
     * slipping and the system singular: the attempt is repeated with the
     * threshold folded into the generalized Newton (solve_load_step())
     */
    bool fold_friction = false;
    /** whether this attempt is that repetition */
    bool friction_folded = false;
  };

  /**
   * @brief The Newton iteration on the monolithic system at frozen (or, with
   * the generalized Newton, linearised) pairings, thresholds and statuses:
   * the loop and its stopping criteria, the tangent predictor, the linear
   * solve, what is done when the system is singular, and the line search
   * (newton.cc, newton_singular_system.cc, newton_line_search.cc).
   *
   * It owns what only the iteration keeps (the last discretisation error
   * estimate of adaptive stopping) and asks the problem, through a View, for
   * what only the problem can do: assemble the system at the iterate, refresh
   * the ghosts, the contact conditions' statuses and the contact points.
   */
  template <int dim> class NewtonSolver
  {
  public:
    /** Call f(state, kinematics) at every locally owned contact point, its state frozen. */
    using PointVisitor =
        std::function<void(ContactPointState<dim> &, const ContactKinematics<dim> &)>;

    /**
     * @brief What the iteration reads and writes of the problem: views of its
     * members, and the operations only the problem can do.
     */
    struct View
    {
      // --- the input, read
      const Parameters::NonlinearSolver &parameters;
      const Parameters::LinearSolver    &linear_solver_parameters;
      bool                               log_newton; ///< `Output/Log Newton`
      MPI_Comm                           communicator;
      const ConditionalOStream          &pcout;
      TimerOutput                       &timer;
      std::string                        force_unit; ///< N, or N/mm in plane strain
      // --- the system and the layout, read
      const IndexSet                       &locally_owned;
      const IndexSet                       &locally_owned_u;
      const AffineConstraints<double>      &newton_constraints;
      const TrilinosWrappers::SparseMatrix &system_matrix;
      /** 1, r_n or r_t per owned row */
      const TrilinosWrappers::MPI::Vector &residual_scaling;
      /** owned: the nodal external forces of the last assembly */
      const TrilinosWrappers::MPI::Vector &external_force;
      /** relevant: the Dirichlet increment Δū of the load step */
      const TrilinosWrappers::MPI::Vector &dirichlet_increment;
      const bool                          &dirichlet_increment_nonzero;
      /** set by an assembly that met a material state outside its admissible range */
      const std::string                                          &inadmissible_state;
      const std::unique_ptr<LinearSolvers::DirectSolver>         &direct_solver;
      const std::unique_ptr<LinearSolvers::BlockIterativeSolver> &iterative_solver;
      const SceneBounds                                          &bounds;
      /** the rigid motions no Dirichlet condition holds, in words */
      const std::string &free_rigid_motions;
      /** a contact pressure below it is round-off */
      const double     &negligible_pressure;
      const LoopPolicy &loops;
      /** Γc: its conditions' statuses */
      const ContactBoundary<dim> &contact;
      const ContactPointLaw<dim> &law;
      // --- what the iteration writes
      /** owned: the iterate, moved by the line search */
      TrilinosWrappers::MPI::Vector &solution;
      /** the residual of the last assembly, negated into the right-hand side of a solve */
      TrilinosWrappers::MPI::Vector &system_rhs;
      /** set around the predictor's assembly alone: the assembly then adds K Δū */
      bool &dirichlet_predictor;
      /** started contacts, provisional pressures and the fold of the friction loop */
      ContactStart &contact_start;
      /** why the run must stop rather than cut the load step */
      std::string  &unrecoverable_failure;
      WorkCounters &work;
      // --- what only the problem can do
      /** assemble the residual (and with true, the Jacobian) at the iterate */
      std::function<void(bool)>                 assemble;
      std::function<double()>                   residual_norm;
      std::function<ScaledResidual()>           scaled_residual;
      std::function<void()>                     update_ghosts;
      std::function<EnergyEstimate()>           estimated_energy_error;
      std::function<unsigned int()>             points_in_contact;
      std::function<void()>                     close_nearest_points;
      std::function<bool()>                     any_friction;
      std::function<bool()>                     any_pressure_dependent_threshold;
      std::function<void(const PointVisitor &)> for_each_contact_point;
      /**
       * Collective: the first of the first @p end of @p seen equal to
       * @p statuses on every rank, or @p end if none is.
       */
      std::function<unsigned int(const std::vector<std::vector<unsigned char>> &seen,
                                 const std::vector<unsigned char>              &statuses,
                                 unsigned int                                   end)>
          first_equal;
    };

    /** @brief The iteration on the problem @p problem views. */
    explicit NewtonSolver(const View &problem);

    /**
     * @brief The Newton loop at the outer loops' iterate (geometry
     * @p geometry_iteration, friction @p friction_iteration, status
     * @p status_iteration, recorded in @p stats): true when it converged or
     * stopped adaptively; false, with the reason printed, when the step must
     * be cut or repeated.
     */
    bool
    solve(StepStatistics    &stats,
          const unsigned int geometry_iteration,
          const unsigned int friction_iteration,
          const unsigned int status_iteration);

    /**
     * @brief Adaptive stopping's test, shared by Newton and the nested loops
     * (doc/formulation.md, "Adaptive stopping"): whether @p change_energy, the
     * energy of a loop's last change, is below `Adaptive stopping fraction`
     * γ of the discretisation error η estimated at the current iterate, and
     * @p relative_change, the loop's own relative measure (its criterion's),
     * below γ η / ‖u‖. The estimate is skipped (false) while the change is
     * above twice what the last one (last_estimate()) allows.
     */
    bool
    below_discretisation_error(const double change_energy, const double relative_change);

    /** @brief The discretisation error estimated at the last check of any loop. */
    const EnergyEstimate &
    last_estimate() const
    {
      return estimate;
    }

    /**
     * @brief (δuᵀ K δu)^½ of the displacement part of @p update, K the last
     * solve's matrix.
     */
    double
    displacement_energy(const TrilinosWrappers::MPI::Vector &update) const;

    /**
     * @brief Whether the state the loops converged to is one a quasi-static
     * contact problem can have (SceneBounds::implausible()): finite, no node
     * moved far beyond the scene's extent. If not, the reason is printed and
     * the step is failed.
     */
    bool
    plausible_converged_state() const;

  private:
    /**
     * The open/stick/slip statuses of a Newton loop's iterates, when Newton
     * decides them: the line search takes a full step whole while the active
     * set settles.
     */
    struct ActiveSetWatch
    {
      std::vector<std::vector<unsigned char>> seen;
      unsigned int last_changes = std::numeric_limits<unsigned int>::max();
    };
    /** What a Newton loop carries from one iteration to the next. */
    struct Progress
    {
      explicit Progress(const bool newton_decides_statuses)
          : newton_decides_statuses(newton_decides_statuses)
      {
      }
      /** The watch of the active set, when Newton decides the statuses. */
      ActiveSetWatch *
      active_set_watch()
      {
        return newton_decides_statuses ? &watch : nullptr;
      }
      unsigned int iteration     = 0;
      double       first_measure = 0.; ///< the criterion's measure at iteration 0
      /** the energy norm (δuᵀ K δu)^½ of the last Newton direction's displacement, √(N mm) */
      double update_energy     = std::numeric_limits<double>::infinity();
      double previous_residual = std::numeric_limits<double>::infinity();
      /** the relative tolerance of the last iterative linear solve (Eisenstat–Walker) */
      double forcing_term = 0.;
      /** the criterion's tolerance over its measure at the iterate: the reduction still needed */
      double needed_reduction = 1.;
      /** whether the last assembly, at the iterate, has the Jacobian */
      bool           jacobian_current = true;
      const bool     newton_decides_statuses;
      ActiveSetWatch watch;
    };
    /** The residual at a Newton iterate as the stopping criterion measures it. */
    struct Measure
    {
      double residual  = 0.; ///< in N
      double scaled    = 0.; ///< the largest scaled block
      double measure   = 0.; ///< what the criterion compares with the tolerance
      double tolerance = 0.;
    };
    /** The points in contact of the current iterate, by what they hold tangentially. */
    struct ContactCensus
    {
      unsigned int in_contact        = 0;  ///< points in contact
      unsigned int slipping          = 0;  ///< of which slip
      unsigned int without_threshold = 0;  ///< of which have s = 0 (friction laws with friction)
      double       area              = 0.; ///< the area in contact
    };

    // --- newton.cc: the loop, its measure and the linear solve
    /**
     * `Nonlinear solver/Stopping = adaptive`: whether the last update's energy
     * is below the fraction of the discretisation error estimated at the
     * iterate.
     */
    bool
    adaptive_stop(Progress &progress, const double scaled_residual);
    /**
     * The tangent predictor, the first Newton iteration of a load step whose
     * Dirichlet increment Δū is non-zero (doc/formulation.md, "Stopping
     * criteria"): the residual linearised at u + Δū, R(u) + K Δū, is solved
     * for, and the step, Δū included, is taken whole.
     */
    bool
    predictor_step(StepStatistics &stats, Progress &progress);
    /**
     * The residual of the last assembly, measured (and logged); false, with
     * the reason printed, when the iterate cannot go on.
     */
    bool
    measure_iterate(Progress &progress, Measure &measured) const;
    /**
     * The Newton update at the iterate; false, with the reason printed, at an
     * iteration limit, an unsupported body or a failed linear solve.
     */
    bool
    newton_direction(const StepStatistics          &stats,
                     Progress                      &progress,
                     const Measure                 &measured,
                     TrilinosWrappers::MPI::Vector &update);
    /** Whether the Newton loop may take another iteration (its limits, a supported body). */
    bool
    may_iterate(const StepStatistics &stats, const Progress &progress, const Measure &measured);
    /** Assemble the Jacobian if needed and solve the Newton system for @p update. */
    bool
    solve_for_update(Progress &progress, TrilinosWrappers::MPI::Vector &update);
    /** Print a Newton iterate: the residual in N and its scaled blocks. */
    void
    log_iterate(const unsigned int iteration) const;

    // --- newton_singular_system.cc: a singular or nearly singular Newton system
    /**
     * After a singular or nearly singular Newton system: start the contact
     * that would hold the body, if it has not started (close_nearest_points)
     * or if its points in contact hold nothing tangentially for want of a
     * friction threshold (a provisional pressure for one solve). True if
     * something changed and the solve is worth repeating.
     */
    bool
    start_holding_contact();
    /**
     * Print why a Newton system is singular or nearly so: @p symptom (what the
     * solve gave), the rigid motions the supports leave free and the points in
     * contact that could hold them, and the usual causes.
     */
    void
    report_near_singular(const std::string &symptom) const;
    /** Count the points of the current iterate (collective). */
    ContactCensus
    contact_census() const;
    /**
     * After a singular solve: if the friction loop's fixed thresholds s leave
     * every point in contact slipping (Tresca thresholds too small for the
     * tangential loads, so nothing holds the motion along the contact), ask
     * for the step to be repeated with the threshold folded into the
     * generalized Newton (ContactStart::fold_friction) and return true.
     */
    bool
    fold_friction_for_slipping_contact();

    // --- newton_line_search.cc: the line search
    /**
     * Move the iterate along @p update (line search with at most
     * @p max_halvings) and count the iteration.
     */
    void
    advance(Progress                            &progress,
            const TrilinosWrappers::MPI::Vector &update,
            const double                         residual,
            const unsigned int                   max_halvings);
    /**
     * Backtracking along @p update from the current iterate (residual
     * @p residual, the one before @p previous_residual); with @p watch, a
     * full step that settles the active set is taken whole.
     */
    void
    line_search(const TrilinosWrappers::MPI::Vector &update,
                const double                         residual,
                const double                         previous_residual,
                const unsigned int                   max_halvings,
                ActiveSetWatch                      *watch);
    /** Collective: whether the statuses at the trial iterate settle the active set of @p watch. */
    bool
    settling(ActiveSetWatch &watch) const;
    /** Print a line-search trial: step length, residual, open/stick/slip counts. */
    void
    log_trial(const double step) const;

    /** the problem's members and operations */
    View problem;
    /** `Stopping = adaptive`: the discretisation error estimated at the last check of any loop */
    EnergyEstimate estimate;
  };
} // namespace StabilizedLagrangian
