#!/usr/bin/python3
"""The error of a reference solution, estimated from the reference and the same
pair one and two levels coarser, and which orders of measured errors it lets
stand (contrib/compare.py).

Richardson's estimate: with d1 the difference between the two coarser levels and
d0 between the reference and the level below it, both relative to the finer
one: halving the mesh size divides an error of order q by 2^q, so d1 / d0 = 2^q
and the reference's error is d0 / (2^q - 1). The observed q is kept to at most
2, so that a lucky ratio on coarse levels does not make the estimate small (the
square-root edge of a contact pressure holds its L2 error near order 1); with
only two levels q = 1 is taken (the reference's error is then d0 itself). Where d0 >= d1 the levels do
not converge and the error is not known (inf).

A measured error e = ||p - p_ref|| / ||p_ref|| is the true one within the
reference's error E (triangle inequality), so two choices whose measured errors
differ by less than 2 E may be in either order; the tool asks for 3 E, room for
E being an estimate."""
import math
import os
import sys

MAX_ORDER = 2.0
# the reference's estimated error must be below this fraction of a difference it decides
TRUST_FRACTION, TRUST_FRACTION_TEXT = 1 / 3, "a third"


def richardson(fine, coarse):
    """(estimate, observed order or None, how it was found) of the finest level's error from the difference
    fine (reference against one level coarser) and coarse (one level against two; None if not run)."""
    if fine is None or not math.isfinite(fine):
        return math.inf, None, "no difference measured"
    if coarse is None:
        return fine, None, "order 1 taken: no third level"
    if fine == 0:
        return 0.0, None, "the levels agree"
    if coarse <= fine:
        return math.inf, None, "the levels' differences do not decrease: no convergence seen"
    order = min(math.log2(coarse / fine), MAX_ORDER)
    return fine / (2 ** order - 1), order, f"observed order {order:.2f}" + (
        f" (at most {MAX_ORDER:g})" if order == MAX_ORDER else "")


def doubtful_orders(values, error):
    """The pairs (a, b) of consecutive (by value) labelled values [(label, value)] whose difference is not
    above error / TRUST_FRACTION: their order is within the reference's error."""
    ranked = sorted((v, label) for label, v in values if v is not None and math.isfinite(v))
    return [(a, b, vb - va) for (va, a), (vb, b) in zip(ranked, ranked[1:])
            if not vb - va > error / TRUST_FRACTION]


def ranking(values):
    """The labels of [(label, value)] by increasing finite value."""
    return [label for label, v in sorted(values, key=lambda lv: lv[1])
            if v is not None and math.isfinite(v)]


if __name__ == "__main__":
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import tool_cli
    tool_cli.module_help(__doc__)
