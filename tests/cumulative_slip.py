#!/usr/bin/python3
"""The slip accumulated at each node of the contact surface (profile columns
cumulative_slip_<axis>_mm and slip_path_mm, VTU fields cumulative_slip_mm and
slip_path_mm) on the elastic patin (prm/patin_elastic.prm: pressed, then
dragged), on 1 and 2 MPI ranks:

- at every step and node, cumulative_slip is the sum of the slip increments of
  the steps up to it in which the node was in contact (status 1 or 2), and
  slip_path the sum of their lengths, to 1e-12 of the largest slip path;
- the left end slips outwards while the patin is pressed and forwards while it
  is dragged, so its slip path exceeds the length of its cumulative slip by
  twice the outward slip it took back;
- the 2-rank run gives the 1-rank run's accumulated slip to 1e-8 of the
  largest slip path (its own iterations round differently).
Checkpoint and restart carry the accumulated slip (tests/restart.py)."""
import math
import os
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
text = sltest.read_prm(os.path.join(root, "prm", "patin_elastic.prm"))
text = text.replace("set Global refinements = 4", "set Global refinements = 3")


def profiles(out):
    names = sorted(f for f in os.listdir(out) if f.startswith("profile-"))
    return [sltest.read_csv(os.path.join(out, name)) for name in names]


finals = {}
for ranks in (1, 2):
    out = os.path.join(workdir, f"np{ranks}")
    sltest.run(executable, text + sltest.QUIET_OUTPUT, out, ranks=ranks)
    steps = profiles(os.path.join(out, "output"))
    scale = max(row["slip_path_mm"] for row in steps[-1])
    sums, worst = {}, 0.0
    for rows in steps:
        for row in rows:
            key = (round(row["x_mm"], 6), round(row["y_mm"], 6))
            sx, sy, path = sums.get(key, (0.0, 0.0, 0.0))
            if row["status"] != 0:
                dx, dy = row["slip_increment_x_mm"], row["slip_increment_y_mm"]
                sx, sy, path = sx + dx, sy + dy, path + math.hypot(dx, dy)
            sums[key] = (sx, sy, path)
            worst = max(worst, abs(row["cumulative_slip_x_mm"] - sx), abs(row["cumulative_slip_y_mm"] - sy),
                        abs(row["slip_path_mm"] - path))
    check(scale > 0 and worst <= 1e-12 * scale,
          f"{ranks} rank(s): at all {len(steps)} steps and {len(steps[-1])} nodes the accumulated slip is "
          f"the sum of the in-contact increments (largest difference {worst:.1e} mm, slip path up to "
          f"{scale:.4f} mm)")
    left = min(steps[-1], key=lambda row: row["x_mm"])
    outward = -min(rows[0]["cumulative_slip_x_mm"] for rows in steps)
    cumulative = math.hypot(left["cumulative_slip_x_mm"], left["cumulative_slip_y_mm"])
    check(outward > 0 and abs(left["slip_path_mm"] - (cumulative + 2 * outward)) <= 1e-3 * scale,
          f"{ranks} rank(s): the left end slid {outward:.4f} mm outwards, then forwards: slip path "
          f"{left['slip_path_mm']:.4f} = |cumulative slip| {cumulative:.4f} + 2 x {outward:.4f} mm "
          "(to 1e-3 of the path: the forward slip starts within a step)")
    finals[ranks] = steps[-1]
worst = max(abs(a[c] - b[c]) for a, b in zip(finals[1], finals[2])
            for c in ("cumulative_slip_x_mm", "cumulative_slip_y_mm", "slip_path_mm"))
check(worst <= 1e-8 * max(row["slip_path_mm"] for row in finals[1]),
      f"2 ranks: the accumulated slip of 1 rank (largest difference {worst:.1e} mm)")
check.finish()
