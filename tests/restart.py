#!/usr/bin/python3
"""Checkpoint and restart (`Output/Checkpoint interval`, `--resume`).

Each scene runs once uninterrupted and once killed with SIGKILL at a random
moment after its first checkpoint, then resumed with --resume: the resumed
run's statistics.csv and iterations.csv must equal the uninterrupted run's to
1e-10 of each column's scale (time and residual columns aside: see
equal_tables; on 1 rank they are equal to the last digit). On 2 ranks the
parallel direct solver does not round the same way from one run to the next,
which can move a loop's stop by an iteration where its criterion is borderline
(seen once in CI on the triangles): there the steps and times must be the same
and the forces equal to the nested loops' tolerance (1e-4 of each column's
scale), see close_tables. The resumed run's .pvd must
list the same, complete, files, and on 1 rank its last profile (with the
slip accumulated over the steps) equal the uninterrupted one's. Scenes: the J2 patin (material history) on 1
rank and on 2 ranks, on quadrilaterals and on triangles (2 ranks), and a Hertz cylinder with two cycles of adaptive
refinement (the mesh is rebuilt from the checkpoint's refinements), and the
patin on a deformable block with `Complementarity = weighted` (the contact
faces' segments of the checkpoint's configuration, the nodal statuses and
thresholds) and `Predictor = extrapolation` (the last step's increment).

Then a damaged checkpoint is refused with a clear message and a non-zero
exit: a truncated rank file, a resume on another number of ranks, a changed
parameter, an End time before the checkpoint's time, and no checkpoint at all."""
import os
import random
import shutil
import signal
import subprocess
import sys
import time
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
sltest.seed_random("SL_RESTART_SEED", "kill moments")


def scene_text(name, refinements, extra=""):
    text = sltest.read_prm(os.path.join(root, "prm", name))
    return (text.replace("set Global refinements = 4", f"set Global refinements = {refinements}") +
            extra + "\nsubsection Output\n  set Output directory = output\n"
            "  set Checkpoint interval = 2\nend\n")


def command(ranks, resume=False):
    c = [executable] + (["--resume"] if resume else []) + ["input.prm"]
    return (["mpirun", "-np", str(ranks)] + c) if ranks > 1 else c


def prepare(directory, text):
    shutil.rmtree(directory, ignore_errors=True)
    os.makedirs(directory)
    with open(os.path.join(directory, "input.prm"), "w") as f:
        f.write(text)


def killed_run(directory, ranks):
    """Start the run, wait for its first checkpoint, kill it at a random moment after."""
    process = subprocess.Popen(command(ranks), cwd=directory, env=sltest.MPI_ENV,
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                               start_new_session=True)
    manifest = os.path.join(directory, "output", "checkpoint", "manifest")
    while not os.path.exists(manifest) and process.poll() is None:
        time.sleep(0.01)
    delay = random.uniform(0., 1.5)
    time.sleep(delay)
    finished = process.poll() is not None
    if not finished:
        os.killpg(process.pid, signal.SIGKILL)
    process.wait()
    kill_leftovers(directory)
    return delay, finished


def kill_leftovers(directory):
    """Kill every process still working in directory and wait until none is left: MPI ranks
    may outlive a killed mpirun for a moment, and one that writes a statistics row after the
    resumed run truncated the file puts that row among the resumed run's (seen once:
    steps 4, 6, 5, 6, ...)."""
    target = os.path.realpath(directory)
    for _ in range(1000):
        left = []
        for pid in filter(str.isdigit, os.listdir("/proc")):
            try:
                if os.path.realpath(os.readlink(f"/proc/{pid}/cwd")) == target:
                    left.append(int(pid))
            except OSError:  # gone, or a zombie
                pass
        if not left:
            return
        for pid in left:
            try:
                os.kill(pid, signal.SIGKILL)
            except OSError:
                pass
        time.sleep(0.01)


def rows(path):
    with open(path) as f:
        return [line.rstrip("\n").split(",") for line in f]


def equal_tables(a, b):
    """Same shape and header; every column but the wall times and the residuals equal to
    1e-10 of the column's largest value (counts therefore exactly). The residuals are left
    out: they are round-off (1e-9 N on forces of 5e4 N), and on 2 ranks the parallel direct
    solver does not round the same way from one run to the next."""
    if len(a) != len(b) or a[0] != b[0]:
        return False
    header = a[0]
    for c, name in enumerate(header):
        if name == "wall_time_s" or "residual" in name:
            continue
        x, y = [float(r[c]) for r in a[1:]], [float(r[c]) for r in b[1:]]
        scale = max([abs(v) for v in x] + [1e-300])
        if any(abs(u - v) > 1e-10 * scale for u, v in zip(x, y)):
            return False
    return True


FORCE_COLUMNS = ("normal_force_N", "tangential_force_N", "contact_force_", "reaction_boundary_")


def close_tables(a, b):
    """For runs on several ranks: the same load steps (step, time, step size) and the forces
    equal to 1e-4 of each column's largest value (the geometry and friction loops stop at a
    relative change of 1e-4)."""
    if len(a) != len(b) or a[0] != b[0]:
        return False
    header = a[0]
    for c, name in enumerate(header):
        x, y = [float(r[c]) for r in a[1:]], [float(r[c]) for r in b[1:]]
        if name in ("step", "time", "step_size"):
            tolerance = 1e-12 * max([abs(v) for v in x] + [1e-300])
        elif name.startswith(FORCE_COLUMNS):
            tolerance = 1e-4 * max([abs(v) for v in x] + [1e-300])
        else:
            continue
        if any(abs(u - v) > tolerance for u, v in zip(x, y)):
            return False
    return True


