#!/usr/bin/python3
"""Mean Newton iterations per load step before and after the scaled Newton
stopping criterion (doc/newton_criterion.md).

    contrib/criterion_comparison.py --old-executable OLD --new-executable NEW --doc

Runs prm/patin_elastic.prm, prm/patin_neo_hookean.prm, prm/patin_elastoplastic.prm
and prm/hertz_cylinder.prm as shipped, each with the nested loops (the default)
and with the generalized Newton (`Method = newton` in the Geometry, Friction and
Status loop subsections of `Nonlinear solver`), with
- OLD: a binary from before the change (its default criterion: the absolute
  residual, Tolerance 1e-6 N), nothing set;
- NEW: the binary with the scaled criterion, nothing set (default: scaled, 1e-8);
- NEW with `Nonlinear solver/Newton/Residual = absolute`, `Tolerance = 1e-6`:
  the old criterion in the new binary, which separates the criterion's effect
  from the other changes (the J2 yield test away from round-off).
Writes the table of mean Newton iterations per load step (run_summary.csv
mean_newton_iterations_per_step), load steps and, where the binary reports
them, the Newton iterations of failed (cut) attempts, as the section
"Mean Newton iterations per load step, before and after" of newton_criterion.md
in the --output folder (default: the work directory; or --output FILE.md), or of
doc/newton_criterion.md with --doc: replaced if the file has it (between its
begin/end comments), appended otherwise. Each run is in
WORKDIR/<scene>/<algorithm>/<binary> with its input.prm and log.txt."""
import argparse
import os
import shlex
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import run_output  # noqa: E402
import tool_cli  # noqa: E402
from robustness_map import GENERALIZED_NEWTON, nested_set, write_section  # noqa: E402

root = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
SCENES = [("patin_elastic", "elastic patin"), ("patin_neo_hookean", "neo-Hookean patin"),
          ("patin_elastoplastic", "J2 patin"), ("hertz_cylinder", "Hertz cylinder")]
ALGORITHMS = [("nested", "nested loops", ""), ("newton", "generalized Newton", GENERALIZED_NEWTON)]
ABSOLUTE = (nested_set("Nonlinear solver/Newton/Residual", "absolute")
            + nested_set("Nonlinear solver/Newton/Tolerance", "1e-6"))
OUTPUT = "\nsubsection Output\n  set Output directory = output\n  set Write vtu = false\n  set Write profiles = false\nend\n"
BEGIN, END = "<!-- begin criterion_comparison -->", "<!-- end criterion_comparison -->"


def run(executable, text, workdir):
    """Run text in workdir; the run_summary.csv row, or None with the log's last line."""
    os.makedirs(workdir, exist_ok=True)
    with open(os.path.join(workdir, "input.prm"), "w") as f:
        f.write(text)
    summary_path = os.path.join(workdir, "output", "run_summary.csv")
    if os.path.exists(summary_path):
        os.remove(summary_path)
    # one BLAS thread (the old binary takes it from the environment, the new one sets it itself)
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    with open(os.path.join(workdir, "log.txt"), "w") as log:
        code = subprocess.run([executable, "input.prm"], cwd=workdir, stdout=log, stderr=subprocess.STDOUT,
                              env=env).returncode
    if code != 0 or not os.path.exists(summary_path):
        with open(os.path.join(workdir, "log.txt")) as f:
            tail = [line.strip() for line in f if line.strip()][-1:]
        return None, f"exit code {code}: {tail[0] if tail else ''}"
    return run_output.read_rows(summary_path, str)[0], None


def cell(summary, error):
    if summary is None:
        return f"failed ({error})"
    return f"{float(summary['mean_newton_iterations_per_step']):.2f}"


