#!/usr/bin/python3
"""The distributed contact search against the replicated one, on 2 MPI ranks.

With `Contact/Master surface search = distributed` (the default) a rank holds only the
master faces within the search distance of its own deformed slave faces, gathered from
their owners as the bodies move; with `replicated` every rank holds the whole master
surface (doc/formulation.md, "Distributed contact search"). Within the search distance
both must give the same pairings, hence the same iterates: the runs are compared step by
step (Newton iterations equal; every force, gap, pressure and traction to 1e-9 of its
column's scale: the two runs differ only by the order of sums, while one wrong pairing of
a contact point moves them by far more), on
- prm/ironing.prm (2D, generalized Newton) with the die as the slave: the die slides 10 mm,
  twenty of the block's cells, over the master; the ranks' holdings must grow along the way, and no rank may
  hold the whole master surface;
- the same with a search distance of 0.3 mm (about half a master face): more growth,
  fewer faces held, the same result where points touch (gap below the distance);
- two 3D blocks (tests/scenes/two_blocks_3d.geo, 8 x 8 slave faces on 6 x 6 master ones)
  pressed and slid 1 mm with friction, with a search distance of 0.5 mm (the automatic one,
  twice the largest face diameter, reaches across the whole 10 mm master).
"""
import os
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
prm_dir = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "prm")
TOLERANCE = 1e-9


def search(mode, distance=None):
    # The pointwise conditions, with which the bounds were set. With the weighted ones (the
    # default for two bodies) the generalized Newton diverges on ironing with the die as the
    # slave at t = 0.22 (doc/two_bodies.md has it too), and on the 3D blocks the two
    # searches agree to 1e-8 of the tangential traction (Newton's tolerance), not 1e-9.
    text = sltest.nested_set("Contact/Complementarity", "pointwise")
    text += sltest.nested_set("Contact/Master surface search", mode)
    if distance is not None:
        text += sltest.nested_set("Contact/Search distance", distance)
    return text


def run(name, scene, mode, distance=None):
    out = os.path.join(workdir, name, mode if distance is None else f"{mode}-{distance}")
    if not sltest.run_checked(executable, scene + search(mode, distance), out, check,
                              f"{name}, {mode} search", ranks=2):
        return None
    output = os.path.join(out, "output")
    profiles = sorted(p for p in os.listdir(output) if p.startswith("profile-"))
    return {"statistics": sltest.read_csv(os.path.join(output, "statistics.csv")),
            "summary": sltest.read_csv(os.path.join(output, "run_summary.csv"))[0],
            "profiles": [sltest.read_csv(os.path.join(output, p)) for p in profiles]}


def largest_difference(rows_a, rows_b, columns):
    """Per column: the largest difference over the rows, over the largest magnitude."""
    result = {}
    for column in columns:
        scale = max(max(abs(row[column]) for row in rows) for rows in (rows_a, rows_b))
        difference = max(abs(a[column] - b[column]) for a, b in zip(rows_a, rows_b))
        result[column] = difference / scale if scale > 0 else difference
    return result


