#!/usr/bin/python3
"""The Newton residual history of a scene's worst load step under the scaled
criterion (the default) and the seed's absolute one (1e-6 N), side by side
(doc/newton_criterion.md).

    contrib/residual_history.py --executable build/stabilized_lagrangian \\
        --scene prm/patin_elastoplastic.prm --doc

Each run logs every Newton iterate (`Output/Log Newton iterations`); the worst
step is the one with the most Newton iterations under the absolute criterion,
those of its failed (cut) attempts included. The two runs may cut different
steps, so the step is matched by pseudo-time: the scaled run shows its steps
(and their failed attempts) that overlap the worst step's time interval. For
each inner loop the table lists the residual in N and the largest scaled block
at every iterate, and where each criterion stopped. The table is written as the
section of newton_criterion.md between its begin/end comments (replaced if the
file has it, appended otherwise, so the file can hold other sections), in the
--output folder (default /tmp/residual_history; or --output FILE.md), or in
doc/ with --doc."""
import argparse
import os
import re
import shlex
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import tool_cli  # noqa: E402
from robustness_map import write_section  # noqa: E402

CRITERIA = {
    "scaled": "set Residual = scaled\n    set Tolerance = 1e-8",
    "absolute": "set Residual = absolute\n    set Tolerance = 1e-6",
}
ITERATE = re.compile(r"\s+Newton (\d+): residual (\S+) N(?:/mm)?; scaled: force (\S+), gap (\S+), slip (\S+)")
STEP = re.compile(r"step\s+(\d+)\s+t =\s+(\S+)")
BEGIN, END = "<!-- begin residual_history -->", "<!-- end residual_history -->"


class Attempt:
    """One attempt at a load step: its inner loops (the iterates of each), accepted or failed."""

    def __init__(self):
        self.loops = []
        self.accepted = False
        self.newton_failed = False  # the attempt ended in a Newton failure (iteration limit, ...)

    def newton_iterations(self):
        return sum(len(loop) - 1 for loop in self.loops)


def run(executable, scene_text, criterion, directory):
    """Run the scene under criterion; ([(step, t_start, t_end, [attempts])], total, failed-attempt total)."""
    text = (scene_text + "\nsubsection Nonlinear solver\n  subsection Newton\n    " +
            CRITERIA[criterion] + "\n  end\nend\nsubsection Output\n  set Output directory = " +
            directory + "\n  set Write vtu = false\n  set Log Newton iterations = true\nend\n")
    prm = os.path.join(directory, "input.prm")
    os.makedirs(directory, exist_ok=True)
    with open(prm, "w") as f:
        f.write(text)
    log = subprocess.run([executable, prm], capture_output=True, text=True).stdout
    with open(os.path.join(directory, "log.txt"), "w") as f:
        f.write(log)
    # split the log into load steps: the attempts logged before each "step N  t = ..." line
    steps, attempts, current = [], [], Attempt()
    t_previous = 0.
    for line in log.splitlines():
        m = ITERATE.match(line)
        if m:
            if int(m.group(1)) == 0:
                current.loops.append([])
            current.loops[-1].append((float(m.group(2)),
                                      max(float(m.group(3)), float(m.group(4)), float(m.group(5)))))
            continue
        m = STEP.match(line)
        if m:
            current.accepted = True
            attempts.append(current)
            t_end = float(m.group(2))
            steps.append((int(m.group(1)), t_previous, t_end, attempts))
            t_previous, attempts, current = t_end, [], Attempt()
        elif line.startswith("  Newton: "):  # a Newton failure, the only "Newton:" messages
            current.newton_failed = True
        elif "step did not converge" in line:
            attempts.append(current)  # a cut attempt: the next attempt starts from the same state
            current = Attempt()
    total = re.search(r"Total Newton iterations: (\d+)", log)
    failed = re.search(r"in failed \(cut\) attempts: (\d+)", log)
    if total is None:
        raise RuntimeError(f"the run with the {criterion} criterion did not finish: "
                           + " / ".join(log.strip().splitlines()[-3:]))
    return steps, int(total.group(1)), int(failed.group(1)) if failed else None


