// The load-step controller (source/solver/load_step_controller.cc): nominal
// steps up to the end time, a step halved on each failure down to the
// nominal one halved `Maximum step cuts` times, and doubled back towards the
// nominal one after each converged step.

#include <stabilized_lagrangian/solver/load_step_controller.h>

#include <cstdlib>
#include <iostream>
#include <string>

using namespace StabilizedLagrangian;

namespace
{
  int failures = 0;

  void
  check(const bool ok, const std::string &what)
  {
    failures += !ok;
    std::cout << (ok ? "ok    " : "FAIL  ") << what << std::endl;
  }
} // namespace

int
main()
{
  // End time 1, 4 nominal steps of 0.25, at most 2 cuts (smallest step 0.0625)
  LoadStepController::State state;
  LoadStepController        steps(1., 4, 2, state);
  steps.restart();
  check(state.step == 0 && state.step_size == 0.25 && state.consecutive_cuts == 0,
        "restart: no step taken, the next one nominal");

  double time = 0.;
  check(steps.next_step_size(time) == 0.25, "first step nominal");
  check(steps.cut() && steps.step_size() == 0.125 && steps.consecutive_cuts() == 1,
        "first cut halves the step");
  check(steps.cut() && steps.step_size() == 0.0625 && steps.consecutive_cuts() == 2,
        "second cut halves it again");
  check(!steps.cut() && steps.step_size() == 0.0625 && steps.consecutive_cuts() == 2,
        "no third cut (Maximum step cuts = 2): the step is left as it was");

  time += steps.step_size();
  steps.accept();
  check(steps.step() == 1 && steps.consecutive_cuts() == 0 && steps.step_size() == 0.125,
        "a converged step counts, resets the cuts and doubles the step");
  time += steps.next_step_size(time);
  steps.accept();
  check(steps.step_size() == 0.25, "regrowth up to the nominal step");
  time += steps.next_step_size(time);
  steps.accept();
  check(steps.step_size() == 0.25, "never beyond the nominal step");

  // from t = 0.875 the nominal step would overshoot the end time
  time = 0.875;
  check(steps.next_step_size(time) == 0.125 && state.step_size == 0.125,
        "the last step ends at the end time");
  time += steps.step_size();
  check(!steps.before_end(time) && steps.before_end(0.5), "end time reached");

  LoadStepController::State none;
  LoadStepController        no_cuts(2., 2, 0, none);
  no_cuts.restart();
  check(!no_cuts.cut() && no_cuts.step_size() == 1., "Maximum step cuts = 0: no cut");
  check(no_cuts.nominal_step() == 1. && no_cuts.end_time() == 2. && no_cuts.max_cuts() == 0,
        "nominal step End time / Number of load steps");

  std::cout << (failures ? "FAILED" : "PASSED") << std::endl;
  return failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
