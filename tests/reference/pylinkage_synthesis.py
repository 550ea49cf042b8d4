#!/usr/bin/env python3
"""The synthesis problems of docs/SYNTHESIS.md solved by pylinkage, timed: its classical
synthesis (Freudenstein's least squares; Burmester path generation with timing), its particle
swarm and its differential evolution; and a Monte Carlo tolerance analysis with pylinkage's
kinematics. Prints `key value` lines for `cargo run --release -p mechgen-tests --bin synthesis
-- write`, which compares them with `mechanisms::synthesis` and `FourBar::tolerance`.

Geometry (the same as `mechanisms::FourBar`): crank pivot O2 at the origin, rocker pivot O4 at
(l1, 0), crank pin A = l2 (cos t2, sin t2), rocker pin B where the circles of radius l3 about A
and l4 about O4 meet, on the open branch (B to the left of the chord from A to O4), coupler
point P at distance p from A at angle delta from A B. Every circle intersection is pylinkage's
own (`pylinkage.geometry.secants.circle_intersect`, compiled by numba).

The optimisers take their objective from pylinkage's `eval_func(linkage, dims, coords)`
interface; they are handed a stand-in linkage (`Dimensions` below) whose only role is to say how
many dimensions there are, because the objective evaluates the four-bar with circle_intersect
directly: cheaper than stepping a `Linkage` through a simulation, so generous to pylinkage.
Each run stops at CAP seconds; its best error is read off at BUDGET seconds and the time it
first reaches the threshold is recorded; each optimiser runs RUNS times.

Run from the repository root:
    tests/reference/setup-pylinkage.sh
    target/pylinkage-venv/bin/python tests/reference/pylinkage_synthesis.py
"""
import importlib.metadata
import math
import sys
import time

try:
    import numpy as np
    from pylinkage.geometry.secants import circle_intersect
    from pylinkage.optimization import particle_swarm_optimization
    from pylinkage.optimization.scipy_optimize import differential_evolution_optimization
    from pylinkage.synthesis import function_generation, path_generation_with_timing
except ImportError as e:
    sys.exit(f"pylinkage is missing ({e}): run tests/reference/setup-pylinkage.sh, then "
             "target/pylinkage-venv/bin/python tests/reference/pylinkage_synthesis.py")

L1, L2, L3, L4 = 180.0, 80.0, 200.0, 150.0
P_DISTANCE, P_ANGLE = 100.0, math.radians(30.0)

# Function generation: rocker angles (degrees) at crank angles (degrees), the open branch of
# 180/80/200/150 to four decimals.
FG_CRANK = [0.0, 45.0, 90.0, 135.0, 180.0, 225.0]
FG_ROCKER = [75.5225, 66.6938, 87.1652, 111.3700, 129.9641, 138.2662]
FG_THRESHOLD = 1e-6  # rad, rms
# Path generation with prescribed timing: the coupler point of 180/80/200/150 with P 100 from
# A at 30 degrees, at crank angles 0..5 rad (also in tests/src/bin/synthesis.rs).
PG_TIMING = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0]
PG_TARGETS = [
    (103.23002763948563, 97.2644118671816),
    (104.96338014345498, 145.98324760306124),
    (28.382571701527226, 151.46023729553343),
    (-33.32881773757787, 100.14841960980091),
    (-40.32857939550637, 38.73766567707234),
    (0.9412713237244894, 20.891710497838275),
]
PG_THRESHOLD = 1e-4  # mm, rms
# Tolerance: every length +-0.1 mm, at 60 degrees.
TOL_LENGTH = 0.1
TOL_THETA2 = math.radians(60.0)

BUDGET = 1.0  # s: the best error reached within this
CAP = 10.0  # s: each optimiser run stops here
RUNS = 3  # runs of each optimiser
PENALTY = 1e6  # the error of a linkage that does not assemble


def rocker_pin(ax, ay, l3, ox, oy, l4):
    """B from A and O4 on the open branch (left of A -> O4), or None."""
    n, x1, y1, x2, y2 = circle_intersect(ax, ay, l3, ox, oy, l4)
    if n == 0 or n == 3:
        return None
    if n == 1:
        return x1, y1
    cross1 = (ox - ax) * (y1 - ay) - (oy - ay) * (x1 - ax)
    return (x1, y1) if cross1 > 0.0 else (x2, y2)