def step_iterations(step):
    return sum(a.newton_iterations() for a in step[3])


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--executable", required=True, type=tool_cli.executable)
    parser.add_argument("--scene", required=True, type=tool_cli.existing_file)
    tool_cli.add_output_arguments(parser, "/tmp/residual_history", ["the section of newton_criterion.md"],
                                  file_suffix=".md")
    args = parser.parse_args()
    tool_cli.check_output(parser, args)
    output = tool_cli.destination(args, "newton_criterion.md")
    command = " ".join(["contrib/residual_history.py"] + [shlex.quote(a) for a in sys.argv[1:]])
    with open(args.scene) as f:
        scene_text = f.read()
    with tempfile.TemporaryDirectory() as tmp:
        runs = {c: run(os.path.abspath(args.executable), scene_text, c, os.path.join(tmp, c))
                for c in CRITERIA}
    worst = max(runs["absolute"][0], key=step_iterations)
    _, t_start, t_end, _ = worst
    lines = [BEGIN, f"## Newton residual history: {os.path.basename(args.scene)}, t = {t_start:g} … {t_end:g}",
             "",
             f"Written by `{command}`.",
             "",
             "Newton iterations of the run (accepted attempts, and in failed (cut) attempts): " +
             ", ".join(f"{c} {runs[c][1]} and {runs[c][2] if runs[c][2] is not None else '?'}"
                       for c in CRITERIA) + ".",
             "",
             f"The load step with the most Newton iterations under the absolute criterion (failed attempts "
             f"included) is step {worst[0]}, from t = {t_start:g} to {t_end:g}; under the scaled criterion, the "
             "steps that overlap that interval. For each attempt at those steps and each of its inner loops "
             "(one status iteration): the residual in N (multiplier rows times r_n, r_t) and the largest scaled "
             "block (doc/formulation.md) at every Newton iterate; **bold**: the iterate where the criterion "
             "stopped (an inner loop whose Newton failed, e.g. at its iteration limit, has none: the "
             "attempt failed and the step was cut). The round-off floor is where the residual stops falling.",
             ""]
    # every load step under both criteria, matched by their time interval
    intervals = sorted({(round(s[1], 12), round(s[2], 12)) for c in CRITERIA for s in runs[c][0]},
                       key=lambda i: (i[1], i[0]))
    lines += ["Newton iterations of every load step (accepted attempt, + those of failed attempts):", "",
              "| t | " + " | ".join(f"`{c}`" for c in CRITERIA) + " |", "|---|" + "---|" * len(CRITERIA)]
    for t0, t1 in intervals:
        cells = []
        for c in CRITERIA:
            match = [s for s in runs[c][0] if (round(s[1], 12), round(s[2], 12)) == (t0, t1)]
            if not match:
                cells.append("–")
                continue
            attempts = match[0][3]
            failed = sum(a.newton_iterations() for a in attempts if not a.accepted)
            cells.append(f"{attempts[-1].newton_iterations()}" + (f" + {failed}" if failed else ""))
        lines.append(f"| {t0:g} … {t1:g} | " + " | ".join(cells) + " |")
    lines.append("")
    for criterion in CRITERIA:
        steps = [s for s in runs[criterion][0] if s[1] < t_end - 1e-12 and s[2] > t_start + 1e-12]
        lines += [f"### `Residual = {criterion}`", ""]
        if not steps:
            lines += ["No step of this run overlaps that interval (the run stopped before it).", ""]
            continue
        summary = []
        for number, t0, t1, attempts in steps:
            failed = sum(a.newton_iterations() for a in attempts if not a.accepted)
            summary.append(f"step {number} (t = {t0:g} … {t1:g}): {attempts[-1].newton_iterations()} Newton "
                           f"iterations" + (f", and {failed} in {len(attempts) - 1} failed attempt(s)"
                                            if len(attempts) > 1 else ""))
        lines += ["; ".join(summary) + ".", "",
                  "| step | attempt | inner loop | iterate | residual (N) | scaled |", "|---|---|---|---|---|---|"]
        for number, _, _, attempts in steps:
            for a, attempt in enumerate(attempts):
                label = f"{a + 1}" + ("" if attempt.accepted else " (failed)")
                for k, loop in enumerate(attempt.loops):
                    for i, (residual, scaled) in enumerate(loop):
                        # every inner loop ends where the criterion stopped it, except one whose
                        # Newton failed (the last one of a failed attempt)
                        stopped = i == len(loop) - 1 and not (attempt.newton_failed and k == len(attempt.loops) - 1)
                        mark = "**" if stopped else ""
                        lines.append(f"| {number} | {label} | {k + 1} | {i} | {mark}{residual:.3e}{mark} | "
                                     f"{mark}{scaled:.3e}{mark} |")
        lines.append("")
    lines.append(END)
    write_section(output, BEGIN, END, "\n".join(lines) + "\n")
    print(f"wrote the section of {output}")
    print("\n".join(lines[1:11]))


if __name__ == "__main__":
    main()
