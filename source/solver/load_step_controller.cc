#include <stabilized_lagrangian/solver/load_step_controller.h>

#include <algorithm>
#include <cmath>

namespace StabilizedLagrangian
{
  LoadStepController::LoadStepController(const double       end_time,
                                         const unsigned int n_steps,
                                         const unsigned int max_cuts,
                                         State             &state)
      : end(end_time)
      , nominal(end_time / n_steps)
      , cuts_allowed(max_cuts)
      , smallest(nominal / std::pow(cut_factor, max_cuts))
      , state(state)
  {
  }

  void
  LoadStepController::restart()
  {
    state = State{0, nominal, 0, 0, initial_hold};
  }

  bool
  LoadStepController::before_end(const double time) const
  {
    return time < end * (1. - 1e-12);
  }

  double
  LoadStepController::next_step_size(const double time)
  {
    // (a resume may have shortened the nominal step: `End time`)
    state.step_size = std::min({state.step_size, nominal, end - time});
    return state.step_size;
  }

  bool
  LoadStepController::just_grown() const
  {
    // a step that grows starts again from no converged step at its size;
    // after a cut that count is zero too, but then the cuts are counted
    return state.step > 0 && state.consecutive_cuts == 0 && state.steps_at_size == 0;
  }

  bool
  LoadStepController::cut()
  {
    // a run cannot crawl on with ever smaller steps
    if (state.step_size <= smallest * (1. + 1e-12))
      return false;
    // the size the step grew to failed again: try it less often
    if (just_grown())
      state.hold = std::min(2 * state.hold, longest_hold);
    ++state.consecutive_cuts;
    state.steps_at_size = 0;
    state.step_size /= cut_factor;
    return true;
  }

  void
  LoadStepController::accept()
  {
    ++state.step;
    state.consecutive_cuts = 0;
    ++state.steps_at_size;
    if (state.step_size >= nominal * (1. - 1e-12))
      state.hold = initial_hold;
    else if (state.steps_at_size >= state.hold)
      {
        state.step_size     = std::min(cut_factor * state.step_size, nominal);
        state.steps_at_size = 0;
      }
  }

  bool
  LoadStepController::valid(const State &state)
  {
    return std::isfinite(state.step_size) && state.step_size > 0. && state.hold >= initial_hold &&
           state.hold <= longest_hold;
  }
} // namespace StabilizedLagrangian
