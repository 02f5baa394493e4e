#!/usr/bin/python3
"""Contact pressure and tangential traction along the contact surface, per load step.

Usage: contrib/plot_profiles.py OUTPUT_DIR [--step N|all|last ...] [--along x|y|z|r]
                                [--output FOLDER]

Reads the run's profile-NNNNN.csv (the contact surface node by node, in
reference coordinates) and writes, per step asked for (default: every step),
FOLDER/profile-NNNNN.png: above, the contact pressure; below, the tangential
traction, with the friction bound of the run's law (Coulomb: ±μ p, Tresca: ±s,
from parameters.prm) dashed. Every node is marked by its status: stick, slip or
open (no contact). With more than one step, FOLDER/profiles.png overlays them,
coloured by load step.

The abscissa is the reference coordinate along --along: in 2D, by default the
coordinate in which the contact surface is longest; the tangential traction is
then its magnitude, signed by its component along that axis. In 3D the nodes
are many: by default the profile is the row of nodes across the contact zone
along x through the pressure's centroid (--along x or y), the tangential
traction its component along that axis, every other node grey in the
background; --along r plots every node against its distance from the centroid
(e.g. for an axisymmetric contact), the tangential traction as its magnitude.

FOLDER defaults to OUTPUT_DIR. Exits with 2 and a message if OUTPUT_DIR has no
profiles or a step is not among them."""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import run_output  # noqa: E402
import tool_cli  # noqa: E402

STATUS = {0: ("open", "x", "grey"), 1: ("stick", "o", "tab:blue"), 2: ("slip", "^", "tab:orange")}
AXES = "xyz"


class Profile:
    """One profile-NNNNN.csv as arrays: positions X (n x dim), pressure p, traction t (n x dim), status."""

    def __init__(self, path):
        rows = run_output.read_csv(path)
        if not rows:
            raise run_output.OutputError(f"{path} has no node")
        self.dim = 3 if "z_mm" in rows[0] else 2
        self.X = np.array([[r[f"{a}_mm"] for a in AXES[:self.dim]] for r in rows])
        self.p = np.array([r["contact_pressure_MPa"] for r in rows]) + 0.0  # + 0.0: no -0 in the labels
        self.t = np.array([[r[f"tangential_traction_{a}_MPa"] for a in AXES[:self.dim]] for r in rows])
        self.status = np.array([int(r["status"]) for r in rows])

    def centroid(self):
        """The pressure's centroid; the nodes' centre where no node is pressed."""
        if self.p.sum() > 0:
            return (self.X * self.p[:, None]).sum(0) / self.p.sum()
        return self.X.mean(0)


def default_axis(profile):
    """2D: the coordinate of the longest extent of the contact surface; 3D: x."""
    if profile.dim == 2:
        return "x" if np.ptp(profile.X[:, 0]) >= np.ptp(profile.X[:, 1]) else "y"
    return "x"


def section(profile, along, centre):
    """(position, pressure, tangential traction, status, indices) of the nodes of the profile
    along `along`, sorted; the tangential traction's label; which nodes, in words (or '')."""
    if along == "r":
        # the distance across the surface: in 3D the normal direction is taken as the one in which the
        # contact nodes spread least
        normal = int(np.argmin(np.ptp(profile.X, axis=0)))
        offsets = np.delete(profile.X - centre, normal, axis=1)
        position = np.sqrt((offsets ** 2).sum(1))
        traction = np.sqrt((profile.t ** 2).sum(1))
        chosen = np.arange(len(position))
        label = "|tangential traction| (MPa)"
        which = ""
    else:
        k = AXES.index(along)
        chosen = np.arange(len(profile.p))
        which = ""
        if profile.dim == 3:
            # the row of nodes through the centroid: within a quarter of the node spacing of the node
            # nearest the centroid, in the other tangential coordinate
            others = [i for i in range(3) if i != k and np.ptp(profile.X[:, i]) > 0]
            other = max(others, key=lambda i: np.ptp(profile.X[:, i])) if others else None
            if other is not None:
                nearest = profile.X[np.argmin(np.abs(profile.X[:, other] - centre[other])), other]
                chosen = np.nonzero(np.abs(profile.X[:, other] - nearest) <= 0.25 * run_output.node_spacing(profile.X))[0]
                which = (f"the row of nodes at {AXES[other]} = {round(nearest, 9) + 0.0:.4g} mm (through the pressure's "
                         "centroid); grey: the other nodes")
            traction = profile.t[:, k]
            label = f"tangential traction, {along} component (MPa)"
        else:
            magnitude = np.sqrt((profile.t ** 2).sum(1))
            traction = np.where(profile.t[:, k] < 0, -magnitude, magnitude)
            label = f"tangential traction (MPa), > 0 towards +{along}"
        position = profile.X[:, k]
    order = chosen[np.argsort(position[chosen], kind="stable")]
    return position[order], profile.p[order], traction[order], profile.status[order], order, label, which


def friction_bound(law, pressure):
    """The largest tangential traction the law allows at each pressure, and its name."""
    if law is None:
        return None, None
    name, value = law
    if name == "Coulomb":
        return value * np.maximum(pressure, 0.0), f"±μ p (Coulomb, μ = {value:g})"
    return np.where(pressure > 0, value, 0.0), f"±s (Tresca, s = {value:g} MPa)"


def axis_label(along):
    if along == "r":
        return "distance from the pressure's centroid (mm, reference configuration)"
    return f"{along} (mm, reference configuration)"