def compare(name, distributed, replicated, gap_limit=None):
    """The distributed run's steps and contact nodes against the replicated run's; with
    gap_limit, the profiles' nodes only where the gap is below it in both."""
    steps_d, steps_r = distributed["statistics"], replicated["statistics"]
    check(len(steps_d) == len(steps_r) and
          all(a["newton_iterations"] == b["newton_iterations"] for a, b in zip(steps_d, steps_r)),
          f"{name}: the same load steps and Newton iterations "
          f"({sum(r['newton_iterations'] for r in steps_d):.0f} against "
          f"{sum(r['newton_iterations'] for r in steps_r):.0f})")
    # (over the largest force of the run: a reaction across the sliding is near zero)
    forces = [c for c in steps_d[0] if c.endswith("_N") and "residual" not in c]
    scale = max(abs(row[c]) for rows in (steps_d, steps_r) for row in rows for c in forces)
    worst = max((max(abs(a[c] - b[c]) for a, b in zip(steps_d, steps_r)) / scale, c) for c in forces)
    check(worst[0] < TOLERANCE, f"{name}: forces agree at every step (worst {worst[1]}: "
          f"{worst[0]:.1e} of the largest force)")
    fields = ["contact_pressure_MPa", "gap_mm"] + [c for c in distributed["profiles"][0][0]
                                                    if c.startswith("tangential_traction")]
    worst, nodes = {}, 0
    for profile_d, profile_r in zip(distributed["profiles"], replicated["profiles"]):
        if len(profile_d) != len(profile_r):
            check(False, f"{name}: the profiles list {len(profile_d)} and {len(profile_r)} nodes")
            return
        kept = [(a, b) for a, b in zip(profile_d, profile_r)
                if gap_limit is None or max(a["gap_mm"], b["gap_mm"]) < gap_limit]
        nodes += len(kept)
        if kept:
            for column, value in largest_difference(*zip(*kept), fields).items():
                worst[column] = max(worst.get(column, 0.), value)
    column = max(worst, key=worst.get)
    check(nodes > 0 and worst[column] < TOLERANCE,
          f"{name}: {nodes} node values of every step agree (worst {column}: {worst[column]:.1e})")


def check_holdings(name, summary, growths_expected):
    held, total, growths = (summary["master_faces_held_max"], summary["master_faces"],
                            summary["master_search_growths"])
    check(0 < held < total, f"{name}: at most {held:.0f} of the {total:.0f} master faces held on a rank")
    if growths_expected:
        check(growths >= 1, f"{name}: the holdings grew {growths:.0f} time(s) as the bodies moved")


# --- ironing (2D): large sliding -------------------------------------------------------
# the die as the slave: its points travel over the block's faces, the search's hard case
SCENE_ROLES = ("set Contact boundary ids = block_top\n  set Master boundary ids  = die_contact")
ironing = sltest.read_prm(os.path.join(prm_dir, "ironing.prm"))
if SCENE_ROLES not in ironing:
    raise SystemExit("FAIL: prm/ironing.prm does not make the block's top the slave")
ironing = ironing.replace(SCENE_ROLES, "set Contact boundary ids = die_contact\n  set Master boundary ids  = block_top")
runs = {mode: run("ironing", ironing, mode) for mode in ("distributed", "replicated")}
if all(runs.values()):
    compare("ironing", runs["distributed"], runs["replicated"])
    check_holdings("ironing", runs["distributed"]["summary"], True)
    check(runs["replicated"]["summary"]["master_faces_held_max"] ==
          runs["replicated"]["summary"]["master_faces"],
          "ironing, replicated: every rank holds every master face")
    near = run("ironing", ironing, "distributed", 0.3)
    if near:
        compare("ironing, search distance 0.3 mm", near, runs["replicated"], gap_limit=0.3)
        check_holdings("ironing, search distance 0.3 mm", near["summary"], True)
        check(near["summary"]["master_faces_held_max"] <
              runs["distributed"]["summary"]["master_faces_held_max"],
              f"ironing: a shorter search distance holds fewer faces "
              f"({near['summary']['master_faces_held_max']:.0f} against "
              f"{runs['distributed']['summary']['master_faces_held_max']:.0f})")

# --- two 3D blocks slid with friction -------------------------------------------------
blocks = (sltest.two_blocks(3, "two_blocks_3d.geo", 0.2, refinements=1) + sltest.GENERALIZED_NEWTON +
          sltest.blocks_pressed_and_slid(0.05, 0.4, 5))
runs = {"distributed": run("blocks_3d", blocks, "distributed", 0.5),
        "replicated": run("blocks_3d", blocks, "replicated")}
if all(runs.values()):
    compare("two 3D blocks, search distance 0.5 mm", runs["distributed"], runs["replicated"],
            gap_limit=0.5)
    check_holdings("two 3D blocks, search distance 0.5 mm", runs["distributed"]["summary"], False)

check.finish()
