#include <stabilized_lagrangian/parameters.h>
#include <stabilized_lagrangian/plugins.h>

/** @file The `Load stepping`, `Nonlinear solver` and `Linear solver` sections. */

namespace StabilizedLagrangian
{
  namespace Parameters
  {
    void
    LoadStepping::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Load stepping");
      prm.declare_entry(
          "End time", "1", Patterns::Double(), "Pseudo-time at the end of the load path, > 0.");
      prm.declare_entry("Number of load steps",
                        "10",
                        Patterns::Integer(1),
                        "Equal load steps up to the end time.");
      prm.declare_entry("Maximum step cuts",
                        "5",
                        Patterns::Integer(0, 30),
                        "A load step that fails is halved and retried, down to the nominal step "
                        "halved this many times; a cut step doubles back towards the nominal one "
                        "after a converged step, and once the step it grew to failed again "
                        "after 2, 4, 8, ... converged steps in a row. A failure at the smallest "
                        "step ends the run (exit code 2).");
      prm.declare_entry("Wall time limit",
                        "0",
                        Patterns::Double(0.),
                        "Seconds of wall time after which the run stops cleanly at the end of "
                        "the load step that passes it (exit code 3), the results of the "
                        "converged steps kept; with `Output/Checkpoint interval` > 0 it writes a "
                        "checkpoint first, so that `--resume` continues the run. After the first "
                        "step the log warns when the load path will not fit. 0: no limit.");
      prm.leave_subsection();
    }

