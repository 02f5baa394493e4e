#pragma once

#include <stabilized_lagrangian/parameters.h>

#include <array>

namespace StabilizedLagrangian
{
  /** The three outer loops of the nest of seed §2.2 (doc/formulation.md, "Nested loops"). */
  enum class Loop : unsigned int
  {
    geometry, ///< pairing, normal and tangents
    friction, ///< friction threshold s = μ λ_n
    status    ///< contact status χ
  };

  /**
   * @brief Which parts of a contact point's state are evaluated afresh at the
   * iterate (ContactProblem::evaluate_point_state): the quantity of each loop.
   */
  struct PointRefresh
  {
    bool pairing   = false; ///< pairing, normal and tangents (geometry loop)
    bool threshold = false; ///< friction threshold (friction loop)
    bool status    = false; ///< contact status (status loop)
  };

  /**
   * @brief Which loops of the nest iterate as fixed points and which are
   * linearised in the generalized Newton (folded into it: their quantity is
   * re-evaluated at every Newton iterate), named once for the whole solver.
   *
   * The methods come from `Nonlinear solver/<loop>/Method`; whether a loop has
   * anything to iterate comes from the scene (a flat obstacle in small strain
   * never moves the pairing; a frictionless or Tresca law never moves the
   * threshold); how the pairing is linearised comes from the contact partner.
   * A fixed point that cycles or does not converge in a step is
   * folded for that step only (fold()).
   */
  class LoopPolicy
  {
  public:
    LoopPolicy() = default;

    explicit LoopPolicy(const Parameters::NonlinearSolver &solver)
        : linearised_loops{{solver.geometry_method == Parameters::LoopMethod::newton,
                            solver.friction_method == Parameters::LoopMethod::newton,
                            solver.status_method == Parameters::LoopMethod::newton}}
    {
    }

    /** Whether @p loop is folded into the generalized Newton. */
    bool
    linearised(const Loop loop) const
    {
      return linearised_loops[index(loop)];
    }

    /** Whether @p loop iterates as a fixed point: its quantity can change, and it is not folded. */
    bool
    iterates(const Loop loop) const
    {
      return can_change[index(loop)] && !linearised(loop);
    }

    /** Whether the scene can change what @p loop iterates on (set at setup). */
    void
    set_can_change(const Loop loop, const bool value)
    {
      can_change[index(loop)] = value;
    }

    bool
    can_change_quantity(const Loop loop) const
    {
      return can_change[index(loop)];
    }

    /**
     * What the contact partner's pairing offers (set at setup): its derivatives
     * with respect to the slave position, and whether they vanish (a plane).
     */
    void
    set_pairing(const bool has_derivatives, const bool flat)
    {
      pairing_derivatives = has_derivatives;
      pairing_flat        = flat;
    }

    /**
     * Whether the folded geometry loop pairs each point anew within the
     * assembly and linearises the pairing there (a rigid obstacle).
     */
    bool
    pairing_linearised() const
    {
      return linearised(Loop::geometry) && pairing_derivatives;
    }

    /** Whether the linearised pairing turns with the slave point (a curved obstacle). */
    bool
    pairing_turns() const
    {
      return pairing_linearised() && !pairing_flat;
    }

    /**
     * Whether the folded geometry loop pairs every point anew before each
     * assembly, frozen within it (a meshed partner, whose pairing is not
     * linearised).
     */
    bool
    pairs_before_assembly() const
    {
      return linearised(Loop::geometry) && !pairing_derivatives;
    }

    /** What the folded loops re-evaluate at every contact point of every Newton iterate. */
    PointRefresh
    at_iterate() const
    {
      PointRefresh what;
      what.pairing   = pairing_linearised();
      what.threshold = linearised(Loop::friction) && can_change_quantity(Loop::friction);
      what.status    = linearised(Loop::status);
      return what;
    }

    /** Fold @p loop into Newton (or restore it with @p value false); returns what it was. */
    bool
    fold(const Loop loop, const bool value = true)
    {
      const bool before             = linearised_loops[index(loop)];
      linearised_loops[index(loop)] = value;
      return before;
    }

  private:
    static unsigned int
    index(const Loop loop)
    {
      return static_cast<unsigned int>(loop);
    }

    std::array<bool, 3> linearised_loops    = {{false, false, false}};
    std::array<bool, 3> can_change          = {{true, true, true}};
    bool                pairing_derivatives = true;
    bool                pairing_flat        = false;
  };
} // namespace StabilizedLagrangian
