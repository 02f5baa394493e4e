#!/usr/bin/python3
"""The numerical inf-sup test (`--inf-sup N`) separates the stable pairs from
the unstable ones on the patin block (4 x 2 cells refined 4 times, 1 rank):

- Q1/P1, Q2/P1, Q2/P2, Q1/P1 coarse (multipliers no richer than the
  displacement trace):
  β_h stays bounded away from zero — it does not decrease over the last
  refinements and stays above 0.1;
- Q1/P0 (face-wise constant multipliers on the same mesh): the multiplier
  alternating from face to face pairs with the trace only at the ends of Γc,
  so β_h → 0: it decreases at every refinement of the last three, by at
  least 20 % each time;
- Q1/P2 (richer than the trace): B has a kernel, β_h = 0 to round-off
  (below 1e-6 of the stable pairs' values).

`Contact/Check inf-sup` in a run, on Hertz refined by the estimator four
times: Q1/P0 is flagged (a warning, and β_h falling in refinement_cycles.csv),
Q1/P1 and Q2/P2 are not (and their β_h is written to run_summary.csv); on 2
ranks the check is skipped with a note."""
import csv
import os
import subprocess
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
with open(os.path.join(os.path.dirname(__file__), "..", "prm", "patin_elastic.prm")) as f:
    base = f.read().replace("set Global refinements = 4", "set Global refinements = 1")


def betas(pair):
    text = base.replace("set Finite element pair  = Q1/P1", f"set Finite element pair  = {pair}")
    out = f"{workdir}/{pair.replace('/', '').replace(' ', '_')}"
    os.makedirs(out, exist_ok=True)
    with open(out + "/input.prm", "w") as f:
        f.write(text + sltest.QUIET_OUTPUT)
    result = subprocess.run([executable, "--inf-sup", "5", "input.prm"], cwd=out,
                            capture_output=True, text=True)
    check(result.returncode == 0, f"{pair}: --inf-sup exit code {result.returncode}")
    with open(out + "/output/inf_sup.csv") as f:
        return [float(r["beta"]) for r in csv.DictReader(f)]


stable = {}
for pair in ("Q1/P1", "Q2/P1", "Q2/P2", "Q1/P1 coarse"):
    b = betas(pair)
    stable[pair] = b
    check(b[-1] >= b[-2] * 0.99 and min(b[-2:]) > 0.1,
          f"{pair} stable: beta_h = {', '.join(f'{x:.3f}' for x in b)}")
b = betas("Q1/P0")
check(all(b[k + 1] < 0.8 * b[k] for k in range(len(b) - 3, len(b) - 1)),
      f"Q1/P0 unstable, beta_h -> 0: {', '.join(f'{x:.4f}' for x in b)}")
b = betas("Q1/P2")
smallest_stable = min(min(v) for v in stable.values())
check(max(b) < 1e-6 * smallest_stable, f"Q1/P2 unstable, beta_h = 0: max {max(b):.2e}")

# --- Contact/Check inf-sup in a run with refinement cycles --------------------
def checked_run(pair, ranks=1):
    text = sltest.coarse_hertz() + f"""
subsection Contact
  set Finite element pair = {pair}
  set Check inf-sup = true
end
subsection Load stepping
  set Number of load steps = 1
end
subsection Adaptive refinement
  set Cycles = 4
  set Criterion = estimator
end
subsection Output
  set Output directory = output
end
"""
    out = f"{workdir}/check_{pair.replace('/', '')}_np{ranks}"
    code, log = sltest.run(executable, text + sltest.QUIET_OUTPUT, out, ranks=ranks, expect_success=False)
    check(code == 0, f"Check inf-sup, {pair} on {ranks} rank(s): exit code {code}")
    return out + "/output", log


for pair, unstable in (("Q1/P1", False), ("Q2/P2", False), ("Q1/P0", True)):
    output, log = checked_run(pair)
    if not os.path.exists(output + "/refinement_cycles.csv"):
        continue
    cycles = sltest.read_csv(output + "/refinement_cycles.csv")
    b = [row["inf_sup_beta"] for row in cycles]
    summary = sltest.read_csv(output + "/run_summary.csv")[0]
    flagged = "fell under refinement" in log
    check(flagged == unstable and len(b) == 5 and min(b) > 0 and abs(summary["inf_sup_beta"] - b[-1]) <= 1e-5 * b[-1],
          f"Check inf-sup, {pair}: {'flagged' if flagged else 'not flagged'}, beta_h per cycle "
          + ", ".join(f"{x:.3f}" for x in b) + " (also in run_summary.csv)")
output, log = checked_run("Q1/P1", ranks=2)
check("runs on one MPI rank" in log and os.path.exists(output + "/run_summary.csv")
      and "inf_sup_beta" not in open(output + "/run_summary.csv").read(),
      "Check inf-sup on 2 ranks: skipped with a note, no column")
check.finish()
