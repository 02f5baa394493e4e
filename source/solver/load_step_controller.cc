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
    state = State{0, nominal, 0};
  }

  bool
  LoadStepController::before_end(const double time) const
  {
    return time < end * (1. - 1e-12);
  }

  double
  LoadStepController::next_step_size(const double time)
  {
    state.step_size = std::min(state.step_size, end - time);
    return state.step_size;
  }

  bool
  LoadStepController::cut()
  {
    // a run cannot crawl on with ever smaller steps
    if (state.step_size <= smallest * (1. + 1e-12))
      return false;
    ++state.consecutive_cuts;
    state.step_size /= cut_factor;
    return true;
  }

  void
  LoadStepController::accept()
  {
    ++state.step;
    state.consecutive_cuts = 0;
    state.step_size        = std::min(cut_factor * state.step_size, nominal);
  }
} // namespace StabilizedLagrangian