def rocker_angle(l1, l2, l3, l4, t2):
    ax, ay = l2 * math.cos(t2), l2 * math.sin(t2)
    b = rocker_pin(ax, ay, l3, l1, 0.0, l4)
    return None if b is None else math.atan2(b[1], b[0] - l1)


def coupler_point(o2x, o2y, gamma, l1, l2, l3, l4, p, delta, t2):
    """P in the targets' frame: crank pivot at (o2x, o2y), ground line at gamma."""
    ax, ay = o2x + l2 * math.cos(gamma + t2), o2y + l2 * math.sin(gamma + t2)
    ox, oy = o2x + l1 * math.cos(gamma), o2y + l1 * math.sin(gamma)
    b = rocker_pin(ax, ay, l3, ox, oy, l4)
    if b is None:
        return None
    theta3 = math.atan2(b[1] - ay, b[0] - ax)
    return ax + p * math.cos(theta3 + delta), ay + p * math.sin(theta3 + delta)


def wrap(angle):
    return (angle + math.pi) % (2.0 * math.pi) - math.pi


def fg_error(lengths):
    """rms rocker angle error (rad) of crank, coupler, rocker with ground L1."""
    l2, l3, l4 = lengths
    if min(l2, l3, l4) <= 0.0:
        return PENALTY
    total = 0.0
    for t2, t4 in zip(FG_CRANK, FG_ROCKER):
        got = rocker_angle(L1, l2, l3, l4, math.radians(t2))
        if got is None:
            return PENALTY
        total += wrap(got - math.radians(t4)) ** 2
    return math.sqrt(total / len(FG_CRANK))


def pg_error(x):
    """rms distance (mm) of the coupler point from the targets, for
    x = (O2x, O2y, gamma, l1, l2, l3, l4, p, delta)."""
    if min(x[3:8]) <= 0.0:
        return PENALTY
    total = 0.0
    for t2, (tx, ty) in zip(PG_TIMING, PG_TARGETS):
        got = coupler_point(*x, t2)
        if got is None:
            return PENALTY
        total += (got[0] - tx) ** 2 + (got[1] - ty) ** 2
    return math.sqrt(total / len(PG_TIMING))


class Stop(Exception):
    pass


class Trace:
    """Wraps an error function: the best error so far against the time since the start."""

    def __init__(self, error, threshold):
        self.error, self.threshold = error, threshold
        self.best, self.at_budget, self.reached, self.evaluations = math.inf, math.inf, None, 0
        self.start = time.perf_counter()

    def __call__(self, dims):
        e = self.error(dims)
        now = time.perf_counter() - self.start
        self.evaluations += 1
        if now <= BUDGET:
            self.at_budget = min(self.at_budget, e)
        if e < self.best:
            self.best = e
            if self.reached is None and e <= self.threshold:
                self.reached = now
        if now > CAP or (self.reached is not None and now > BUDGET):
            raise Stop
        return e


class Dimensions:
    """A stand-in for a pylinkage Linkage: the optimisers ask it only how many dimensions
    there are (get_constraints) and for joint coordinates (get_coords)."""

    def __init__(self, n):
        self.n = n

    def get_constraints(self, *args, **kwargs):
        return [1.0] * self.n

    def get_coords(self):
        return []


def optimise_once(name, error, threshold, bounds, seed):
    trace = Trace(error, threshold)

    def eval_func(_linkage, dims, _coords):
        return trace(dims)

    lower, _ = bounds
    try:
        if name == "pso":
            # pylinkage's swarm draws from an unseeded generator: each run differs.
            particle_swarm_optimization(
                eval_func, Dimensions(len(lower)), dimensions=len(lower), bounds=bounds,
                n_particles=100, iterations=1_000_000, order_relation=min, verbose=False)
        else:
            differential_evolution_optimization(
                eval_func, Dimensions(len(lower)), bounds=bounds, order_relation=min,
                maxiter=1_000_000, tol=0.0, atol=0.0, seed=seed, verbose=False)
    except Stop:
        pass
    trace.elapsed = time.perf_counter() - trace.start
    return trace


