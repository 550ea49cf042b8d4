#!/usr/bin/env python3
"""The four-bar 180/80/200/150's joint positions over a turn of 360 crank angles, one degree
apart, vectorised with numpy: the reference the batch kernels' speed is quoted against.

Same geometry and branch as `tests/src/batch_baseline.rs`: O2 = (0, 0), O4 = (l1, 0), crank
pin A = l2 (cos t2, sin t2), rocker pin B where the circles of radius l3 about A and l4 about
O4 meet, on the open branch (B to the left of the chord from A to O4). Checked against known
values and against the 25-digit sweep references of `sweeps.csv` (theta3, theta4 from
mpmath), then timed: the best of many samples, in nanoseconds per crank angle.

Run from the repository root:
    tests/reference/setup-numpy.sh
    target/numpy-venv/bin/python tests/reference/numpy_four_bar.py
and compare `numpy_ns_per_step` with `cargo run --release -p mechgen-tests --bin batch`.
"""
import csv
import math
import os
import sys
import time

try:
    import numpy as np
except ImportError:
    sys.exit("numpy is missing: run tests/reference/setup-numpy.sh, then "
             "target/numpy-venv/bin/python tests/reference/numpy_four_bar.py")

L1, L2, L3, L4 = 180.0, 80.0, 200.0, 150.0
SAMPLES = 3000


def joints(t2, l1=L1, l2=L2, l3=L3, l4=L4):
    """A and B for an array of crank angles: circle intersection, five lines of numpy."""
    ax, ay = l2 * np.cos(t2), l2 * np.sin(t2)   # crank pin A
    dx, dy = l1 - ax, -ay                         # chord from A to O4
    inv = 1.0 / (dx * dx + dy * dy)               # 1 / |chord|^2
    k = 0.5 + 0.5 * (l3 * l3 - l4 * l4) * inv     # foot of B along the chord, in chords
    t = np.sqrt(l3 * l3 * inv - k * k)            # B off the chord, to its left (NaN: misses)
    return ax, ay, ax + k * dx - t * dy, ay + k * dy + t * dx


def check(theta2):
    ax, ay, bx, by = joints(theta2)
    # Known values: at t2 = 0, A = (80, 0) and B = (217.5, sqrt(21093.75)) exactly
    # (100 mm chord, k = 1.375); at 60 degrees, theta4 = 72.1377 degrees (the seeds' Example 1).
    assert (ax[0], ay[0]) == (80.0, 0.0)
    assert abs(bx[0] - 217.5) < 1e-12 and abs(by[0] - math.sqrt(21093.75)) < 1e-12
    assert abs(math.degrees(math.atan2(by[60], bx[60] - L1)) - 72.1377) < 1e-4
    # The links keep their lengths at every angle.
    assert np.max(np.abs(np.hypot(bx - ax, by - ay) - L3)) < 1e-11
    assert np.max(np.abs(np.hypot(bx - L1, by) - L4)) < 1e-11
    # The 25-digit references: B from theta4 and from A + l3 e^(i theta3).
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "sweeps.csv")
    with open(path, newline="") as f:
        rows = [r for r in csv.DictReader(f) if r["mechanism"] == "four_bar"]
    assert len(rows) == 360 and all(int(r["degree"]) == k for k, r in enumerate(rows))
    t3 = np.array([float(r["q1"]) for r in rows])
    t4 = np.array([float(r["q2"]) for r in rows])
    worst = max(
        np.max(np.hypot(bx - (L1 + L4 * np.cos(t4)), by - L4 * np.sin(t4))),
        np.max(np.hypot(bx - (ax + L3 * np.cos(t3)), by - (ay + L3 * np.sin(t3)))),
    )
    assert worst < 1e-10, worst
    return worst


def best_ns_per_step(theta2):
    # As many calls per sample as fill about a millisecond, then the best of SAMPLES.
    calls = 1
    while True:
        start = time.perf_counter_ns()
        for _ in range(calls):
            joints(theta2)
        if time.perf_counter_ns() - start >= 1_000_000:
            break
        calls *= 2
    best = math.inf
    for _ in range(SAMPLES):
        start = time.perf_counter_ns()
        for _ in range(calls):
            joints(theta2)
        best = min(best, (time.perf_counter_ns() - start) / (calls * len(theta2)))
    return best


def main():
    theta2 = np.deg2rad(np.arange(360.0))
    worst = check(theta2)
    ns = best_ns_per_step(theta2)
    print(f"numpy {np.__version__}, Python {sys.version.split()[0]}")
    print(f"max_deviation_from_references_mm {worst:.3e}")
    print(f"numpy_us_per_turn {ns * len(theta2) / 1000:.3f}")
    print(f"numpy_ns_per_step {ns:.3f}")


if __name__ == "__main__":
    main()