def plot_step(profile, along, law, title, png):
    centre = profile.centroid()
    x, p, t, status, order, t_label, which = section(profile, along, centre)
    if which:
        title += "\n" + which
    scatter = along == "r"
    fig, (ax_p, ax_t) = plt.subplots(2, 1, figsize=(9, 7), sharex=True)
    if profile.dim == 3 and not scatter:
        rest = np.setdiff1d(np.arange(len(profile.p)), order)
        k = AXES.index(along)
        if len(rest):
            ax_p.plot(profile.X[rest, k], profile.p[rest], ".", color="0.8", ms=3, label="other nodes")
            ax_t.plot(profile.X[rest, k], profile.t[rest, k], ".", color="0.8", ms=3)
    line = "none" if scatter else "-"
    ax_p.plot(x, p, color="k", lw=1, ls=line)
    ax_t.plot(x, t, color="k", lw=1, ls=line)
    bound, bound_label = friction_bound(law, p)
    if law is None:
        ax_t.text(0.5, 0.9, "frictionless: no tangential traction", transform=ax_t.transAxes, ha="center")
    else:
        ax_t.plot(x, bound, "--", color="tab:red", lw=1, label=bound_label)
        ax_t.plot(x, -bound, "--", color="tab:red", lw=1)
    for value, (name, marker, colour) in STATUS.items():
        if value == 2 and law is None:
            name = "in contact"  # every point in contact slips where there is no friction
        mask = status == value
        if mask.any():
            ax_p.plot(x[mask], p[mask], marker, color=colour, ms=4, ls="none", label=f"{name} ({mask.sum()})")
            ax_t.plot(x[mask], t[mask], marker, color=colour, ms=4, ls="none")
    ax_p.set_ylabel("contact pressure (MPa)")
    ax_t.set_ylabel(t_label)
    ax_t.set_xlabel(axis_label(along))
    ax_p.set_title(title)
    for ax in (ax_p, ax_t):
        ax.grid(True, alpha=0.3)
        ax.axhline(0, color="k", lw=0.5)
    ax_p.legend(fontsize=8, loc="best")
    if bound is not None:
        ax_t.legend(fontsize=8, loc="best")
    fig.tight_layout()
    fig.savefig(png, dpi=100)
    plt.close(fig)


def plot_overlay(profiles, along, run_name, png):
    fig, (ax_p, ax_t) = plt.subplots(2, 1, figsize=(9, 7), sharex=True)
    colours = plt.get_cmap("viridis")
    steps = list(profiles)
    t_label = None
    for i, step in enumerate(steps):
        profile, time = profiles[step]
        x, p, t, _, _, t_label, _ = section(profile, along, profile.centroid())
        style = dict(color=colours(i / max(len(steps) - 1, 1)), lw=1.2, marker="." if along == "r" else None,
                     ls="none" if along == "r" else "-", ms=3)
        ax_p.plot(x, p, label=f"step {step}" + (f", t = {time:g}" if time is not None else ""), **style)
        ax_t.plot(x, t, **style)
    ax_p.set_ylabel("contact pressure (MPa)")
    ax_t.set_ylabel(t_label)
    ax_t.set_xlabel(axis_label(along))
    ax_p.set_title(f"{run_name}: load steps {steps[0]} to {steps[-1]}")
    for ax in (ax_p, ax_t):
        ax.grid(True, alpha=0.3)
        ax.axhline(0, color="k", lw=0.5)
    ax_p.legend(fontsize=7, ncol=2 if len(steps) > 8 else 1, loc="best")
    fig.tight_layout()
    fig.savefig(png, dpi=100)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("output_dir", metavar="OUTPUT_DIR", type=tool_cli.existing_directory,
                        help="the run's output directory (holding profile-NNNNN.csv)")
    parser.add_argument("--step", nargs="+", metavar="N", default=["all"],
                        help="load steps: numbers, 'all' (the default) or 'last'")
    parser.add_argument("--along", choices=["x", "y", "z", "r"],
                        help="abscissa (default: 2D the longest extent of the contact surface, 3D x)")
    parser.add_argument("--output", metavar="FOLDER", help="folder of the PNGs (default: OUTPUT_DIR)")
    args = parser.parse_args()
    output = args.output or args.output_dir
    if os.path.exists(output) and not os.path.isdir(output):
        parser.error(f"argument --output: '{output}' exists and is not a directory")
    files = run_output.profile_steps(args.output_dir)
    try:
        if not files:
            raise run_output.OutputError(
                f"no profile-NNNNN.csv in {args.output_dir} (was the run made with Output/Write profiles = false?)")
        steps = run_output.select_steps(args.step, files, os.path.join(args.output_dir, "profile-*.csv"))
        profiles = {step: Profile(files[step]) for step in steps}
        parameters = run_output.run_parameters(args.output_dir)
        law = run_output.friction_law(parameters)
    except run_output.OutputError as error:
        parser.error(str(error))
    dim = next(iter(profiles.values())).dim
    if args.along == "z" and dim == 2:
        parser.error("argument --along: z is not a coordinate of a 2D run")
    times = run_output.step_times(args.output_dir)
    last = max(files)
    run_name = os.path.basename(os.path.normpath(os.path.abspath(args.output_dir)))
    os.makedirs(output, exist_ok=True)
    for step, profile in profiles.items():
        along = args.along or default_axis(profile)
        time = times.get(step)
        title = f"{run_name}: load step {step} of {last}" + (f", t = {time:g}" if time is not None else "")
        png = os.path.join(output, f"profile-{step:05d}.png")
        plot_step(profile, along, law, title, png)
        print(png)
    if len(profiles) > 1:
        along = args.along or default_axis(next(iter(profiles.values())))
        png = os.path.join(output, "profiles.png")
        plot_overlay({s: (p, times.get(s)) for s, p in profiles.items()}, along, run_name, png)
        print(png)


if __name__ == "__main__":
    main()
