#pragma once

namespace StabilizedLagrangian
{
  /**
   * @brief The size of the load steps along the load path (doc/formulation.md,
   * "Stopping criteria"): the nominal step `End time` / `Number of load steps`;
   * a step that fails is halved and retried, down to the nominal step halved
   * `Maximum step cuts` times.
   *
   * After a cut the step grows back (doubles, up to the nominal step) once
   * `hold` load steps in a row have converged at its size. The hold starts
   * at initial_hold = 1, the rule of MOOSE's ConstantDT with its
   * growth_factor 2 (and of this controller before), which costs nothing
   * where the difficulty passed (a contact that starts); it doubles each
   * time a step fails at the first attempt after it grew (2, 4, 8, ...:
   * Abaqus/Standard grows an increment only after two consecutive
   * increments converged), so a size that keeps failing is tried again less
   * and less often, and goes back to initial_hold once a step of the
   * nominal size converges. Without the back-off a load path whose nominal
   * step fails from some point on paid a failed attempt every other step.
   *
   * The controller works on a State it does not own: the part of the load
   * stepping a checkpoint keeps (source/solver/run_state_list.cc), while the
   * nominal step and the end come from the parameters of the run, which a
   * resume may change (`End time`).
   */
  class LoadStepController
  {
  public:
    /** Where the load stepping stands: what a checkpoint keeps of it. */
    struct State
    {
      unsigned int step             = 0;  ///< converged load steps
      double       step_size        = 0.; ///< of the next attempt
      unsigned int consecutive_cuts = 0;
      /** load steps converged in a row at the size of the next attempt */
      unsigned int steps_at_size = 0;
      /** converged load steps in a row a cut step waits before it doubles */
      unsigned int hold = 0;
    };

    /** Each cut divides the step by this factor; growth multiplies it back. */
    static constexpr double cut_factor = 2.;

    /** The hold after a first cut: the step doubles after one converged step. */
    static constexpr unsigned int initial_hold = 1;

    /** The hold does not double beyond this (a retry every 1024 steps at least). */
    static constexpr unsigned int longest_hold = 1024;

    LoadStepController(const double       end_time,
                       const unsigned int n_steps,
                       const unsigned int max_cuts,
                       State             &state);

    /** Start the load path: no step taken, the next one nominal. */
    void
    restart();

    /** Whether the load path at @p time has not reached the end time yet. */
    bool
    before_end(const double time) const;

    /** The size of the next attempt from @p time: the current size, not beyond the end. */
    double
    next_step_size(const double time);

    /**
     * After a failed attempt: cut the step and return true, or return false
     * when the step is already the smallest allowed (`Maximum step cuts`).
     * A step that fails at the first attempt after it grew doubles the hold.
     */
    bool
    cut();

    /**
     * After a converged step: count it, and double the step (up to the
     * nominal one) once `hold` steps in a row converged at its size.
     */
    void
    accept();

    /** Converged load steps. */
    unsigned int
    step() const
    {
      return state.step;
    }

    /** The size of the next attempt. */
    double
    step_size() const
    {
      return state.step_size;
    }

    /** Cuts since the last converged step. */
    unsigned int
    consecutive_cuts() const
    {
      return state.consecutive_cuts;
    }

    /** Converged load steps in a row a step below the nominal one waits before it doubles. */
    unsigned int
    hold() const
    {
      return state.hold;
    }

    double
    nominal_step() const
    {
      return nominal;
    }

    double
    end_time() const
    {
      return end;
    }

    unsigned int
    max_cuts() const
    {
      return cuts_allowed;
    }

    /** Whether @p state is one the controller can reach (a checkpoint is untrusted input). */
    static bool
    valid(const State &state);

  private:
    double       end;
    double       nominal;
    unsigned int cuts_allowed;
    /** the nominal step cut `Maximum step cuts` times */
    double smallest;
    State &state;

    /** Whether the next attempt is the first at a size the step has just grown to. */
    bool
    just_grown() const;
  };
} // namespace StabilizedLagrangian