def optimise(name, prefix, error, threshold, bounds):
    """RUNS runs (seeds 1, 2, ... for differential evolution): the median time to the
    threshold (never where most runs never reach it), the median error at the budget, the
    best error of all."""
    traces = [optimise_once(name, error, threshold, bounds, seed)
              for seed in range(1, RUNS + 1)]
    times = sorted(math.inf if t.reached is None else t.reached for t in traces)
    median = times[len(times) // 2]
    print(f"{prefix}_{name}_runs {RUNS}")
    print(f"{prefix}_{name}_reached {sum(t.reached is not None for t in traces)}")
    print(f"{prefix}_{name}_seconds_to_threshold "
          f"{'never' if math.isinf(median) else f'{median:.4e}'}")
    print(f"{prefix}_{name}_seconds_to_threshold_all "
          f"{','.join('never' if math.isinf(t) else f'{t:.3g}' for t in times)}")
    at_budget = sorted(t.at_budget for t in traces)
    print(f"{prefix}_{name}_error_at_budget {at_budget[len(at_budget) // 2]:.4e}")
    print(f"{prefix}_{name}_best_error {min(t.best for t in traces):.4e}")
    print(f"{prefix}_{name}_run_seconds {sum(t.elapsed for t in traces):.3f}")
    print(f"{prefix}_{name}_evaluations {sum(t.evaluations for t in traces)}")


def best_time(f, repeats):
    best, result = math.inf, None
    for _ in range(repeats):
        start = time.perf_counter()
        result = f()
        best = min(best, time.perf_counter() - start)
    return best, result


def classical_function_generation():
    pairs = [(math.radians(a), math.radians(b)) for a, b in zip(FG_CRANK, FG_ROCKER)]
    seconds, result = best_time(lambda: function_generation(pairs, ground_length=L1), 20)
    if not result.raw_solutions:
        print("fg_classical_solutions 0")
        return
    s = result.raw_solutions[0]
    print(f"fg_classical_seconds {seconds:.4e}")
    print(f"fg_classical_lengths {s.crank_length:.6f} {s.coupler_length:.6f} "
          f"{s.rocker_length:.6f}")
    print(f"fg_classical_error {fg_error((s.crank_length, s.coupler_length, s.rocker_length)):.4e}")


def solution_path_error(s):
    """The rms error at the timed targets of a Burmester solution: its crank turned from its
    first position by the prescribed crank angle differences, on the branch it was drawn on."""
    (ax, ay), (dx, dy) = s.ground_pivot_a, s.ground_pivot_d
    (bx, by), (cx, cy) = s.crank_pivot_b, s.coupler_pivot_c
    px, py = s.coupler_point if s.coupler_point is not None else PG_TARGETS[0]
    l2, l3, l4 = math.dist((ax, ay), (bx, by)), math.dist((bx, by), (cx, cy)), \
        math.dist((dx, dy), (cx, cy))
    p = math.dist((bx, by), (px, py))
    delta = math.atan2(py - by, px - bx) - math.atan2(cy - by, cx - bx)
    side = (dx - bx) * (cy - by) - (dy - by) * (cx - bx)
    start = math.atan2(by - ay, bx - ax)
    total = 0.0
    for t2, (tx, ty) in zip(PG_TIMING, PG_TARGETS):
        t = start + t2 - PG_TIMING[0]
        qx, qy = ax + l2 * math.cos(t), ay + l2 * math.sin(t)
        n, x1, y1, x2, y2 = circle_intersect(qx, qy, l3, dx, dy, l4)
        if n == 0 or n == 3:
            return PENALTY
        c1 = (dx - qx) * (y1 - qy) - (dy - qy) * (x1 - qx)
        rx, ry = (x1, y1) if (c1 > 0.0) == (side > 0.0) or n == 1 else (x2, y2)
        theta3 = math.atan2(ry - qy, rx - qx)
        gx, gy = qx + p * math.cos(theta3 + delta), qy + p * math.sin(theta3 + delta)
        total += (gx - tx) ** 2 + (gy - ty) ** 2
    return math.sqrt(total / len(PG_TIMING))


def classical_path_generation():
    seconds, result = best_time(
        lambda: path_generation_with_timing(PG_TARGETS, PG_TIMING, require_grashof=False), 3)
    errors = [solution_path_error(s) for s in result.raw_solutions]
    print(f"pg_classical_seconds {seconds:.4e}")
    print(f"pg_classical_solutions {len(errors)}")
    print(f"pg_classical_error {min(errors, default=math.inf):.4e}")


def tolerance():
    """Monte Carlo with pylinkage's kinematics: every length off by a uniform error within
    +-t (the largest deviation approaches the worst case) and by a normal error of standard
    deviation t/3 (3 x the rms deviation estimates the root-sum-square stack-up)."""
    def state(l1, l2, l3, l4, p):
        ax, ay = l2 * math.cos(TOL_THETA2), l2 * math.sin(TOL_THETA2)
        b = rocker_pin(ax, ay, l3, l1, 0.0, l4)
        theta3 = math.atan2(b[1] - ay, b[0] - ax)
        return (math.atan2(b[1], b[0] - l1),
                ax + p * math.cos(theta3 + P_ANGLE), ay + p * math.sin(theta3 + P_ANGLE))

    nominal = state(L1, L2, L3, L4, P_DISTANCE)
    dims = np.array([L1, L2, L3, L4, P_DISTANCE])

    def run(errors):
        out = np.empty((len(errors), 2))
        for k, e in enumerate(errors):
            t4, px, py = state(*(dims + e))
            out[k] = abs(t4 - nominal[0]), math.hypot(px - nominal[1], py - nominal[2])
        return out

    rng = np.random.default_rng(1)
    for samples in (1000, 10000, 100000):
        start = time.perf_counter()
        uniform = run(rng.uniform(-TOL_LENGTH, TOL_LENGTH, (samples, 5)))
        normal = run(rng.normal(0.0, TOL_LENGTH / 3.0, (samples, 5)))
        seconds = (time.perf_counter() - start) / 2.0
        print(f"mc{samples}_seconds {seconds:.4e}")
        print(f"mc{samples}_output_largest_uniform {uniform[:, 0].max():.6e}")
        print(f"mc{samples}_point_largest_uniform {uniform[:, 1].max():.6e}")
        print(f"mc{samples}_output_3rms_normal {3.0 * math.sqrt((normal[:, 0] ** 2).mean()):.6e}")
        print(f"mc{samples}_point_3rms_normal {3.0 * math.sqrt((normal[:, 1] ** 2).mean()):.6e}")


def main():
    versions = " ".join(f"{p} {importlib.metadata.version(p)}"
                        for p in ("pylinkage", "numba", "scipy", "numpy"))
    print(f"versions {versions} Python {sys.version.split()[0]}")
    # Compile circle_intersect before any clock starts.
    circle_intersect(0.0, 0.0, 1.0, 1.0, 0.0, 1.0)
    exact = fg_error((L2, L3, L4))
    print(f"fg_error_of_exact_answer {exact:.4e}")
    print(f"pg_error_of_exact_answer {pg_error((0, 0, 0, L1, L2, L3, L4, P_DISTANCE, P_ANGLE)):.4e}")
    print(f"budget_seconds {BUDGET}")
    print(f"cap_seconds {CAP}")
    print(f"runs {RUNS}")
    print(f"fg_threshold {FG_THRESHOLD}")
    print(f"pg_threshold {PG_THRESHOLD}")
    classical_function_generation()
    fg_bounds = ([1.0] * 3, [500.0] * 3)
    for name in ("pso", "de"):
        optimise(name, "fg", fg_error, FG_THRESHOLD, fg_bounds)
    classical_path_generation()
    pg_bounds = ([-300.0, -300.0, -math.pi, 1.0, 1.0, 1.0, 1.0, 1.0, -math.pi],
                 [300.0, 300.0, math.pi, 500.0, 500.0, 500.0, 500.0, 500.0, math.pi])
    for name in ("pso", "de"):
        optimise(name, "pg", pg_error, PG_THRESHOLD, pg_bounds)
    tolerance()


if __name__ == "__main__":
    main()