def failed_cell(summary):
    if summary is None or "failed_attempt_newton_iterations" not in summary:
        return "–"
    return summary["failed_attempt_newton_iterations"]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--old-executable", required=True, type=tool_cli.executable,
                        help="binary of the absolute criterion (before)")
    parser.add_argument("--new-executable", required=True, type=tool_cli.executable,
                        help="binary of the scaled criterion (after)")
    tool_cli.add_output_arguments(parser, None, ["the section of newton_criterion.md"], file_suffix=".md")
    parser.add_argument("--workdir", default="/tmp/criterion_comparison", help="default: %(default)s")
    args = parser.parse_args()
    args.output = args.output or args.workdir
    tool_cli.check_output(parser, args)
    output = tool_cli.destination(args, "newton_criterion.md")
    binaries = [("old", os.path.abspath(args.old_executable), ""),
                ("new", os.path.abspath(args.new_executable), ""),
                ("new_absolute", os.path.abspath(args.new_executable), ABSOLUTE)]
    command = " ".join(["contrib/criterion_comparison.py"] + [shlex.quote(a) for a in sys.argv[1:]])

    rows = []
    for scene, title in SCENES:
        with open(os.path.join(root, "prm", scene + ".prm")) as f:
            base = f.read()
        for algorithm, algorithm_title, algorithm_text in ALGORITHMS:
            results = {}
            for name, executable, extra in binaries:
                results[name] = run(executable, base + algorithm_text + extra + OUTPUT,
                                    os.path.join(args.workdir, scene, algorithm, name))
            old, new, new_abs = (results[n][0] for n in ("old", "new", "new_absolute"))

            def steps(summary):
                return summary["load_steps"] if summary else "–"

            rows.append(f"| {title} | {algorithm_title} | {cell(*results['old'])} | {steps(old)} "
                        f"| {cell(*results['new'])} | {steps(new)} | {failed_cell(new)} "
                        f"| {cell(*results['new_absolute'])} | {steps(new_abs)} | {failed_cell(new_abs)} |")
            print(rows[-1], flush=True)

    section = [BEGIN, "## Mean Newton iterations per load step, before and after", "",
               f"Written by `{command}`.", "",
               "Each scene of `prm/` as shipped (its load steps, step cuts, automatic r_n and r_t), with the "
               "nested loops (the default) and with the generalized Newton (`Method = newton` in "
               "`Nonlinear solver/Geometry loop`, `Friction loop` and `Status loop`), 1 MPI rank, "
               "OPENBLAS_NUM_THREADS=1. *Before*: the binary of commit c9589cb "
               f"(`{args.old_executable}`), whose default criterion is `Residual = absolute`, "
               f"`Tolerance = 1e-6` (N). *After*: the binary of commit 0bd9ea7 (`{args.new_executable}`), "
               "default `Residual = scaled`, `Tolerance = 1e-8`. The last three columns run the new binary with "
               "the old criterion (`set Residual = absolute`, `set Tolerance = 1e-6` in "
               "`Nonlinear solver/Newton`): they separate the criterion's effect from the other changes of the "
               "commit (the J2 yield test away from round-off). *Mean*: `mean_newton_iterations_per_step` of "
               "run_summary.csv, the Newton iterations of the accepted attempts over the load steps done; "
               "*failed*: `failed_attempt_newton_iterations`, those of the attempts that failed and were cut "
               "(the old binary does not count them; a step count above the scene's nominal one, 10 for the "
               "patins and 2 for Hertz, means cut steps).", "",
               "Every run is `EXECUTABLE input.prm` in its directory, input.prm being the scene file with, "
               "appended, the `Method = newton` subsections (generalized Newton), the criterion (last three "
               "columns) and `subsection Output / set Output directory = output / set Write vtu = false / "
               "set Write profiles = false`; the directories are under "
               f"`{args.workdir}/<scene>/<nested|newton>/<old|new|new_absolute>`.", "",
               "| scene | algorithm | before: mean / step | before: steps | after: mean / step | after: steps "
               "| after: failed | new binary, absolute 1e-6: mean / step | steps | failed |",
               "|---|---|---|---|---|---|---|---|---|---|"] + rows + ["", END]
    write_section(output, BEGIN, END, "\n".join(section) + "\n")
    print(f"wrote the section of {output}")


if __name__ == "__main__":
    main()