    void
    LoadStepping::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Load stepping");
      end_time        = prm.get_double("End time");
      n_steps         = prm.get_integer("Number of load steps");
      max_cuts        = prm.get_integer("Maximum step cuts");
      wall_time_limit = prm.get_double("Wall time limit");
      if (!(end_time > 0.))
        throw InputError("Load stepping/End time = " + prm.get("End time") +
                         ": the time (s) the load stepping ends at must be > 0.");
      prm.leave_subsection();
    }

    namespace
    {
      /** `Method` of a loop of `Nonlinear solver`: @p what is frozen, or linearised. */
      void
      declare_loop_method(ParameterHandler &prm, const std::string &what)
      {
        prm.declare_entry("Method",
                          "fixed point",
                          Patterns::Selection("fixed point|newton"),
                          "fixed point: " + what +
                              " is frozen in the inner loops and updated between them "
                              "(the seed's nested algorithm); newton: it is evaluated at every "
                              "Newton iterate and linearised in the Jacobian (generalized "
                              "Newton), and this loop runs once per step.");
      }

      /**
       * The subsection @p name of an outer loop that stops on a relative change:
       * its `Method` (what it freezes: @p what), iterations and tolerance.
       */
      void
      declare_outer_loop(ParameterHandler  &prm,
                         const std::string &name,
                         const std::string &what,
                         const std::string &max_iterations,
                         const std::string &tolerance_documentation)
      {
        prm.enter_subsection(name);
        declare_loop_method(prm, what);
        prm.declare_entry("Maximum iterations", max_iterations, Patterns::Integer(1));
        prm.declare_entry("Tolerance", "1e-4", Patterns::Double(0.), tolerance_documentation);
        prm.leave_subsection();
      }

      /** The subsections of `Nonlinear solver`: its loops and Newton (seed §2.2). */
      void
      declare_loop_entries(ParameterHandler &prm)
      {
        declare_outer_loop(prm,
                           "Geometry loop",
                           "the pairing (closest point, normal and tangents)",
                           "10",
                           "Stop when max|u_k − u_{k−1}| / max|u_k| is at most this (seed §3).");
        declare_outer_loop(prm,
                           "Friction loop",
                           "the friction threshold s = μ λ_n",
                           "30",
                           "Stop when max|s_new − s_old| / max|s_new| is at most this (seed §3).");
        prm.enter_subsection("Status loop");
        declare_loop_method(prm, "the contact status χ of every point");
        prm.declare_entry("Maximum iterations",
                          "30",
                          Patterns::Integer(1),
                          "Stops when no contact point changes status (seed §3).");
        prm.leave_subsection();
        prm.enter_subsection("Newton");
        prm.declare_entry("Maximum iterations", "25", Patterns::Integer(1));
        prm.declare_entry("Tolerance",
                          "1e-8",
                          Patterns::Double(0.),
                          "Newton stops when the measure chosen by `Residual` is at most this.");
        prm.declare_entry(
            "Residual",
            "scaled",
            Patterns::Selection("scaled|absolute|relative"),
            "scaled: each block of the residual against its own scale, dimensionless: the "
            "force rows (max norm) against the largest nodal internal or external force, "
            "the contact and friction rows as lengths (a gap, a stick point's slip) against "
            "the largest displacement; independent of r_n, r_t and of the load level, and "
            "far above round-off (doc/formulation.md). absolute: the seed's criterion, the "
            "residual in N (multiplier rows scaled by r_n and r_t; the seed uses Tolerance "
            "= 1e-6), which sits at the round-off floor when forces are large. relative: "
            "that residual against the first one of the Newton loop.");
        prm.declare_entry("Line search steps",
                          "5",
                          Patterns::Integer(0),
                          "Backtracking: the Newton step is halved at most this many times "
                          "while the residual does not decrease (or a material point leaves "
                          "its admissible range); 0 takes every full step.");
        prm.leave_subsection();
      }

      /** The entries of `Linear solver` that only `Method = iterative` reads. */
      void
      declare_iterative_entries(ParameterHandler &prm)
      {
        prm.declare_entry(
            "Forcing term",
            "Newton tolerance",
            Patterns::Selection("Newton tolerance|Eisenstat-Walker"),
            "Method = iterative: the relative GMRES tolerance of each Newton system. Newton "
            "tolerance: a tenth of the reduction of the Newton criterion's measure that would "
            "meet its tolerance in this iteration, so that a Newton loop whose statuses are "
            "frozen (a linear problem) ends in the iterations of the direct solver. "
            "Eisenstat-Walker: choice 2 of Eisenstat and Walker (1996), looser early in a "
            "loop; it costs Newton iterations on these problems (doc/iterative_solver.md). "
            "Both within [1e-10, Maximum forcing term].");
        prm.declare_entry(
            "Maximum forcing term",
            "1e-3",
            Patterns::Double(1e-14, 0.5),
            "Method = iterative: the largest relative GMRES tolerance |b - J x| / |b|.");
        prm.declare_entry(
            "Schur augmentation",
            "10",
            Patterns::Double(0., 1e6),
            "Method = iterative: c in the augmented preconditioner. The multiplier rows that "
            "only constrain the displacement, each on its own (no entry in D, no displacement DoF "
            "shared with another row: a nodal contact quadrature against a rigid obstacle) are "
            "added to the displacement rows, weighted by Gamma = c diag(C diag(K)^-1 C^T)^-1, so "
            "the "
            "multigrid "
            "works on K + C^T Gamma C (a penalty stiffness of c times the node's diagonal) and the "
            "Schur complement with diag(K + C^T Gamma C) is within a factor (1 + c) / c of the "
            "exact one whatever the mesh (doc/formulation.md, \"Iterative linear solver\"). "
            "0: no augmentation (K, and D - C diag(K)^-1 B, off by a factor that grows under "
            "refinement).");
        prm.declare_entry(
            "AMG near-null space",
            "translations",
            Patterns::Selection("translations|rigid body modes"),
            "Method = iterative: the modes the algebraic multigrid keeps on its coarse levels. "
            "rigid body modes adds the rotations: fewer GMRES iterations (3D Hertz ball at 176k "
            "DoFs: 22 instead of 30 per solve), a set-up twice as dear, about 1.2 times the "
            "time per Newton iteration on one rank (doc/iterative_solver.md). In an "
            "axisymmetric model the translations only.");
        prm.declare_entry("Maximum iterations",
                          "300",
                          Patterns::Integer(1, 100000),
                          "Method = iterative: GMRES iterations per Newton system.");
      }
    } // namespace

    void
    NonlinearSolver::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Nonlinear solver");
      prm.declare_entry("Maximum Newton iterations per load step",
                        "2000",
                        Patterns::Integer(1),
                        "Budget of Newton iterations over all the loops of one load step: "
                        "a step that needs more fails (and is cut), so cycling fixed points end "
                        "quickly.");
      prm.declare_entry("Stopping",
                        "fixed",
                        Patterns::Selection("fixed|adaptive"),
                        "fixed: each loop stops at its own criterion (Newton at its "
                        "`Tolerance`, the friction and geometry loops at theirs, the status "
                        "loop when no status changes). adaptive: each also stops as soon as its "
                        "error is below `Adaptive stopping fraction` of the discretisation error "
                        "estimated at the iterate (after Ern and Vohralik's adaptive inexact "
                        "Newton methods): the energy norm of its last change (Newton's update, "
                        "an outer loop's change of the displacement) against the residual "
                        "error estimate, and its own relative measure (Newton's scaled "
                        "residual, the friction threshold's and the displacement's relative "
                        "changes) against the estimate relative to the solution's energy norm "
                        "(doc/formulation.md, \"Adaptive stopping\"). An iteration that cannot "
                        "change the answer beyond the mesh's own error is not made.");
      prm.declare_entry("Adaptive stopping fraction",
                        "0.02",
                        Patterns::Double(0., 1.),
                        "Stopping = adaptive: the fraction γ of the estimated discretisation "
                        "error that a loop's error must be below. The residual estimate "
                        "overestimates the error by 3-7 (doc/error_estimator.md), so 0.02 keeps "
                        "the loops' error near a tenth of the true discretisation error.");
      prm.declare_entry(
          "Predictor",
          "tangent",
          Patterns::Selection("tangent|extrapolation"),
          "Where each load step's iterations start. tangent: at the last converged state, "
          "the first Newton iteration linearised about it with the step's Dirichlet "
          "increment (the seed's start). extrapolation: at the last converged state plus "
          "the last load step's change of every unknown (displacement, contact pressure, "
          "friction multiplier) scaled to this step's size, so that a steady motion (a "
          "die sliding, a load growing linearly) starts near its answer and with its "
          "contact statuses; the Dirichlet values left over, if any, are then taken by the "
          "tangent step. The first step of a load path, and the first after a mesh change, "
          "start as with tangent (doc/formulation.md, \"Predictor\").");
      declare_loop_entries(prm);
      prm.leave_subsection();
    }

    void
    NonlinearSolver::parse_parameters(ParameterHandler &prm)
    {
      const auto method = [&prm]() {
        return prm.get("Method") == "newton" ? LoopMethod::newton : LoopMethod::fixed_point;
      };
      prm.enter_subsection("Nonlinear solver");
      max_newton_per_step = prm.get_integer("Maximum Newton iterations per load step");
      adaptive_stopping   = prm.get("Stopping") == "adaptive";
      adaptive_fraction   = prm.get_double("Adaptive stopping fraction");
      extrapolate         = prm.get("Predictor") == "extrapolation";
      prm.enter_subsection("Geometry loop");
      geometry_method         = method();
      geometry_max_iterations = prm.get_integer("Maximum iterations");
      geometry_tolerance      = prm.get_double("Tolerance");
      prm.leave_subsection();
      prm.enter_subsection("Friction loop");
      friction_method         = method();
      friction_max_iterations = prm.get_integer("Maximum iterations");
      friction_tolerance      = prm.get_double("Tolerance");
      prm.leave_subsection();
      prm.enter_subsection("Status loop");
      status_method         = method();
      status_max_iterations = prm.get_integer("Maximum iterations");
      prm.leave_subsection();
      prm.enter_subsection("Newton");
      newton_max_iterations       = prm.get_integer("Maximum iterations");
      newton_tolerance            = prm.get_double("Tolerance");
      line_search_steps           = prm.get_integer("Line search steps");
      const std::string criterion = prm.get("Residual");
      newton_criterion            = criterion == "scaled"     ? ResidualCriterion::scaled
                                    : criterion == "absolute" ? ResidualCriterion::absolute
                                                              : ResidualCriterion::relative;
      prm.leave_subsection();
      prm.leave_subsection();
    }

    void
    LinearSolver::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Linear solver");
      prm.declare_entry(
          "Method",
          "automatic",
          Patterns::Selection("direct|iterative|automatic"),
          "automatic: iterative in 3D from `Automatic threshold` unknowns on, direct below it "
          "and in 2D (decided on each mesh). "
          "direct: one sparse factorisation per Newton system (`Direct solver`). iterative: "
          "GMRES with a block-triangular preconditioner, algebraic multigrid (Trilinos ML) on "
          "the displacement block and the Schur complement with the displacement block's "
          "diagonal on the multipliers (doc/formulation.md, \"Iterative linear solver\"); its "
          "tolerance follows the Newton residual (`Forcing term`), and a system it does not "
          "solve within `Maximum iterations` is solved by the direct solver instead.");
      prm.declare_entry("Automatic threshold",
                        "20000",
                        Patterns::Integer(1),
                        "Method = automatic: the unknowns (displacement and multipliers) of a 3D "
                        "mesh from which the iterative solver is used. Measured on the 3D Hertz "
                        "ball (doc/iterative_solver.md): 2.1 times faster per Newton iteration "
                        "than the direct solver at 26k DoFs, 12 times at 176k; below, both take "
                        "well under a second and the direct solver's exact solves are kept.");
      declare_iterative_entries(prm);
      prm.declare_entry("Direct solver",
                        "Amesos_Mumps",
                        Patterns::Selection("Amesos_Klu|Amesos_Mumps|Amesos_Superludist"),
                        "Trilinos Amesos sparse direct solver for each Newton system. "
                        "MUMPS is 2x (2D) to 8x (3D) faster than KLU on these saddle-point "
                        "systems (doc/benchmark_patin.md).");
      prm.declare_entry("Null pivot detection",
                        "false",
                        Patterns::Bool(),
                        "MUMPS only: detect null pivots and return one solution of a singular "
                        "system instead of failing. Pairs that violate the inf-sup condition "
                        "(Q1/P2) make the Newton system singular wherever contact is active; "
                        "with this their (non-unique) multipliers can be looked at.");
      prm.declare_entry("Work space increase",
                        "20",
                        Patterns::Integer(0, 100000),
                        "MUMPS only: percent added to the work space MUMPS estimates at the "
                        "analysis (its ICNTL(14)). Pivoting on the saddle-point systems can need "
                        "more than estimated: where the factorisation says the space is too small "
                        "(INFOG(1) = -8, -9, -11, -14, -15, -17, -20), it is redone with this "
                        "margin quadrupled, up to three times, before the run stops.");
      prm.declare_entry("Threads per rank",
                        "1",
                        Patterns::Integer(1, 256),
                        "BLAS and OpenMP threads of each MPI rank (the direct solver's dense "
                        "kernels). The program sets them itself, whatever OPENBLAS_NUM_THREADS "
                        "or OMP_NUM_THREADS say, so a run does not depend on the environment; "
                        "the command-line option --threads N overrides this entry. At most the "
                        "processors each rank has and as many as the address space left under "
                        "its limit (ulimit -v) holds OpenBLAS's 128 MiB thread buffers for are "
                        "used, with a note when fewer. Different "
                        "thread counts round differently: loop counts stay the same with the "
                        "scaled Newton criterion, values agree to round-off.");
      prm.leave_subsection();
    }

    void
    LinearSolver::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Linear solver");
      iterative            = prm.get("Method") == "iterative";
      automatic            = prm.get("Method") == "automatic";
      automatic_threshold  = prm.get_integer("Automatic threshold");
      eisenstat_walker     = prm.get("Forcing term") == "Eisenstat-Walker";
      maximum_forcing_term = prm.get_double("Maximum forcing term");
      maximum_iterations   = prm.get_integer("Maximum iterations");
      schur_augmentation   = prm.get_double("Schur augmentation");
      rigid_body_modes     = prm.get("AMG near-null space") == "rigid body modes";
      direct_solver        = prm.get("Direct solver");
      null_pivot_detection = prm.get_bool("Null pivot detection");
      threads_per_rank     = prm.get_integer("Threads per rank");
      workspace_increase   = prm.get_integer("Work space increase");
      if (null_pivot_detection && direct_solver != "Amesos_Mumps")
        throw InputError("Linear solver/Null pivot detection = true needs Direct solver = "
                         "Amesos_Mumps, got " +
                         direct_solver + ".");
      prm.leave_subsection();
    }

  } // namespace Parameters
} // namespace StabilizedLagrangian
