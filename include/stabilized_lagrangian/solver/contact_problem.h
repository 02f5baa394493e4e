#pragma once

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/timer.h>

#include <deal.II/distributed/fully_distributed_tria.h>
#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <boost/signals2/signal.hpp>

#include <stabilized_lagrangian/boundary_conditions/interface.h>
#include <stabilized_lagrangian/contact/contact_boundary.h>
#include <stabilized_lagrangian/discretization/fe_pair.h>
#include <stabilized_lagrangian/geometry/body_mesh.h>
#include <stabilized_lagrangian/geometry/scene.h>
#include <stabilized_lagrangian/materials/body_response.h>
#include <stabilized_lagrangian/materials/material.h>
#include <stabilized_lagrangian/materials/quadrature_history.h>
#include <stabilized_lagrangian/obstacles/obstacle.h>
#include <stabilized_lagrangian/parameters.h>
#include <stabilized_lagrangian/postprocessing/solution_output.h>
#include <stabilized_lagrangian/postprocessing/statistics.h>
#include <stabilized_lagrangian/solver/checkpoint.h>
#include <stabilized_lagrangian/solver/error_estimator.h>
#include <stabilized_lagrangian/solver/inf_sup_test.h>
#include <stabilized_lagrangian/solver/iterative_solver.h>
#include <stabilized_lagrangian/solver/linear_solver.h>
#include <stabilized_lagrangian/solver/load_path.h>
#include <stabilized_lagrangian/solver/load_step_controller.h>
#include <stabilized_lagrangian/solver/loop_policy.h>
#include <stabilized_lagrangian/solver/mesh_refinement.h>
#include <stabilized_lagrangian/solver/nested_loops.h>
#include <stabilized_lagrangian/solver/newton_solver.h>
#include <stabilized_lagrangian/solver/refinement_cycles.h>
#include <stabilized_lagrangian/solver/run_log.h>
#include <stabilized_lagrangian/solver/scene_bounds.h>
#include <stabilized_lagrangian/solver/scene_checks.h>
#include <stabilized_lagrangian/solver/step_statistics_collector.h>
#include <stabilized_lagrangian/solver/system_assembler.h>
#include <stabilized_lagrangian/solver/system_constraints.h>

#include <algorithm>
#include <functional>

namespace StabilizedLagrangian
{
  using namespace dealii;

