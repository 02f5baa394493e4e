#!/usr/bin/python3
"""Contact zones with their own friction law (`Contact/Zone <name>`) on prm/two_zones.prm: one
block on a rigid plane whose bottom is two boundaries, mu = 0.1 under the left half (`Zone
left`) and mu = 0.3 under the right half (`Zone right`), pressed then slid.

- In full slip every point's tangential traction is its zone's mu times its pressure, so each
  zone's F_t = mu F_n (statistics.csv, zone_<name>_normal_force_N and _tangential_force_N) to
  the solver's tolerance (1e-8); the zones' normal forces add up to the total.
- Before the slide the block is pressed only, and the zones' ratios stay below their mu.
- With the nested loops, the generalized Newton on 2 MPI ranks, and with `Zone left` left out
  (its boundary then takes Contact/Friction law, also mu = 0.1): the same forces.
- Refused with a message: a zone naming a boundary that is not a contact boundary, a boundary
  in two zones, zones with the weighted conditions."""
import os
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
text = sltest.read_prm(os.path.join(root, "prm", "two_zones.prm"))
ZONE_LEFT = text[text.index("  subsection Zone left"):text.index("  subsection Zone right")]
MU = {"left": 0.1, "right": 0.3}

runs = {}
for name, prm, ranks in (("nested loops", text, 1), ("generalized Newton, 2 ranks", text + sltest.GENERALIZED_NEWTON, 2),
                         ("without Zone left", text.replace(ZONE_LEFT, ""), 1)):
    out = os.path.join(workdir, name.replace(" ", "_").replace(",", ""))
    sltest.run(executable, prm + sltest.QUIET_OUTPUT, out, ranks=ranks)
    rows = sltest.read_csv(os.path.join(out, "output", "statistics.csv"))
    runs[name] = rows
    zones = [z for z in MU if f"zone_{z}_normal_force_N" in rows[0]]
    slipping = [row for row in rows if row["points_stick"] == 0]
    pressed = [row for row in rows if row["time"] <= 0.5]
    check(len(slipping) >= 3 and len(pressed) >= 3, f"{name}: {len(slipping)} steps in full slip, {len(pressed)} pressed only")
    for zone in zones:
        ratios = [row[f"zone_{zone}_tangential_force_N"] / row[f"zone_{zone}_normal_force_N"] for row in slipping]
        check(all(abs(r - MU[zone]) <= 1e-8 for r in ratios),
              f"{name}: zone {zone} in full slip, F_t / F_n = mu = {MU[zone]}: "
              + ", ".join(f"{r:.10f}" for r in ratios))
        below = [row[f"zone_{zone}_tangential_force_N"] / row[f"zone_{zone}_normal_force_N"] for row in pressed]
        check(all(r < MU[zone] for r in below), f"{name}: zone {zone} pressed only, F_t / F_n below mu "
              f"({max(below):.4f})")
    total = max(abs(sum(row[f"zone_{z}_normal_force_N"] for z in zones) - row["normal_force_N"]) for row in rows)
    if len(zones) == 2:
        check(total <= 1e-8 * rows[-1]["normal_force_N"], f"{name}: the zones' normal forces add up to F_n "
              f"(largest difference {total:.1e} N/mm)")
    else:
        check(zones == ["right"], f"{name}: only zone right has columns")
for name in ("generalized Newton, 2 ranks", "without Zone left"):
    tolerance = 1e-4 if "Newton" in name else 1e-8  # the nested loops stop at their 1e-4
    worst = max(abs(a[c] - b[c]) / runs["nested loops"][-1]["normal_force_N"]
                for a, b in zip(runs[name], runs["nested loops"])
                for c in ("normal_force_N", "tangential_force_N", "zone_right_normal_force_N"))
    check(len(runs[name]) == len(runs["nested loops"]) and worst <= tolerance,
          f"{name}: the forces of the nested run at every step (largest relative difference {worst:.1e})")

for name, prm, expect in (
        ("a zone on a boundary without contact", text.replace("    set Boundary ids = bottom_left", "    set Boundary ids = top"),
         "is not a contact boundary"),
        ("a boundary in two zones", text.replace("    set Boundary ids = bottom_left", "    set Boundary ids = bottom_right"),
         "already in another zone"),
        ("zones with the weighted conditions", text + sltest.nested_set("Contact/Complementarity", "weighted"),
         "pointwise conditions only")):
    code, log = sltest.run(executable, prm + sltest.QUIET_OUTPUT, os.path.join(workdir, "refused"),
                           expect_success=False)
    check(code == 1 and expect in log and "Zone" in log, f"{name}: refused ({log.strip().splitlines()[-1][:150]})")
check.finish()
