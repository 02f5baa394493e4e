#pragma once

namespace StabilizedLagrangian
{
  /**
   * @brief The size of the load steps along the load path (doc/formulation.md,
   * "Stopping criteria"): the nominal step `End time` / `Number of load steps`;
   * a step that fails is halved and retried, down to the nominal step halved
   * `Maximum step cuts` times; after a converged step the size doubles back
   * towards the nominal one.
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
    };

    /** Each cut divides the step by this factor; a converged step multiplies it back. */
    static constexpr double cut_factor = 2.;

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
     */
    bool
    cut();

    /** After a converged step: count it and grow the step back towards the nominal one. */
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

  private:
    double       end;
    double       nominal;
    unsigned int cuts_allowed;
    /** the nominal step cut `Maximum step cuts` times */
    double smallest;
    State &state;
  };
} // namespace StabilizedLagrangian
