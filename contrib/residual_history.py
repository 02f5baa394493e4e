#!/usr/bin/python3
"""The Newton residual history of a scene's worst load step under the scaled
criterion (the default) and the seed's absolute one (1e-6 N), side by side
(doc/newton_criterion.md).

    contrib/residual_history.py --executable build/stabilized_lagrangian \\
        --scene prm/patin_elastoplastic.prm --output doc/newton_criterion.md

Each run logs every Newton iterate (`Output/Log Newton iterations`); the worst
step is the one with the most Newton iterations under the absolute criterion.
For each inner loop of that step the table lists the residual in N and the
largest scaled block at every iterate, and where each criterion stopped."""
import argparse
import os
import re
import subprocess
import tempfile

CRITERIA = {
    "scaled": "set Residual = scaled\n    set Tolerance = 1e-8",
    "absolute": "set Residual = absolute\n    set Tolerance = 1e-6",
}


def run(executable, scene_text, criterion, directory):
    text = (scene_text + "\nsubsection Nonlinear solver\n  subsection Newton\n    " +
            CRITERIA[criterion] + "\n  end\nend\nsubsection Output\n  set Output directory = " +
            directory + "\n  set Write vtu = false\n  set Log Newton iterations = true\nend\n")
    prm = os.path.join(directory, "input.prm")
    os.makedirs(directory, exist_ok=True)
    with open(prm, "w") as f:
        f.write(text)
    log = subprocess.run([executable, prm], capture_output=True, text=True).stdout
    # split the log into load steps: the iterates logged before each "step N" line
    steps, current = [], []
    for line in log.splitlines():
        m = re.match(r"\s+Newton (\d+): residual (\S+) N; scaled: force (\S+), gap (\S+), slip (\S+)",
                     line)
        if m:
            if int(m.group(1)) == 0:
                current.append([])
            current[-1].append((float(m.group(2)),
                                max(float(m.group(3)), float(m.group(4)), float(m.group(5)))))
        elif re.match(r"step\s+\d+", line):
            steps.append((line.split("  ")[0], current))
            current = []
        elif "step did not converge" in line:
            current = []  # a cut attempt: the accepted attempt follows
    total = re.search(r"Total Newton iterations: (\d+)", log)
    return steps, int(total.group(1)) if total else None


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--executable", required=True)
    parser.add_argument("--scene", required=True)
    parser.add_argument("--output", required=True)
    args = parser.parse_args()
    with open(args.scene) as f:
        scene_text = f.read()
    with tempfile.TemporaryDirectory() as tmp:
        runs = {c: run(os.path.abspath(args.executable), scene_text, c, os.path.join(tmp, c))
                for c in CRITERIA}
    absolute_steps = runs["absolute"][0]
    worst = max(range(len(absolute_steps)),
                key=lambda i: sum(len(loop) - 1 for loop in absolute_steps[i][1]))
    lines = [f"# Newton residual history: {os.path.basename(args.scene)}, load step {worst + 1}",
             "",
             "Written by `contrib/residual_history.py --executable build/stabilized_lagrangian "
             f"--scene {args.scene} --output {args.output}`.",
             "",
             "Total Newton iterations of the run: " +
             ", ".join(f"{c} {runs[c][1]}" for c in CRITERIA) + ".",
             "",
             "Each inner loop (one status iteration) of the worst load step under the absolute "
             "criterion: the residual in N (multiplier rows times r_n, r_t) and the largest "
             "scaled block (doc/formulation.md) at every Newton iterate; **bold**: the iterate "
             "where the criterion stopped. The round-off floor is where the residual stops "
             "falling.",
             ""]
    for criterion in CRITERIA:
        steps = runs[criterion][0]
        if worst >= len(steps):
            continue
        lines += [f"## `Residual = {criterion}`", "",
                  "| inner loop | iterate | residual (N) | scaled |", "|---|---|---|---|"]
        for k, loop in enumerate(steps[worst][1]):
            for i, (residual, scaled) in enumerate(loop):
                mark = "**" if i == len(loop) - 1 else ""
                lines.append(f"| {k + 1} | {i} | {mark}{residual:.3e}{mark} | "
                             f"{mark}{scaled:.3e}{mark} |")
        lines.append("")
    with open(args.output, "w") as f:
        f.write("\n".join(lines))
    print("\n".join(lines[:6]))


if __name__ == "__main__":
    main()
