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
#include <deal.II/fe/fe_values.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <boost/signals2/signal.hpp>

#include <stabilized_lagrangian/boundary_conditions/interface.h>
#include <stabilized_lagrangian/contact/contact_conditions.h>
#include <stabilized_lagrangian/contact/contact_edge.h>
#include <stabilized_lagrangian/contact/contact_surface.h>
#include <stabilized_lagrangian/contact/cumulative_slip.h>
#include <stabilized_lagrangian/contact/friction_law.h>
#include <stabilized_lagrangian/contact/friction_law_check.h>
#include <stabilized_lagrangian/contact/friction_zones.h>
#include <stabilized_lagrangian/contact/partner.h>
#include <stabilized_lagrangian/contact/stabilized_lagrangian.h>
#include <stabilized_lagrangian/discretization/fe_pair.h>
#include <stabilized_lagrangian/geometry/body_mesh.h>
#include <stabilized_lagrangian/geometry/scene.h>
#include <stabilized_lagrangian/materials/f_bar.h>
#include <stabilized_lagrangian/materials/material.h>
#include <stabilized_lagrangian/materials/quadrature_history.h>
#include <stabilized_lagrangian/obstacles/obstacle.h>
#include <stabilized_lagrangian/parameters.h>
#include <stabilized_lagrangian/postprocessing/solution_output.h>
#include <stabilized_lagrangian/postprocessing/statistics.h>
#include <stabilized_lagrangian/solver/checkpoint.h>
#include <stabilized_lagrangian/solver/chosen_parameters.h>
#include <stabilized_lagrangian/solver/error_estimator.h>
#include <stabilized_lagrangian/solver/inf_sup_test.h>
#include <stabilized_lagrangian/solver/iterative_solver.h>
#include <stabilized_lagrangian/solver/linear_solver.h>
#include <stabilized_lagrangian/solver/load_step_controller.h>
#include <stabilized_lagrangian/solver/loop_policy.h>
#include <stabilized_lagrangian/solver/mesh_refinement.h>
#include <stabilized_lagrangian/solver/nested_loops.h>
#include <stabilized_lagrangian/solver/newton_solver.h>
#include <stabilized_lagrangian/solver/run_log.h>
#include <stabilized_lagrangian/solver/run_state.h>
#include <stabilized_lagrangian/solver/scene_bounds.h>
#include <stabilized_lagrangian/solver/scene_checks.h>

