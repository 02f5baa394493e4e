// The load-step controller (source/solver/load_step_controller.cc): nominal
// steps up to the end time, a step halved on each failure down to the
// nominal one halved `Maximum step cuts` times; a cut step doubles back
// towards the nominal one after `hold` converged steps in a row at its size,
// a hold of 1 that doubles each time the size the step grew to fails at once.

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

  /** Accept @p n steps from @p time; returns the sizes taken, as "a b c". */
  std::string
  accept_steps(LoadStepController &steps, double &time, const unsigned int n)
  {
    std::string sizes;
    for (unsigned int i = 0; i < n; ++i)
      {
        const double h = steps.next_step_size(time);
        sizes += (i ? " " : "") + std::to_string(static_cast<int>(h * 1000. + 0.5));
        time += h;
        steps.accept();
      }
    return sizes;
  }
} // namespace

int
main()
{
  // End time 1, 4 nominal steps of 0.25, at most 2 cuts (smallest step 0.0625)
  LoadStepController::State state;
  LoadStepController        steps(1., 4, 2, state);
  steps.restart();
  check(state.step == 0 && state.step_size == 0.25 && state.consecutive_cuts == 0 &&
            state.hold == LoadStepController::initial_hold,
        "restart: no step taken, the next one nominal, the initial hold");

  double time = 0.;
  check(steps.next_step_size(time) == 0.25, "first step nominal");
  check(steps.cut() && steps.step_size() == 0.125 && steps.consecutive_cuts() == 1,
        "first cut halves the step");
  check(steps.cut() && steps.step_size() == 0.0625 && steps.consecutive_cuts() == 2,
        "second cut halves it again");
  check(!steps.cut() && steps.step_size() == 0.0625 && steps.consecutive_cuts() == 2,
        "no third cut (Maximum step cuts = 2): the step is left as it was");
  check(steps.hold() == 1, "cuts of the first attempt of a step leave the hold");

  time += steps.step_size();
  steps.accept();
  check(steps.step() == 1 && steps.consecutive_cuts() == 0 && steps.step_size() == 0.125,
        "a converged step counts, resets the cuts and doubles the step (hold 1)");
  check(accept_steps(steps, time, 1) == "125" && steps.step_size() == 0.25,
        "regrowth up to the nominal step");
  check(accept_steps(steps, time, 1) == "250" && steps.step_size() == 0.25,
        "never beyond the nominal step");

  // from t = 0.875 the nominal step would overshoot the end time
  time = 0.875;
  check(steps.next_step_size(time) == 0.125 && state.step_size == 0.125,
        "the last step ends at the end time");
  time += steps.step_size();
  check(!steps.before_end(time) && steps.before_end(0.5), "end time reached");

  // The failing size is not retried straight away once it failed again,
  // and ever less often while it keeps failing: End time 100, 50 nominal
  // steps of 2, where every step of 2 fails from t = 10 on and every step of
  // 1 converges. Growing back after each converged step (the rule before)
  // failed every other attempt.
  {
    LoadStepController::State hard;
    LoadStepController        path(100., 50, 5, hard);
    path.restart();
    double       t               = 0.;
    unsigned int failed_attempts = 0, steps_of_one = 0;
    std::string  attempts;
    while (path.before_end(t))
      {
        const double h      = path.next_step_size(t);
        const bool   fails  = t >= 10. - 1e-12 && h > 1.5;
        const bool   record = t >= 10. - 1e-12 && t < 26.;
        if (record)
          attempts += std::string(attempts.empty() ? "" : " ") + (fails ? "2!" : "1");
        if (fails)
          {
            ++failed_attempts;
            check(path.cut(), "a cut at t = " + std::to_string(t));
            continue;
          }
        steps_of_one += h == 1.;
        t += h;
        path.accept();
      }
    check(attempts == "2! 1 2! 1 1 2! 1 1 1 1 2! 1 1 1 1 1 1 1 1 2! 1",
          "from t = 10: the first failure is retried after one step (as before), the failed "
          "retry after 2 steps, the next after 4, then 8 (" +
              attempts + ")");
    // failures at t = 10, 11, 13, 17, 25, 41, 73: 7 in 90 steps of 1
    check(failed_attempts == 7,
          "7 failed attempts over the 90 steps of 1 (" + std::to_string(failed_attempts) +
              "; 90 before)");
    check(path.hold() == 64,
          "the hold doubled at each failed retry (" + std::to_string(path.hold()) + ")");
    check(path.step() == 5 + 90 && steps_of_one == 90, "5 steps of 2, 90 of 1");
  }

  // A retry that converges ends the back-off: the hold is back to 1
  {
    LoadStepController::State easy;
    LoadStepController        path(8., 4, 3, easy);
    path.restart();
    double t = 0.;
    path.next_step_size(t);
    path.cut(); // 2 fails: 1
    check(accept_steps(path, t, 1) == "1000" && path.step_size() == 2.,
          "one step of 1, then the nominal step again");
    path.next_step_size(t);
    path.cut(); // the retry fails: hold 2
    check(path.hold() == 2 && accept_steps(path, t, 1) == "1000" && path.step_size() == 1.,
          "the failed retry: the step is held at 1 for two steps");
    check(accept_steps(path, t, 2) == "1000 2000" && path.hold() == 1,
          "then the nominal step converges: hold 1 again (" + std::to_string(path.hold()) + ")");
    path.next_step_size(t);
    path.cut(); // the nominal step fails after having converged: not a failed retry
    check(path.hold() == 1, "a nominal step that fails after converging leaves the hold");
  }

  // What a checkpoint may hold
  LoadStepController::State damaged = state;
  check(LoadStepController::valid(state), "a reachable state is valid");
  damaged.hold = 0;
  check(!LoadStepController::valid(damaged), "a hold of 0 is not");
  damaged           = state;
  damaged.step_size = -1.;
  check(!LoadStepController::valid(damaged), "a negative step size is not");

  LoadStepController::State none;
  LoadStepController        no_cuts(2., 2, 0, none);
  no_cuts.restart();
  check(!no_cuts.cut() && no_cuts.step_size() == 1., "Maximum step cuts = 0: no cut");
  check(no_cuts.nominal_step() == 1. && no_cuts.end_time() == 2. && no_cuts.max_cuts() == 0,
        "nominal step End time / Number of load steps");

  std::cout << (failures ? "FAILED" : "PASSED") << std::endl;
  return failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
