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
   * @brief Which loops of the nest iterate as fixed points and which are
   * linearised in the generalized Newton (folded into it: their quantity is
   * re-evaluated at every Newton iterate), named once for the whole solver.
   *
   * The methods come from `Nonlinear solver/<loop>/Method`; whether a loop has
   * anything to iterate comes from the scene (a flat obstacle in small strain
   * never moves the pairing; a frictionless or Tresca law never moves the
   * threshold). A fixed point that cycles or does not converge in a step is
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

    std::array<bool, 3> linearised_loops = {{false, false, false}};
    std::array<bool, 3> can_change       = {{true, true, true}};
  };
} // namespace StabilizedLagrangian