  /**
   * @brief Quasi-static frictional contact of a deformable body with a rigid
   * obstacle or a second deformable body, stabilized Lagrangian mixed
   * formulation (doc/formulation.md).
   *
   * Unknowns: displacement u on the bodies, contact pressure λ_n and friction
   * semi-multiplier Λ on Γc only, assembled as one monolithic system
   * [u | λ_n, Λ] on distributed Trilinos objects. The problem owns the mesh,
   * the DoFs, the Newton system and the run's state, and asks one class per
   * concept for the rest (doc/architecture.md has the map): Γc and its
   * conditions (ContactBoundary), the law at a point (StabilizedPointLaw),
   * the Newton iteration and the loops of seed §2.2 (NewtonSolver,
   * NestedLoops), the load path and the refinement cycles (LoadPath,
   * RefinementCycles), the assembly (SystemAssembler), the checkpoints
   * (Checkpoint). Each reads the problem through a view its section of the
   * private part builds; each section names the file that defines it.
   */
  template <int dim> class ContactProblem
  {
  public:
    /**
     * @brief Build the problem from parsed parameters (declared by
     * Parameters::declare_all<dim>).
     * @param prm the parsed parameters
     * @param sections the condition subsections @p prm holds (Parameters::parse())
     * @param verbose print the progress to screen (rank 0)
     */
    ContactProblem(ParameterHandler                    &prm,
                   const Parameters::ConditionSections &sections,
                   const bool                           verbose = true);

    /**
     * @brief Solve the load path on each mesh of the refinement cycles
     * (contact_problem.cc, RefinementCycles); returns false if a step could not be solved.
     * @param resume continue from the checkpoint in the output directory
     * (Checkpoint::restore()) instead of starting from rest
     */
    bool
    run(const bool resume = false);

    /**
     * @brief The run's state, listed once (Checkpoint lists the problem's
     * own, source/solver/run_state_list.cc): what a step cut restores and a
     * checkpoint keeps. An extension adds the state it keeps here, before run().
     */
    RunState &
    run_state()
    {
      return state_list;
    }

    /**
     * @brief Called at the start of every attempt of a load step, with the
     * step's start and end time, once the state a step cut restores is saved:
     * an extension advances the state it added to run_state() here.
     */
    boost::signals2::signal<void(double start, double end)> load_step_attempt;

    /** @brief Whether run() stopped at `Load stepping/Wall time limit` (not a failure). */
    bool
    stopped_at_wall_time_limit() const
    {
      return load_path.stopped_at_wall_time_limit();
    }

    /** @brief Mesh, DoFs, multiplier numbering, sparsity, contact points (contact_problem.cc). */
    void
    setup();

    /**
     * @brief Numerical inf-sup test of the FE pair (InfSupTest, setup_checks.cc):
     * β_h on the scene's mesh and @p n_meshes − 1 global refinements of it,
     * printed and written to inf_sup.csv in the output directory. One MPI rank.
     */
    void
    run_inf_sup_test(const unsigned int n_meshes);

    /**
     * @brief Assemble the residual and (optionally) the Jacobian at the current
     * iterate with the contact statuses, thresholds and pairings frozen
     * (SystemAssembler, through assembly_view(); assembly.cc).
     */
    void
    assemble_newton_system(const bool assemble_matrix = true);

    /** @brief Number of displacement DoFs (the first block of the monolithic system). */
    types::global_dof_index
    n_displacement_dofs() const
    {
      return n_u;
    }

    /** @brief Number of multiplier DoFs on Γc (the second block). */
    types::global_dof_index
    n_multiplier_dofs() const
    {
      return n_multipliers;
    }

    /** @brief The monolithic iterate (locally owned part); writable, for tests. */
    TrilinosWrappers::MPI::Vector &
    current_solution()
    {
      return solution;
    }

    /** @brief Residual from the last assembly. */
    const TrilinosWrappers::MPI::Vector &
    residual() const
    {
      return system_rhs;
    }

    /** @brief Jacobian from the last assembly. */
    const TrilinosWrappers::SparseMatrix &
    jacobian() const
    {
      return system_matrix;
    }

    /** @brief Γc: its faces, the states of their points, its conditions; writable, for tests. */
    ContactBoundary<dim> &
    contact_boundary()
    {
      return contact;
    }

    /** @brief The multiplier element component (0: λ_n, 1..: Λ) of each owned multiplier row
     * (dofs.cc). */
    std::vector<std::pair<types::global_dof_index, unsigned int>>
    locally_owned_multiplier_components() const;

    /**
     * @brief Re-pair every contact point with the contact partner at the
     * current positions; with @p resegment,
     * first update the segments of the contact faces
     * (ContactBoundary::update_segments(); contact_points.cc).
     */
    void
    update_pairings(const bool resegment = false);
    /** @brief Refresh the ghosted copy of the iterate after current_solution() changed
     * (assembly.cc). */
    void
    update_ghosts();

  private:
    // --- load_path.cc: the load path on one mesh (LoadPath); refinement_cycles.cc:
    // the adaptive refinement cycles (RefinementCycles) ---
    /** What the load path reads and writes of this problem, and what it asks of it. */
    typename LoadPath<dim>::View
    load_path_view();
    /** What the refinement cycles read and write of this problem, and what they ask of it. */
    typename RefinementCycles<dim>::View
    refinement_cycles_view();

    // --- run_log.cc: the log of the load path and run_summary.csv (RunLog) ---
    /** What the log of the load path reads of this problem, now. */
    typename RunLog<dim>::View
    run_log_view() const;

    /** The energy estimate η and the solution's energy norm, at an iterate (ErrorEstimator). */
    using EnergyEstimate = StabilizedLagrangian::EnergyEstimate;

    // --- nested_loops.cc: the loops of seed §2.2 (NestedLoops) ---
    /** What the nested loops read and write of this problem, and what they ask of it. */
    typename NestedLoops<dim>::View
    nested_loops_view();

    // --- newton.cc: the Newton iteration (NewtonSolver; its line search in
    // newton_line_search.cc, a singular system in newton_singular_system.cc) ---
    /** What the Newton iteration reads and writes of this problem, and what it asks of it. */
    typename NewtonSolver<dim>::View
    newton_view();

    // --- run_state_list.cc: the view the checkpoints read (Checkpoint) ---
    /** What the checkpoints and the run's state list read and write of this problem. */
    typename Checkpoint<dim>::View
    checkpoint_view();

    // --- contact_problem.cc: the mesh (BodyMesh), and the setup after each refinement ---
    /** Build the mesh, resolve the boundaries and bodies the input names on it, check them. */
    void
    make_grid();
    /** Refuse a pair for the other cell shape, and what simplex meshes cannot do yet. */
    void
    check_cell_shape() const;
    /** DoFs, sparsity, contact points and history after the mesh changed. */
    void
    setup_after_refinement();

    // --- setup_checks.cc: what the checks of the scene (SceneChecks) and the
    // inf-sup test (InfSupTest) read; the start of a body nothing holds ---
    /** The scene as SceneChecks reads it, now. */
    typename SceneChecks<dim>::View
    scene_view() const;
    /** The discretisation as InfSupTest reads it, now. */
    typename InfSupTest<dim>::View
    inf_sup_view();
    /** Put the contact points nearest to the obstacle in contact (an unheld body's start). */
    void
    close_nearest_points();

    // --- dofs.cc: DoFs, multiplier numbering, sparsity; the constraints in SystemConstraints ---
    void
    setup_dofs();
    /**
     * The contact partner of this mesh: the rigid obstacle, or the deformable
     * master's surface holding the master faces near this rank's slave faces.
     */
    std::unique_ptr<Contact::Partner<dim>>
    make_partner() const;
    /** The vectors of the Newton system on this mesh's DoFs; the scaling of the residual rows. */
    void
    reinit_system_vectors();
    /** What the constraints of the Newton system read and write of this problem
     * (SystemConstraints). */
    typename SystemConstraints<dim>::View
    constraints_view();
    /**
     * The AMG's near-null space over the displacement's locally owned DoFs,
     * in their order: the dim translations, then with `AMG near-null space =
     * rigid body modes` the rotations (one in 2D, three in 3D) about the
     * origin of the reference configuration (not in an axisymmetric model).
     */
    std::vector<std::vector<double>>
    rigid_body_modes() const;
    /**
     * Boxes around this rank's slave contact faces, displaced by @p u at their
     * vertices (null: in the reference configuration): where the partner's
     * faces must be held for the search (Contact::Partner::gather_faces_near()).
     */
    std::vector<BoundingBox<dim>>
    slave_search_region(const TrilinosWrappers::MPI::Vector *u) const;
    /**
     * Collective: the partner gathers the faces near this rank's slave faces
     * in the configuration of ghosted_solution (following its DoFs with the
     * ghosts where it took new ones) and deforms them.
     */
    void
    update_partner_configuration();
    /**
     * Collective: the ghosts of the vectors, the constraints and (at the next
     * pairing) the sparsity pattern grow by the partner's DoFs, the values kept.
     */
    void
    follow_partner_dofs();
    /** What the boundary conditions read of the problem, now. */
    BoundaryConditions::Problem<dim>
    boundary_view() const;
    /**
     * The sparsity pattern and the matrix: the bodies, and on Γc the slave,
     * multiplier and (with a deformable master) the paired master faces' DoFs,
     * with their neighbours so that small sliding keeps the pattern.
     */
    void
    setup_sparsity();
    /** Whether some pairing left the master faces of the sparsity pattern (on any rank). */
    bool
    pairings_left_sparsity() const;

    // --- contact_points.cc: Γc on a new mesh, its pairing (ContactBoundary) ---
    /** Γc's points of this mesh, paired, with the statuses of the initial configuration. */
    void
    setup_contact_points();

    // --- assembly.cc: the Newton system (SystemAssembler, solver/system_assembler.h) ---
    /** What the assembly of the Newton system reads and writes of this problem, now. */
    typename SystemAssembler<dim>::View
    assembly_view();

    // --- refinement.cc: the view of a step's statistics (StepStatisticsCollector) and of the
    // adaptive refinement ---
    /** What the statistics of a converged step read and write of this problem. */
    typename StepStatisticsCollector<dim>::View
    statistics_view();
    /** The displacement block of the iterate, on the displacement DoFHandler (ghosted). */
    TrilinosWrappers::MPI::Vector
    ghosted_displacement() const;
    /** What a refinement of the mesh reads and writes of this problem (MeshRefinement). */
    typename MeshRefinement<dim>::View
    refinement_view();

    // --- error_estimator.cc: the residual error estimate (ErrorEstimator, doc/formulation.md,
    // "Error estimate") ---
    /** What the error estimate reads of this problem (its history of the ghost cells it writes). */
    typename ErrorEstimator<dim>::View
    error_estimator_view();
    /**
     * The error estimate of the converged state of a load step: η_K of every
     * locally owned cell into error_indicators, the totals (η, its contact
     * part, the pressure estimate, the energy norm of the solution) into @p stats.
     */
    void
    estimate_error(StepStatistics &stats);
    /**
     * The energy estimate η alone, at the current iterate (adaptive stopping):
     * no pressure estimate, error_indicators left as they are.
     */
    EnergyEstimate
    estimated_energy_error();

    // --- converged_step.cc ---
    /**
     * A load step (or the initial state, step 0) converged: sample Γc at the
     * iterate, commit the step's slip into cumulative_slip and write the output.
     */
    void
    commit_converged_step(const unsigned int step, const double time);
    /** the slip of Γc's nodes over the converged steps (a checkpoint keeps it) */
    CumulativeSlip<dim> cumulative_slip;

    /** Hand the output files of @p step the converged state and @p samples (SolutionOutput). */
    void
    output_results(const unsigned int                     step,
                   const double                           time,
                   const std::vector<ContactSample<dim>> &samples);
    /** The cell averages of the stress and the history fields of the iterate @p u (ghosted). */
    CellAverages
    cell_averages(const TrilinosWrappers::MPI::Vector &u) const;

    MPI_Comm           mpi_communicator;
    ConditionalOStream pcout;
    TimerOutput        timer;

    // the parsed input, in the order it is read (its first error is the one reported)
    std::unique_ptr<Geometry::Interface<dim>> geometry;
    /** `Geometry/Axisymmetric` (2D): x₁ is the radius r ≥ 0, x₂ the axis of revolution */
    const bool                axisymmetric;
    const Parameters::Contact contact_parameters;
    /** the boundary condition plug-ins, in the registry's order of kinds */
    std::vector<std::unique_ptr<BoundaryConditions::Interface<dim>>> boundary_conditions;
    const Parameters::LoadStepping                                   load_stepping;
    const Parameters::NonlinearSolver                                solver_parameters;
    const Parameters::LinearSolver                                   linear_solver_parameters;
    const Parameters::Output                                         output_parameters;
    const Parameters::AdaptiveRefinement                             adaptive_refinement;
    /** the values chosen from the input, the mesh and the materials (reported, not input) */
    ChosenParameters chosen;
    /** the current cycle's output: `Output/Output directory`, or its cycle's subdirectory */
    std::string output_directory;
    /** the process's memory before the mesh existed (MeshRefinement::refine checks growth) */
    Utilities::System::MemoryStats memory_at_start;
    /** why the run must stop rather than cut the load step (empty: it may cut) */
    std::string unrecoverable_failure;

    std::unique_ptr<Obstacles::Interface<dim>> obstacle;
    /** `Obstacle/Motion`: the rigid obstacle's translation d(t) */
    std::shared_ptr<Parameters::BoundaryFunction<dim>> obstacle_translation;
    /** `Obstacle/Motion/Rotation`: its rotation θ(t), null when it does not turn */
    std::shared_ptr<Parameters::BoundaryFunction<dim>> obstacle_rotation;
    /** the two, about `Obstacle/Motion/Rotation centre` */
    std::shared_ptr<const Contact::ObstacleMotion<dim>> obstacle_motion;
    /**
     * the contact partner, built with the DoFs (dofs.cc): the deformable
     * master's surface when `Contact/Master boundary ids` is set, else the obstacle
     */
    std::unique_ptr<Contact::Partner<dim>> partner;
    /** per contact face: the master faces whose DoFs the sparsity pattern couples to it */
    std::vector<std::vector<unsigned int>> sparsity_master_faces;
    bool                                   sparsity_ready = false;
    /** the locally relevant DoFs grew since the sparsity pattern was built */
    bool sparsity_stale = false;
    /** how often the ghosts grew by the partner's DoFs on this mesh (follow_partner_dofs()) */
    unsigned int partner_dof_growths = 0;
    /** `Contact/Friction law` and the contact zones (`Contact/Zone <name>`), each with its law */
    Contact::FrictionZones                       contact_zones;
    std::unique_ptr<Discretization::FEPair<dim>> fe_pair;
    Materials::QuadratureHistory                 material_history;
    /** Set by an assembly that met a material state outside its admissible range. */
    std::string inadmissible_state;

    /** the bodies' distributed mesh, its cell shape and quadratures */
    BodyMesh<dim>                                body_mesh;
    parallel::DistributedTriangulationBase<dim> &triangulation;
    std::unique_ptr<FiniteElement<dim>>          fe_u, fe_m;
    /**
     * per face number, fe_m's DoFs on that face, ascending (the face's own
     * DoFs: FE_SimplexP's has_support_on_face() says true for all)
     */
    std::vector<std::vector<unsigned int>> multiplier_dofs_on_face;
    DoFHandler<dim>                        dof_handler_u, dof_handler_m;
    Quadrature<dim>                        cell_quadrature;
    Quadrature<dim - 1>                    contact_quadrature;
    /**
     * the bodies' material slots, each cell's model and formulation, its
     * response and the F-bar fields (Materials::BodyResponse)
     */
    Materials::BodyResponse<dim> body_response{
        body_mesh, material_history, fe_pair, fe_u, dof_handler_u, cell_quadrature, axisymmetric};

    types::global_dof_index n_u           = 0;
    types::global_dof_index n_multipliers = 0;
    IndexSet                locally_owned, locally_relevant;
    IndexSet                locally_owned_u, locally_relevant_u;

    AffineConstraints<double> newton_constraints;  ///< hanging nodes + homogeneous Dirichlet
    AffineConstraints<double> hanging_constraints; ///< hanging nodes only

    TrilinosWrappers::SparseMatrix               system_matrix;
    std::unique_ptr<LinearSolvers::DirectSolver> direct_solver;
    /** `Linear solver/Method = iterative`; null with the direct solver */
    std::unique_ptr<LinearSolvers::BlockIterativeSolver> iterative_solver;
    TrilinosWrappers::MPI::Vector                        system_rhs;
    TrilinosWrappers::MPI::Vector                        solution; ///< owned
    TrilinosWrappers::MPI::Vector ghosted_solution; ///< relevant, kept in sync with solution
    TrilinosWrappers::MPI::Vector step_start;       ///< relevant, solution at the step start
    /** owned: the last accepted load step's change of every unknown (the predictor's slope) */
    TrilinosWrappers::MPI::Vector last_increment;
    /** the size of that step; 0 before a load path's first step and after a mesh change */
    double                        last_step_size = 0.;
    TrilinosWrappers::MPI::Vector residual_scaling; ///< 1, r_n or r_t per owned row
    /** owned: the nodal internal forces ∫σ:∇φ_i of the last assembly (reactions included) */
    TrilinosWrappers::MPI::Vector internal_force;
    /** the contact terms of the residual, without constraints (for the reactions) */
    TrilinosWrappers::MPI::Vector contact_residual;
    /** owned: the nodal external (Neumann, spring, plate) forces of the last assembly */
    TrilinosWrappers::MPI::Vector external_force;
    /**
     * owned, multiplier rows: the weight that turns the row's residual into a
     * length, ∫|ψ_j| on the λ_n rows and ∫|ψ_j| (χ_f s + (1 − χ_f) r_t) on the Λ rows
     */
    TrilinosWrappers::MPI::Vector multiplier_length_weights;
    /** the multiplier element component (0: λ_n, 1..: Λ) of each owned multiplier row */
    std::vector<std::pair<types::global_dof_index, unsigned int>> owned_multiplier_components;
    WorkCounters                                                  work;
    /**
     * E_max h_min^(dim−2): the nodal stiffness of the stiffest, smallest cell
     * (N/mm; per mm of thickness in 2D), for the floor of the force scale
     */
    double nodal_stiffness = 0.;
    /**
     * 1e-12 E_max (MPa): a contact pressure below it is round-off, and the
     * friction threshold sees zero there (StabilizedPointLaw::threshold_pressure())
     */
    double negligible_pressure = 0.;
    /** the bodies' size and the prescribed displacements: what an iterate may not exceed */
    SceneBounds bounds;
    /** the rigid motions no Dirichlet condition holds, in words; empty if none */
    std::string free_rigid_motions;
    /** |g_n| at most this counts as touching in the status test (round-off of the coordinates) */
    double touching_gap = 0.;
    /** how a step starts a contact that would hold a body (ContactStart) */
    ContactStart contact_start;
    /** relevant: the Dirichlet increment Δū of the load step (apply_dirichlet_values()) */
    TrilinosWrappers::MPI::Vector dirichlet_increment;
    /** whether Δū is non-zero: the step's first Newton iteration is then the predictor */
    bool dirichlet_increment_nonzero = false;
    /** set by the predictor around its assembly alone: add_to_global_system() adds K Δū */
    bool dirichlet_predictor = false;

    double time = 0.;
    /** reference positions of the points in contact at the end of some step on this mesh */
    std::vector<Point<dim>> active_set;
    double                  last_normal_force = 0.;
    bool                    verbose;
    /** The spaces FaceEvaluator reads, views of this problem's members. */
    const ContactSpaces<dim> spaces;
    /** The law at a contact point (pairing, threshold, status, seed eqs. (5)–(8)). */
    const StabilizedPointLaw<dim> law{{partner,
                                       ghosted_solution,
                                       step_start,
                                       contact_zones,
                                       chosen.r_n,
                                       chosen.r_t,
                                       loops,
                                       touching_gap,
                                       contact_start.approach_gap,
                                       negligible_pressure,
                                       contact_start.provisional_pressure}};
    /** which loops iterate, which are folded into Newton (LoopPolicy) */
    LoopPolicy loops;
    /** Γc: its faces, the states of their contact points and the contact conditions */
    ContactBoundary<dim> contact{{spaces,
                                  body_mesh,
                                  fe_pair,
                                  dof_handler_u,
                                  contact_quadrature,
                                  contact_parameters,
                                  adaptive_refinement,
                                  contact_zones,
                                  chosen,
                                  law,
                                  partner,
                                  ghosted_solution,
                                  locally_owned,
                                  locally_relevant,
                                  n_u,
                                  hanging_constraints,
                                  loops,
                                  negligible_pressure,
                                  mpi_communicator,
                                  pcout}};
    std::string          parameters_used;
    /** the output files of the converged steps (VTU, profiles, obstacle, .pvd records) */
    SolutionOutput<dim> solution_output;
    StatisticsWriter    statistics;
    /** where the load stepping stands (LoadStepController works on it; a checkpoint keeps it) */
    LoadStepController::State controller;
    unsigned int              cycle = 0; ///< adaptive refinement cycle
    std::string  run_directory;   ///< `Output directory` (the cycles write into subdirectories)
    WorkCounters path_start_work; ///< work when the load path began
    /** η_K of the last converged state per active cell (√(N mm)), owned cells only */
    Vector<float> error_indicators;
    /** the statistics of the last converged load step */
    StepStatistics last_step;
    /**
     * `Errors against the last cycle`: the displacement at the end of each
     * cycle's load path, carried through the refinements (ghosted, on
     * dof_handler_u), and each cycle's DoFs and error estimate
     */
    std::vector<TrilinosWrappers::MPI::Vector>              earlier_cycles;
    std::vector<std::pair<types::global_dof_index, double>> cycle_records;
    /** `Contact/Check inf-sup`: β_h of each cycle's mesh so far */
    InfSupTest<dim> inf_sup{mpi_communicator, contact_parameters, pcout};
    /** per adaptive refinement cycle, the cells this rank flagged for refinement */
    std::vector<std::vector<CellId>> refinement_history;
    /** the run's state: what a step cut restores and a checkpoint keeps */
    RunState state_list;
    /** the Newton iteration, called by the nested loops and the generalized Newton alike */
    NewtonSolver<dim> newton{newton_view()};
    /** the loops of seed §2.2 around it: geometry → friction threshold → status */
    NestedLoops<dim> nested_loops{nested_loops_view()};
    /** the checkpoints, and the problem's own entries of state_list */
    Checkpoint<dim> checkpoint{checkpoint_view()};
    /** the load path on the current mesh, and the clock of `Load stepping/Wall time limit` */
    LoadPath<dim> load_path{load_path_view()};
    /** the adaptive refinement cycles around it */
    RefinementCycles<dim> refinement_cycles{refinement_cycles_view()};
  };
} // namespace StabilizedLagrangian