#include <algorithm>
#include <functional>
#include <map>

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
   * [u | λ_n, Λ] on distributed Trilinos objects. The members are defined by
   * phase, in source/solver/ (each section of the private part names its
   * file): contact_problem.cc the mesh (built and held by BodyMesh,
   * geometry/body_mesh.h) and the setup, setup_checks.cc what
   * the checks of the scene and the inf-sup test read and the start of a
   * body nothing holds, dofs.cc DoFs and sparsity, constraints.cc the constraints,
   * contact_points.cc pairing and statuses, assembly.cc the Newton system,
   * load_path.cc the load steps, run_log.cc the view the log reads,
   * nested_loops.cc the view the loops of seed §2.2 read, newton.cc the view
   * the Newton iteration reads, converged_step.cc what an accepted step commits,
   * refinement.cc the step's statistics and reactions, the adaptive
   * refinement's view and the cycles' errors, run_state_list.cc the view the
   * checkpoints read. The checkpoints and the problem's entries of the run's
   * state (what a step cut restores and a checkpoint keeps) are Checkpoint's
   * (solver/checkpoint.h: checkpoint.cc, run_state_list.cc). The loops of
   * seed §2.2 are NestedLoops' (solver/nested_loops.h), the Newton iteration
   * they call NewtonSolver's
   * (solver/newton_solver.h: newton.cc, newton_singular_system.cc,
   * newton_line_search.cc); the log of the load path and run_summary.csv are
   * written by RunLog (solver/run_log.h), the output files are written by SolutionOutput
   * (postprocessing/solution_output.h), the scene is checked by SceneChecks
   * (solver/scene_checks.h), the pair by InfSupTest (solver/inf_sup_test.h),
   * the residual error estimate is ErrorEstimator's (solver/error_estimator.h;
   * error_estimator.cc builds its view) and the refinement of the mesh
   * MeshRefinement's (solver/mesh_refinement.h); the mesh is BodyMesh's
   * (geometry/body_mesh.h), the friction laws of Γc and its zones are
   * Contact::FrictionZones (contact/friction_zones.h).
   */
  template <int dim> class ContactProblem : private ContactPointLaw<dim>
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
     * @brief Solve every load step (load_path.cc); returns false if a step could not be solved.
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
      return wall_time_limit_reached;
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
     * (assembly.cc, as the residuals below).
     */
    void
    assemble_newton_system(const bool assemble_matrix = true);

    /** @brief Residual max norm in force units (multiplier rows scaled by r_n, r_t). */
    double
    residual_norm() const;

    /** @brief The blocks of the last assembled residual against their scales. */
    ScaledResidual
    scaled_residual() const;

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

    /** @brief Frozen states of the locally owned contact points; writable, for tests. */
    std::vector<ContactPointState<dim>> &
    contact_points()
    {
      return contact_states;
    }

    /**
     * @brief With `Complementarity = weighted`, freeze the status of the k-th
     * owned multiplier node to @p in_contact(k) and every threshold to
     * @p threshold; for tests. Returns the number of owned nodes.
     */
    unsigned int
    freeze_nodal_conditions(const std::function<bool(unsigned int)> &in_contact,
                            const double                             threshold);

    /**
     * @brief The multiplier mass matrix M_jk = ∫_Γc ψ_j φ_k of this rank's
     * contact faces (weighted_contact.cc), per pair of multiplier nodes (their
     * λ_n DoFs): ψ_j the run's multiplier basis, φ_k the standard (nodal) one.
     * Diagonal, D_jj = ∫φ_j, with a dual pair. The entries of nodes shared
     * with another rank are this rank's part.
     */
    std::map<std::pair<types::global_dof_index, types::global_dof_index>, double>
    multiplier_mass() const;

    /** @brief The multiplier element component (0: λ_n, 1..: Λ) of each owned multiplier row
     * (dofs.cc). */
    std::vector<std::pair<types::global_dof_index, unsigned int>>
    locally_owned_multiplier_components() const;

    /**
     * @brief Re-pair every contact point with the contact partner at the
     * current positions; with @p resegment,
     * first update the segments of the contact faces (update_segments();
     * both in contact_points.cc).
     */
    void
    update_pairings(const bool resegment = false);
    /**
     * Cut the contact faces into segments at the projections of the deformed
     * master's vertices (2D, deformable master) and rebuild the contact points
     * of the faces whose segments changed, with thresholds and statuses
     * evaluated at the current iterate. Returns whether any face changed.
     */
    bool
    update_segments();

    /** @brief Refresh the ghosted copy of the iterate after current_solution() changed
     * (assembly.cc). */
    void
    update_ghosts();

  private:
    /** One face of Γc on a locally owned cell (contact_surface.h). */
    using ContactFace = StabilizedLagrangian::ContactFace<dim>;
    /** The contact points of @p face. */
    const Quadrature<dim - 1> &
    face_quadrature(const ContactFace &face) const
    {
      return face.segments ? *face.segments : contact_quadrature;
    }

    /** The evaluation of the fields on one contact face (contact_surface.h). */
    using FaceEvaluator = StabilizedLagrangian::FaceEvaluator<dim>;

    /**
     * The segments of one contact face (ContactFace::segments) from its
     * current corners (@p corners: a FaceEvaluator at the face's vertices):
     * 2D, the cuts at the projected master vertices; 3D, the parts of the
     * projected master faces (Contact::face_segments()); null: nothing to cut.
     */
    std::shared_ptr<const Quadrature<dim - 1>>
    face_segments(const FaceEvaluator &corners) const;

    // --- weighted_contact.cc: the choice of the contact conditions ---
    bool
    weighted_complementarity() const
    {
      return chosen.weighted_complementarity();
    }
    /**
     * @brief `Complementarity = automatic`: weighted for two deformable bodies
     * and dual pairs, pointwise against a rigid obstacle and where weighted does
     * not apply (doc/formulation.md, "Which conditions by default"), into
     * chosen.complementarity. The constrained multiplier nodes are seen by
     * setup_nodal_conditions().
     */
    void
    choose_complementarity();
    /** With `automatic`: the choice and its reason, logged once the mesh is known */
    std::string complementarity_choice;
    /** ContactFace::dual_basis of every contact face, with a dual pair. */
    void
    set_dual_multiplier_basis();
    /**
     * The contact conditions of this mesh (make_contact_conditions(), the one
     * place that names them): refuse, or with `automatic` avoid, the weighted
     * conditions on constrained multiplier nodes.
     */
    void
    setup_contact_conditions();
    /** What the contact conditions read and write: views of this problem's members. */
    ContactConditionsData<dim>
    conditions_data();

    // --- load_path.cc: load steps, step cuts ---
    /** What the refinement cycles took in all (an accuracy target reports it). */
    struct CycleTotals
    {
      double        wall_time         = 0.;
      unsigned long newton_iterations = 0;
    };
    /** Start refinement_cycles.csv (a fresh run with cycles). */
    void
    start_cycle_log(const bool resume) const;
    /**
     * The output directory of cycle @p k: the run's for the last cycle, else
     * cycle-k/ below it (with an accuracy target every cycle's, until
     * finish_targeted_cycles()).
     */
    std::string
    cycle_directory(const unsigned int k) const;
    /** Add the cycle to @p totals and its row to refinement_cycles.csv. */
    void
    record_cycle(const double wall_time, CycleTotals &totals) const;
    /** Whether the last load step's estimates meet the accuracy targets. */
    bool
    targets_met() const;
    /**
     * After the cycles of an accuracy target: move the output of cycle @p last
     * into the run's directory, report the cost and write target_error.csv.
     */
    void
    finish_targeted_cycles(const unsigned int last, const CycleTotals &totals);
    /**
     * The whole load path on the current mesh, from rest, or with @p resumed
     * from the state a checkpoint restored.
     */
    bool
    solve_load_path(const bool resumed = false);
    /** Open the output of a load path from rest; the next step is the nominal one. */
    void
    start_load_path(LoadStepController &steps);
    /**
     * After a failed attempt (the state restored): cut the step and return
     * true, or report why the path stops and return false.
     */
    bool
    cut_load_step(LoadStepController &steps);
    /** Commit a converged step: its statistics, output and log line. */
    void
    record_load_step(StepStatistics &stats, PathLog &path, const Timer &step_clock);
    /**
     * Warn of a slow pace after the first step; at `Load stepping/Wall time
     * limit`, checkpoint (unless @p checkpointed), report and return true.
     */
    bool
    stop_at_wall_time_limit(const LoadStepController &steps,
                            const PathLog            &path,
                            const bool                checkpointed);
    /**
     * `Nonlinear solver/Predictor = extrapolation`: move the iterate by the
     * last accepted step's change of every unknown, scaled to @p step_size
     * (doc/formulation.md, "Predictor").
     */
    void
    extrapolate_last_step(const double step_size);
    void
    apply_dirichlet_values(const double time);

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
    /** Whether the cells are triangles / tetrahedra (BodyMesh::simplex()). */
    bool
    simplex_mesh() const
    {
      return body_mesh.simplex();
    }
    /**
     * The measure of the model at @p x: 2πr (r = x₁) in an axisymmetric model,
     * whose integrals are over the solid of revolution (forces are totals over
     * the circumference), 1 otherwise (2D: per unit thickness).
     */
    double
    radial_weight(const Point<dim> &x) const
    {
      return spaces.radial_weight(x);
    }
    /**
     * The hoop strain u_r / r at @p x of an axisymmetric model, 0 otherwise;
     * on the axis its limit ∂u_r/∂r (u_r = 0 there), from @p grad_u.
     */
    double
    hoop_strain(const Point<dim> &x, const Tensor<1, dim> &u, const Tensor<2, dim> &grad_u) const
    {
      if (!axisymmetric)
        return 0.;
      return x[0] > 0. ? u[0] / x[0] : grad_u[0][0];
    }
    /** The reference cell of the mesh's cells (BodyMesh::cell_shape()). */
    ReferenceCell
    cell_shape() const
    {
      return body_mesh.cell_shape();
    }
    /** The Gauss rule of the cells with @p n points per direction (BodyMesh::cell_gauss()). */
    Quadrature<dim>
    cell_gauss(const unsigned int n) const
    {
      return body_mesh.cell_gauss(n);
    }
    /** The Gauss rule of the faces with @p n points per direction (BodyMesh::face_gauss()). */
    Quadrature<dim - 1>
    face_gauss(const unsigned int n) const
    {
      return body_mesh.face_gauss(n);
    }
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
    inf_sup_view() const;
    /** Collective: the number of contact points whose status χ is contact. */
    unsigned int
    points_in_contact() const;
    /** Put the contact points nearest to the obstacle in contact (an unheld body's start). */
    void
    close_nearest_points();

    // --- dofs.cc: DoFs, multiplier numbering, sparsity; constraints.cc: the constraints ---
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
    /** The hanging-node and Newton constraints on the locally relevant DoFs (collective). */
    void
    setup_constraints();
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
    void
    setup_multiplier_numbering();
    /** The cell of the multiplier DoFHandler that is @p cell of the displacement one. */
    typename DoFHandler<dim>::active_cell_iterator
    multiplier_cell(const typename DoFHandler<dim>::active_cell_iterator &cell) const
    {
      return spaces.multiplier_cell(cell);
    }
    /** Whether face @p f of @p cell lies on the contact boundary Γc. */
    template <typename CellIterator>
    bool
    is_contact_face(const CellIterator &cell, const unsigned int f) const
    {
      return cell->face(f)->at_boundary() &&
             chosen.contact_boundaries.count(cell->face(f)->boundary_id()) > 0;
    }
    /** Whether face @p f of @p cell lies on Γc or on the master surface of a second body. */
    template <typename CellIterator>
    bool
    is_slave_or_master_face(const CellIterator &cell, const unsigned int f) const
    {
      return is_contact_face(cell, f) ||
             (cell->face(f)->at_boundary() &&
              chosen.master_boundaries.count(cell->face(f)->boundary_id()) > 0);
    }
    /**
     * Call f(dof, i) for each multiplier DoF on a contact face of the
     * non-artificial cells, in the multiplier DoFHandler's numbering (i: its
     * index in the cell; a DoF of several faces is visited once per face).
     */
    template <typename Function>
    void
    for_each_contact_multiplier_dof(const Function &f) const
    {
      for_each_contact_multiplier_face(
          [&](const std::vector<types::global_dof_index> &dofs, const unsigned int face) {
            for (const unsigned int i : multiplier_face_dofs(face))
              f(dofs[i], i);
          });
    }
    /**
     * Call f(dofs, face) for each contact face of the non-artificial cells,
     * with the multiplier DoFs of its cell (multiplier numbering).
     */
    template <typename Function>
    void
    for_each_contact_multiplier_face(const Function &f) const
    {
      std::vector<types::global_dof_index> dofs(fe_m->n_dofs_per_cell());
      for (const auto &cell : dof_handler_m.active_cell_iterators())
        if (!cell->is_artificial())
          for (const unsigned int face : cell->face_indices())
            if (is_contact_face(cell, face))
              {
                cell->get_dof_indices(dofs);
                f(dofs, face);
              }
    }
    /** The multiplier element's DoFs on face @p face of a cell, ascending (setup_dofs()). */
    const std::vector<unsigned int> &
    multiplier_face_dofs(const unsigned int face) const
    {
      return multiplier_dofs_on_face[face];
    }
    /** Multiplier continuity at hanging vertices of Γc (3D), in the monolithic numbering. */
    void
    add_multiplier_hanging_node_constraints(AffineConstraints<double> &constraints) const;
    /**
     * Λ_α = 0 at the vertices of Γc whose displacement along the (fixed) tangent
     * t_α of a plane obstacle is prescribed: there the stick condition leaves
     * Λ_α undetermined (the Dirichlet reaction carries the friction) and the
     * Newton system would be singular. On a symmetry plane, 0 is the symmetric value.
     */
    void
    add_prescribed_slip_constraints(AffineConstraints<double> &constraints) const;
    /** The multiplier of a coarse-mesh pair: multilinear on the parents of the contact faces. */
    void
    add_multiplier_coarsening_constraints(AffineConstraints<double> &constraints) const;
    /** u_i = 0 on the Dirichlet boundaries (the Newton update's constraints). */
    void
    add_homogeneous_dirichlet_constraints(AffineConstraints<double> &constraints) const;
    /** Axisymmetric: u_r = 0 at the DoFs on the axis r = 0. */
    void
    add_axis_constraints(AffineConstraints<double> &constraints) const;
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

    // --- contact_points.cc: pairing, segments, kinematics, statuses, thresholds ---
    void
    setup_contact_points();
    /** The consistent nodal weights of the contact faces (ContactFace::nodal_weights). */
    void
    set_consistent_nodal_weights();
    /** Whether any material is finite strain. */
    bool
    finite_strain() const;
    /** Call f(state, kinematics) at every locally owned contact point, nothing re-evaluated. */
    template <typename Function>
    void
    visit_contact_points(const Function &f)
    {
      FaceEvaluator evaluator(spaces, contact_quadrature);
      for (const auto &face : contact_faces)
        {
          evaluator.reinit(face, ghosted_solution);
          for (unsigned int q = 0; q < evaluator.n_points(); ++q)
            f(contact_states[face.first_point + q], evaluator.kinematics(q));
        }
    }
    /**
     * At every locally owned contact point, evaluate what @p what names
     * (evaluate_point_state()) and call f(before, state, kinematics) with the
     * state before and after.
     */
    template <typename Function>
    void
    refresh_contact_points(const PointRefresh &what, const Function &f)
    {
      visit_contact_points([&](ContactPointState<dim> &state, ContactKinematics<dim> k) {
        const ContactPointState<dim> before = state;
        evaluate_point_state(state, k, what);
        f(before, state, k);
      });
    }
    /** Call f(state, kinematics) at every locally owned contact point, its state frozen. */
    template <typename Function>
    void
    for_each_contact_point(const Function &f)
    {
      visit_contact_points([&](ContactPointState<dim> &state, ContactKinematics<dim> k) {
        evaluate_point_state(state, k, PointRefresh());
        f(state, k);
      });
    }
    /**
     * The point-wise stabilized Lagrangian with the status and threshold of
     * @p state (with the threshold's slope when it is linearised).
     */
    Contact::PointResponse<dim - 1>
    point_response(const ContactPointState<dim> &state,
                   const ContactKinematics<dim> &k) const override;
    /**
     * The one evaluation of a contact point's state at the iterate, which the
     * loops, the folded refresh in the assembly and the output share: pair the
     * point anew (with @p what.pairing), let the pairing follow the partner's
     * displacement (the slip increment becomes relative, Δu¹ − Δu²(ξ)), then
     * evaluate the friction threshold and the status as @p what names.
     */
    void
    evaluate_point_state(ContactPointState<dim> &state,
                         ContactKinematics<dim> &k,
                         const PointRefresh     &what) const override;
    /**
     * The gap the status test sees: @p gap, or 0 within touching_gap (or
     * approach_gap) of zero.
     */
    double
    status_gap(const double gap) const override
    {
      return std::abs(gap) <= std::max(touching_gap, contact_start.approach_gap) ? 0. : gap;
    }
    /** The contact status χ of seed eq. (5) at a point, with status_gap(). */
    bool
    status(const ContactPointState<dim> &state, const ContactKinematics<dim> &k) const;
    /** The pressure the friction threshold sees: λ_n, or 0 below negligible_pressure. */
    double
    threshold_pressure(double contact_pressure) const override;

    // --- assembly.cc: assembly of the Newton system and its residual ---
    /** The material of a cell (by its body, `Material 2`, `Material 3`, else `Material`). */
    const Materials::Interface<dim> &
    material_of(const typename Triangulation<dim>::cell_iterator &cell) const
    {
      return *body_of(cell).model;
    }
    /** The material slot of a cell: its model and formulation. */
    const Materials::BodyMaterial<dim> &
    body_of(const typename Triangulation<dim>::cell_iterator &cell) const
    {
      return materials[body_mesh.material_slot(cell->material_id())];
    }
    /**
     * The response of @p cell's material at its quadrature point @p q (the
     * history's) or reference point @p unit for @p grad_u, from the committed
     * history (that of the last converged state); the updated history is
     * discarded. With F-bar and mixed, ∂P̃/∂v̄ into @p d_kept when given; in an
     * axisymmetric model @p hoop is the hoop strain u_r/r. For
     * the output and the error estimate, never the assembly.
     */
    Materials::Response<dim>
    committed_response(const typename Triangulation<dim>::cell_iterator &cell,
                       const unsigned int                                q,
                       const Point<dim>                                 &unit,
                       const Tensor<2, dim>                             &grad_u,
                       Tensor<2, dim>                                   *d_kept = nullptr,
                       const double                                      hoop   = 0.) const
    {
      const auto          history = material_history.committed(cell->active_cell_index(), q);
      std::vector<double> discarded(history.size());
      const auto         &body = body_of(cell);
      if (!body.modified_volume())
        return body.model->evaluate(grad_u, history, make_array_view(discarded), hoop);
      // The estimate evaluates the stress between the quadrature points too,
      // where a cell whose quadrature points are admissible may be inverted
      // (J ≤ 0 at a face point of an hourglassing cell): there, the centre's state.
      const unsigned int                     index      = cell->active_cell_index();
      const Materials::VolumeProjection<dim> projection = volume_projection(body);
      const bool                             finite     = body.model->is_finite_strain();
      const double kept = projection.value(kept_volume_coefficients[index], unit);
      const bool   admissible =
          !finite || (determinant(unit_symmetric_tensor<dim>() + grad_u) > 0. && kept > 0.);
      return material_response(body,
                               admissible ? grad_u : centre_gradients[index],
                               admissible ? kept : kept_volume_coefficients[index][0],
                               history,
                               make_array_view(discarded),
                               d_kept);
    }
    /**
     * The response of @p body's model at one quadrature point from the
     * history @p committed (the updated one into @p trial): P and ∂P/∂F at
     * @p grad_u; with F-bar or mixed the weak-form stress P̃, ∂P̃/∂F and, into
     * @p d_kept when given, ∂P̃/∂v̄ for the volume change @p kept the point
     * keeps (include/stabilized_lagrangian/materials/f_bar.h); @p hoop: the hoop
     * strain u_r/r of an axisymmetric model (displacement formulation only).
     */
    Materials::Response<dim>
    material_response(const Materials::BodyMaterial<dim> &body,
                      const Tensor<2, dim>               &grad_u,
                      const double                        kept,
                      const ArrayView<const double>      &committed,
                      const ArrayView<double>            &trial,
                      Tensor<2, dim>                     *d_kept,
                      const double                        hoop = 0.) const
    {
      if (!body.modified_volume())
        return body.model->evaluate(grad_u, committed, trial, hoop);
      const Materials::FBar<dim> f_bar(grad_u, kept, body.model->is_finite_strain());
      Materials::Response<dim>   weak;
      Tensor<2, dim>             unused;
      f_bar.weak_form(body.model->evaluate_3d(f_bar.modified_gradient(), committed, trial),
                      weak,
                      d_kept ? *d_kept : unused);
      return weak;
    }
    /**
     * The projection of the volume change of @p body's cells: degree 0 for
     * F-bar (one sample, the centre) and for mixed on Q1 and simplices, degree 1
     * for mixed on Q2 (Q2/P1disc).
     */
    Materials::VolumeProjection<dim>
    volume_projection(const Materials::BodyMaterial<dim> &body) const
    {
      const bool p1 = body.volumetric == Materials::BodyMaterial<dim>::Volumetric::mixed &&
                      !simplex_mesh() && fe_pair->displacement_degree() == 2;
      return Materials::VolumeProjection<dim>(
          p1 ? 1 : 0, cell_gauss(1).point(0), body.model->is_finite_strain());
    }
    /**
     * F-bar and mixed: the gradient of @p u at the centre of every cell this
     * rank holds (owned and ghost) and the coefficients of its kept volume
     * change, for committed_response(); nothing when no material slot asks
     * for them.
     */
    void
    compute_volume_fields(const TrilinosWrappers::MPI::Vector &u) const;
    void
    assemble_volume(const bool assemble_matrix);
    void
    assemble_contact(const bool assemble_matrix);
    /**
     * Add the boundary conditions' face terms (the tractions of the Neumann
     * conditions and the springs) on @p cell's faces to @p cell_rhs (the springs' stiffness to @p
     * cell_matrix), and the external force they make to external_force.
     */
    void
    add_boundary_loads(const typename DoFHandler<dim>::active_cell_iterator &cell,
                       const std::vector<types::global_dof_index>           &dofs,
                       const std::vector<double>                            &coefficients,
                       FEFaceValues<dim>                                    &face_values,
                       FullMatrix<double>                                   &cell_matrix,
                       Vector<double>                                       &cell_rhs,
                       Vector<double>                                       &cell_external,
                       const bool                                            assemble_matrix);
    /** Add a local system to the global one (with the tangent predictor, if pending). */
    void
    add_to_global_system(const FullMatrix<double>                   &local_matrix,
                         Vector<double>                             &local_rhs,
                         const std::vector<types::global_dof_index> &dofs,
                         const bool                                  assemble_matrix);

    // --- refinement.cc: contact statistics of a step, the view of the adaptive refinement ---
    /** Forces and point counts of a converged step; records the active set. */
    void
    compute_contact_statistics(StepStatistics &stats);
    /**
     * The boundary ids with a Dirichlet condition or springs, each once: the
     * Dirichlet ones in the order of their subsections, then the springs'.
     */
    std::vector<types::boundary_id>
    supported_boundaries() const;
    /**
     * The unit of forces: N, or per unit thickness in plane strain, N/mm
     * (@p column: as a column name's suffix, N_per_mm).
     */
    std::string
    force_unit(const bool column) const
    {
      if (dim == 3 || axisymmetric)
        return "N";
      return column ? "N_per_mm" : "N/mm";
    }
    /** The supports statistics.csv has columns for: the supported boundaries, the conditions' own.
     */
    StatisticsWriter::Supports
    statistics_supports() const;
    /**
     * The reaction of each supported boundary of the converged state, into
     * stats.reactions: the sum over its constrained DoFs of the residual
     * without constraints (internal minus applied forces plus the contact
     * terms; a DoF on two such boundaries counts for the first), plus the
     * springs' force ∫ −K (u − u_0); and the conditions' own statistics.
     */
    void
    compute_reactions(StepStatistics &stats) const;
    /** The displacement block of the iterate, on the displacement DoFHandler (ghosted). */
    TrilinosWrappers::MPI::Vector
    ghosted_displacement() const;
    /** What a refinement of the mesh reads and writes of this problem (MeshRefinement). */
    typename MeshRefinement<dim>::View
    refinement_view();
    /**
     * Write cycle_errors.csv into @p directory: each earlier cycle's
     * displacement against the last one's (earlier_cycles), beside its error
     * estimate.
     */
    void
    write_cycle_errors(const std::string &directory) const;

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
    /** The converged state at the nodes of Γc, evaluated afresh at the iterate. */
    std::vector<ContactSample<dim>>
    sample_contact_surface();
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
    /** wall time since the problem was built, for `Load stepping/Wall time limit` */
    Timer run_clock;
    bool  wall_time_limit_reached = false;
    /** why the run must stop rather than cut the load step (empty: it may cut) */
    std::string unrecoverable_failure;

    std::unique_ptr<Obstacles::Interface<dim>> obstacle;
    /** `Obstacle/Motion`: the rigid obstacle's translation d(t) */
    std::shared_ptr<Parameters::BoundaryFunction<dim>> obstacle_translation;
    /** `Obstacle/Motion/Rotation`: its rotation θ(t), null when it does not turn */
    std::shared_ptr<Parameters::BoundaryFunction<dim>> obstacle_rotation;
    /** the two, about `Obstacle/Motion/Rotation centre` */
    std::shared_ptr<const Contact::ObstacleMotion<dim>> obstacle_motion;
    /** the default model first, then the slots in use (BodyMesh::material_slot() of a body) */
    std::vector<Materials::BodyMaterial<dim>> materials;
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
    Contact::FrictionZones contact_zones;
    /** The friction law at a contact point: its zone's, or Contact/Friction law. */
    const FrictionLaws::Interface &
    friction_law_of(const ContactPointState<dim> &state) const override
    {
      return contact_zones.law_of(state.zone);
    }
    /** Whether some zone has friction (then Λ exists on the whole of Γc). */
    bool
    any_friction() const
    {
      return contact_zones.any_friction();
    }
    /** Whether some zone's threshold depends on the pressure (then the friction loop iterates). */
    bool
    any_pressure_dependent_threshold() const
    {
      return contact_zones.any_pressure_dependent_threshold();
    }
    std::unique_ptr<Discretization::FEPair<dim>> fe_pair;
    Materials::QuadratureHistory                 material_history;
    /** Set by an assembly that met a material state outside its admissible range. */
    std::string inadmissible_state;

    /** F-bar: ∇u at each cell's centre for the output and the error estimate (by active index) */
    mutable std::vector<Tensor<2, dim>>              centre_gradients;
    mutable std::vector<std::array<double, dim + 1>> kept_volume_coefficients;
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
     * The vertices of the point loads and point Dirichlet conditions: the
     * vertex of the mesh nearest to each Point, refused when it is not at the
     * point (to 1e-6 of the body's size) or hangs.
     */
    void
    find_point_dofs();
    /** The DoFs of the vertex at @p point, per component (@p section names it in errors). */
    std::array<types::global_dof_index, dim>
    vertex_dofs(const Point<dim> &point, const std::string &section) const;
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
     * friction threshold sees zero there (threshold_pressure())
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

    std::vector<ContactFace>            contact_faces;
    std::vector<ContactPointState<dim>> contact_states;
    /** the contact conditions, pointwise or weighted (setup_contact_conditions()) */
    std::unique_ptr<ContactConditions<dim>> conditions;

    double time = 0.;
    /** reference positions of the points in contact at the end of some step on this mesh */
    std::vector<Point<dim>> active_set;
    double                  last_normal_force = 0.;
    bool                    verbose;
    /** The spaces FaceEvaluator reads, views of this problem's members. */
    const ContactSpaces<dim> spaces;
    /** which loops iterate, which are folded into Newton (LoopPolicy) */
    LoopPolicy  loops;
    std::string parameters_used;
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
  };
} // namespace StabilizedLagrangian
