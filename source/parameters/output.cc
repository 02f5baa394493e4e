#include <stabilized_lagrangian/parameters.h>
#include <stabilized_lagrangian/plugins.h>

/** @file The `Output` and `Adaptive refinement` sections. */

namespace StabilizedLagrangian
{
  namespace Parameters
  {
    void
    Output::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Output");
      prm.declare_entry(
          "Output directory", "output", Patterns::FileName(Patterns::FileName::output));
      prm.declare_entry(
          "Write vtu", "true", Patterns::Bool(), "Write .pvd/.vtu/.pvtu per load step.");
      prm.declare_entry("Write profiles",
                        "true",
                        Patterns::Bool(),
                        "Write a contact-surface profile .csv per load step.");
      prm.declare_entry("Checkpoint interval",
                        "0",
                        Patterns::Integer(0),
                        "Load steps between checkpoints (0: none). A checkpoint (directory "
                        "`checkpoint` in the output directory, replaced atomically) holds the "
                        "mesh with its refinements, the solution, the multipliers, the contact "
                        "points' states, the material history, the step controller and the "
                        "statistics; `stabilized_lagrangian --resume input.prm` continues from "
                        "it on the same number of MPI ranks. Between a resume and its "
                        "checkpoint only `Load stepping/End time` and `Wall time limit`, the "
                        "`Output` entries other than the directory and `Linear solver/Threads per "
                        "rank` may change.");
      prm.declare_entry("Log Newton iterations",
                        "false",
                        Patterns::Bool(),
                        "Print every Newton iterate's residual, the line search's step "
                        "lengths and the open/stick/slip counts of each trial: to see where "
                        "an algorithm spends its iterations.");
      prm.leave_subsection();
    }

    void
    AdaptiveRefinement::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Adaptive refinement");
      prm.declare_entry(
          "Cycles",
          "0",
          Patterns::Integer(0, 60),
          "Adaptive refinement: after the whole load path is solved, the mesh "
          "is refined by the `Criterion` and the load path is solved again from "
          "rest on the new mesh, this many times. The last mesh writes into the output "
          "directory, the earlier ones into cycle-N/ below it, and "
          "refinement_cycles.csv sums them up.");
      prm.declare_entry("Criterion",
                        "active set",
                        Patterns::Selection("active set|Kelly|estimator|uniform"),
                        "active set: refine the cells near the points in contact (below); "
                        "Kelly: refine the `Refined fraction` of the cells with the largest "
                        "Kelly indicators (jumps of the displacement gradient across faces), "
                        "which also follows the stresses below the contact zone; estimator: "
                        "the `Refined fraction` with the largest residual error indicators "
                        "eta_K of the last load step (the field error_indicator, with the "
                        "contact terms; doc/formulation.md, \"Error estimate\"); uniform: "
                        "every cell (nested meshes, for convergence studies).");
      prm.declare_entry("Refined fraction",
                        "0.3",
                        Patterns::Double(0., 1.),
                        "Kelly, estimator: with `Marking = fixed number`, the fraction of the "
                        "cells refined at each cycle; with `bulk`, the fraction of the sum of "
                        "the squared indicators that the refined cells carry.");
      prm.declare_entry("Marking",
                        "fixed number",
                        Patterns::Selection("fixed number|bulk"),
                        "Kelly, estimator: which cells the indicators refine. fixed number: "
                        "the `Refined fraction` of the cells with the largest indicators; "
                        "bulk: the fewest cells whose squared indicators make up the `Refined "
                        "fraction` of their sum (Doerfler marking, which the convergence of "
                        "adaptive finite elements rests on; it refines only where the error "
                        "concentrates, with smaller steps and more cycles: "
                        "doc/error_estimator.md).");
      prm.declare_entry("Errors against the last cycle",
                        "false",
                        Patterns::Bool(),
                        "Carry every cycle's displacement through the refinements (exactly: "
                        "the meshes are nested) and measure it against the last cycle's in "
                        "the energy norm of the last state's tangent; cycle_errors.csv gives "
                        "it beside the error estimate of that cycle and their ratio (the "
                        "effectivity index against this reference). Not with --resume.");
      prm.declare_entry("Target error",
                        "0",
                        Patterns::Double(0., 1.),
                        "Accuracy target: the cycles stop as soon as the estimated relative "
                        "error of the last load step in the energy norm "
                        "(estimated_relative_error) is at most this; `Cycles` is then the most "
                        "cycles. The output directory holds the cycle that met it (the earlier "
                        "ones in cycle-N/), target_error.csv what it cost. 0: no target.");
      prm.declare_entry("Target pressure error",
                        "0",
                        Patterns::Double(0., 1.),
                        "Accuracy target on the contact pressure: the estimated relative L2 "
                        "error of the pressure on the contact surface (estimated_pressure_error: "
                        "the mismatch between the multiplier and the pressure recovered from "
                        "the stress and, where the contact zone ends, from a square-root onset; "
                        "doc/formulation.md, \"Error estimate\"), as `Target error`; with "
                        "both, both must be met. 0: no target.");
      prm.declare_entry("Refinement band",
                        "0.5",
                        Patterns::Double(0.),
                        "active set: cells closer to a point in contact than this fraction of "
                        "the active zone's size (the diameter of its bounding box), plus half "
                        "their own diameter, are refined.");
      prm.leave_subsection();
    }

    void
    AdaptiveRefinement::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Adaptive refinement");
      cycles                                          = prm.get_integer("Cycles");
      const std::map<std::string, Criterion> criteria = {{"active set", Criterion::active_set},
                                                         {"Kelly", Criterion::kelly},
                                                         {"estimator", Criterion::estimator},
                                                         {"uniform", Criterion::uniform}};
      criterion                                       = criteria.at(prm.get("Criterion"));
      errors_against_last_cycle = prm.get_bool("Errors against the last cycle");
      target_error              = prm.get_double("Target error");
      target_pressure_error     = prm.get_double("Target pressure error");
      band                      = prm.get_double("Refinement band");
      fraction                  = prm.get_double("Refined fraction");
      bulk_marking              = prm.get("Marking") == "bulk";
      prm.leave_subsection();
      if (targeted() && cycles == 0)
        throw InputError("Adaptive refinement/Target error and Target pressure error need "
                         "`Cycles` > 0: the most refinement cycles the target may take.");
    }

    void
    Output::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Output");
      directory           = prm.get("Output directory");
      write_vtu           = prm.get_bool("Write vtu");
      write_profiles      = prm.get_bool("Write profiles");
      log_newton          = prm.get_bool("Log Newton iterations");
      checkpoint_interval = prm.get_integer("Checkpoint interval");
      prm.leave_subsection();
    }

  } // namespace Parameters
} // namespace StabilizedLagrangian