def pvd_files(directory):
    with open(os.path.join(directory, "solution.pvd")) as f:
        return [line.split('file="')[1].split('"')[0] for line in f if 'file="' in line]


scenes = {
    "j2_patin_1_rank": (scene_text("patin_elastoplastic.prm", 4), 1, ""),
    "j2_patin_2_ranks": (scene_text("patin_elastoplastic.prm", 3), 2, ""),
    "j2_patin_triangles_2_ranks": (scene_text("patin_elastoplastic_triangles.prm", 0), 2, ""),
    "hertz_adaptive": (scene_text("hertz_cylinder.prm", 4,
                                  sltest.nested_set("Adaptive refinement/Cycles", 2)), 1,
                       "the last cycle"),
    # two bodies: the segments of the checkpoint's configuration, the weighted
    # conditions' nodal statuses and thresholds, and the extrapolating predictor's
    # last increment
    "weighted_two_bodies_1_rank": (scene_text("patin_deformable_block.prm", 1,
                                              sltest.nested_set("Contact/Complementarity", "weighted")
                                              + sltest.nested_set("Nonlinear solver/Predictor",
                                                                  "extrapolation")), 1, ""),
}
for name, (text, ranks, note) in scenes.items():
    full, interrupted = f"{workdir}/{name}/full", f"{workdir}/{name}/killed"
    prepare(full, text)
    code = subprocess.run(command(ranks), cwd=full, env=sltest.MPI_ENV,
                          capture_output=True).returncode
    check(code == 0, f"{name}: the uninterrupted run ends with 0")
    prepare(interrupted, text)
    delay, finished = killed_run(interrupted, ranks)
    resumed = subprocess.run(command(ranks, resume=True), cwd=interrupted, env=sltest.MPI_ENV,
                             capture_output=True, text=True)
    check(resumed.returncode == 0,
          f"{name}: killed {delay:.2f} s after its first checkpoint"
          f"{' (it had finished)' if finished else ''}, resumed with exit code "
          f"{resumed.returncode}")
    if resumed.returncode != 0:
        print(resumed.stdout[-2000:] + resumed.stderr[-2000:])
        continue
    if ranks == 1:
        for table in ("statistics.csv", "iterations.csv"):
            a, b = rows(f"{full}/output/{table}"), rows(f"{interrupted}/output/{table}")
            check(equal_tables(a, b),
                  f"{name}: {table} of the resumed run equals the uninterrupted one ({len(a) - 1} rows)")
        if not note:
            # the last profile: its accumulated slip is carried by the checkpoint
            last = sorted(f for f in os.listdir(f"{full}/output") if f.startswith("profile-"))[-1]
            a, b = rows(f"{full}/output/{last}"), rows(f"{interrupted}/output/{last}")
            check("slip_path_mm" in a[0] and equal_tables(a, b),
                  f"{name}: {last} of the resumed run (its cumulative slip and slip path) equals "
                  f"the uninterrupted one ({len(a) - 1} nodes)")
    else:
        a, b = rows(f"{full}/output/statistics.csv"), rows(f"{interrupted}/output/statistics.csv")
        same = equal_tables(a, b)
        check(same or close_tables(a, b),
              f"{name}: statistics.csv of the resumed run "
              + ("equals the uninterrupted one" if same else
                 "has the uninterrupted one's steps and its forces to 1e-4 (the iterations differ)")
              + f" ({len(a) - 1} rows)")
    listed = pvd_files(f"{interrupted}/output")
    check(listed == pvd_files(f"{full}/output") and
          all(os.path.getsize(f"{interrupted}/output/{f}") > 0 for f in listed),
          f"{name}: the .pvd lists the same {len(listed)} files, all written")
    if note:
        a = rows(f"{full}/output/refinement_cycles.csv")
        b = rows(f"{interrupted}/output/refinement_cycles.csv")
        check(equal_tables(a, b),
              f"{name}: refinement_cycles.csv equal ({len(a) - 1} cycles)")

# damaged checkpoints and wrong resumes
base = f"{workdir}/j2_patin_1_rank/full"
checkpoint = f"{base}/output/checkpoint"


def refused(what, ranks=1, expected=""):
    result = subprocess.run(command(ranks, resume=True), cwd=base, env=sltest.MPI_ENV,
                            capture_output=True, text=True)
    output = result.stdout + result.stderr
    check(result.returncode != 0 and expected in output,
          f"{what}: refused with exit code {result.returncode} and a message naming it")
    if result.returncode == 0 or expected not in output:
        print(output[-1500:])


if os.path.exists(checkpoint):
    refused("resume on 2 ranks of a 1-rank checkpoint", 2, "mpirun -np 1")
    with open(f"{base}/input.prm") as f:
        original = f.read()
    with open(f"{base}/input.prm", "w") as f:
        f.write(original.replace("u0=2.5", "u0=2.0"))
    refused("a changed Boundary conditions entry", 1, "Function constants")
    # an End time before the checkpoint's time leaves nothing to solve
    with open(f"{base}/input.prm", "w") as f:
        f.write(original + "\nsubsection Load stepping\n  set End time = 1e-6\nend\n")
    refused("an End time before the checkpoint's time", 1, "Load stepping/End time = 1e-06 is before")
    with open(f"{base}/input.prm", "w") as f:
        f.write(original)
    data = open(f"{checkpoint}/rank-0.bin", "rb").read()
    with open(f"{checkpoint}/rank-0.bin", "wb") as f:
        f.write(data[:len(data) // 2])
    refused("a truncated checkpoint file", 1, "truncated")
    shutil.rmtree(checkpoint)
    refused("no checkpoint", 1, "no checkpoint")
check.finish()
