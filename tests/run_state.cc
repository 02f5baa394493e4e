// The run's state, listed once (RunState, issue 44): a field added from
// outside source/, through the list only, is restored by a step cut and by a
// resume from a checkpoint.
//
// The field counts the attempts of load steps (ContactProblem::load_step_attempt).
// A failed attempt is undone by the step cut, so the count seen at the start of
// an attempt is the number of steps accepted before it: after a cut it equals
// the count before the failed attempt, and a run resumed from a checkpoint
// starts from the count of the checkpoint's step. The scene, the elastic patin
// on a coarse mesh with a small Newton budget per step, needs cuts; the first
// run stops at a wall-time limit below its first step's time (a checkpoint is
// written there), the second resumes it.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <stabilized_lagrangian/parameters.h>
#include <stabilized_lagrangian/solver/contact_problem.h>

#include "check_tools.h"

#include <filesystem>
#include <map>
#include <string>
#include <vector>

using namespace dealii;
using namespace StabilizedLagrangian;

namespace
{
  const std::string directory = "run_state_output";

  /**
   * The elastic patin (prm/patin_elastic.prm) on a coarse mesh in 4 steps,
   * with a Newton budget that the third step (8 iterations) exceeds: it is cut.
   */
  std::string
  scene(const double wall_time_limit)
  {
    return CheckTools::coarse_patin(SL_PRM_DIR) + R"(
subsection Nonlinear solver
  set Maximum Newton iterations per load step = 7
end
subsection Load stepping
  set Number of load steps = 4
  set Maximum step cuts    = 8
  set Wall time limit      = )" +
           std::to_string(wall_time_limit) + R"(
end
subsection Output
  set Output directory    = )" +
           directory + R"(
  set Write vtu           = false
  set Write profiles      = false
  set Checkpoint interval = 1000
end
)";
  }

  /** The attempts of one run: the start of each and the count it began with. */
  struct Attempts
  {
    unsigned int                             count = 0; ///< the field added to the run's state
    std::vector<std::pair<double, unsigned>> seen;
  };

  /**
   * Run the scene (resumed from the checkpoint with @p resume), the attempt
   * counter added to its state through RunState only; returns whether the
   * run ended (true) or stopped at the wall-time limit.
   */
  bool
  run(const double wall_time_limit, const bool resume, Attempts &attempts)
  {
    ParameterHandler prm;
    Parameters::declare_all<2>(prm);
    const auto        sections = Parameters::parse<2>(prm, scene(wall_time_limit), false);
    ContactProblem<2> problem(prm, sections, false);
    problem.run_state().add(
        "attempt counter",
        RunState::Scope::step_cut_and_checkpoint,
        [&](StateWriter &out) { out.put(attempts.count); },
        [&](StateReader &in) -> std::function<void()> {
          unsigned int count = 0;
          in.get(count);
          return [&attempts, count]() { attempts.count = count; };
        });
    problem.load_step_attempt.connect([&](const double start, const double) {
      attempts.seen.emplace_back(start, attempts.count);
      ++attempts.count;
    });
    return problem.run(resume);
  }

  /** The checks of one run's attempts; @p first_count the count its first attempt must see. */
  void
  check_attempts(const Attempts &attempts, const unsigned int first_count, const std::string &run)
  {
    CheckTools::check(!attempts.seen.empty() && attempts.seen.front().second == first_count,
                      run + ": the first attempt begins with the count " +
                          std::to_string(first_count),
                      attempts.seen.empty() ? -1. : attempts.seen.front().second);
    // each start time: the count at its first attempt, which a cut must give back
    std::map<double, unsigned int> at_start;
    unsigned int                   retries = 0, wrong = 0;
    for (const auto &[start, count] : attempts.seen)
      {
        const auto [known, first] = at_start.emplace(start, count);
        retries += !first;
        wrong += !first && known->second != count;
      }
    CheckTools::check(wrong == 0,
                      run + ": after each of its " + std::to_string(retries) +
                          " step cuts, the count is that before the failed attempt (wrong)",
                      wrong);
    CheckTools::check(attempts.count == first_count + at_start.size(),
                      run + ": the count at the end is that of the accepted steps, " +
                          std::to_string(first_count + at_start.size()),
                      attempts.count);
  }
} // namespace

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  std::filesystem::remove_all(directory);

  Attempts   stopped;
  const bool ended = run(1e-6, false, stopped);
  CheckTools::check(!ended, "the first run stops at the wall-time limit", stopped.count);
  check_attempts(stopped, 0, "stopped run");

  Attempts   resumed;
  const bool completed = run(0., true, resumed);
  CheckTools::check(completed, "the resumed run ends", resumed.count);
  check_attempts(resumed, stopped.count, "resumed run");

  unsigned int retries = 0;
  for (const Attempts *attempts : {&stopped, &resumed})
    for (unsigned int k = 1; k < attempts->seen.size(); ++k)
      retries += attempts->seen[k].first == attempts->seen[k - 1].first;
  CheckTools::check(retries > 0, "the scene has step cuts", retries);
  return CheckTools::summary();
}
