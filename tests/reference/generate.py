#!/usr/bin/env python3
"""Reference values for mechgen's accuracy tests, computed independently at 60 significant
digits with mpmath.

Run from the repository root:
    python3 tests/reference/generate.py > tests/reference/cases.csv
    python3 tests/reference/generate.py sweeps > tests/reference/sweeps.csv
The second is the benchmarks' sweep (360 angles, one degree apart, omega2 = 10, alpha2 = 2,
open branch) for the performance report's accuracy column.

Every position comes from a closed form written here (circle-circle, line-circle,
length-and-angle), every rate from the velocity and acceleration relations of KINEMATICS.md
solved as 2x2 systems in high precision: none of it shares code with the Rust generator.
Parameters and inputs are first rounded to the precision under test (f64 or f32), and the
references are computed at those exactly representable values, so the comparison measures
only the Rust code's own error.
"""
import csv
import struct
import sys

import mpmath as mp

mp.mp.dps = 60
OMEGA2 = mp.mpf(1)
ALPHA2 = mp.mpf("0.5")
DELTAS = ["1e-3", "1e-6", "1e-9", "1e-12"]


def rounded(x, precision):
    """x rounded to the nearest f64 or f32, returned exactly as an mpf."""
    value = float(x)
    if precision == "f32":
        value = struct.unpack("f", struct.pack("f", value))[0]
    return mp.mpf(value)


def solve2(a, b):
    det = a[0][0] * a[1][1] - a[0][1] * a[1][0]
    return [(b[0] * a[1][1] - a[0][1] * b[1]) / det, (a[0][0] * b[1] - b[0] * a[1][0]) / det]


def columns(j):
    """The Jacobian's column norms, one per unknown."""
    return [mp.sqrt(j[0][0] ** 2 + j[1][0] ** 2), mp.sqrt(j[0][1] ** 2 + j[1][1] ** 2)]


def condition(j):
    """kappa = product of column norms over |det|, as mechgen defines it; then the norms."""
    det = j[0][0] * j[1][1] - j[0][1] * j[1][0]
    c1, c2 = columns(j)
    return [c1 * c2 / abs(det) if det != 0 else mp.inf, c1, c2]


def four_bar(p, t2, branch):
    l1, l2, l3, l4 = p
    ax, ay = l2 * mp.cos(t2), l2 * mp.sin(t2)
    dx, dy = l1 - ax, -ay
    z = mp.sqrt(dx * dx + dy * dy)
    along = (l3 * l3 - l4 * l4 + z * z) / (2 * z)
    h2 = l3 * l3 - along * along
    if h2 < 0:
        return None
    h = branch * mp.sqrt(h2)
    ux, uy = dx / z, dy / z
    bx, by = ax + along * ux - h * uy, ay + along * uy + h * ux
    t3, t4 = mp.atan2(by - ay, bx - ax), mp.atan2(by, bx - l1)
    j = [[-l3 * mp.sin(t3), l4 * mp.sin(t4)], [l3 * mp.cos(t3), -l4 * mp.cos(t4)]]
    if j[0][0] * j[1][1] - j[0][1] * j[1][0] == 0:
        return [t3, t4, None, None, None, None] + condition(j)
    # Velocity: J (w3, w4) = -(df/dt2) w2; acceleration from KINEMATICS.md's C, D, E, F.
    w3, w4 = solve2(j, [l2 * mp.sin(t2) * OMEGA2, -l2 * mp.cos(t2) * OMEGA2])
    a_, b_ = l4 * mp.sin(t4), l3 * mp.sin(t3)
    c_ = (l2 * ALPHA2 * mp.sin(t2) + l2 * OMEGA2**2 * mp.cos(t2) + l3 * w3**2 * mp.cos(t3)
          - l4 * w4**2 * mp.cos(t4))
    d_, e_ = l4 * mp.cos(t4), l3 * mp.cos(t3)
    f_ = (l2 * ALPHA2 * mp.cos(t2) - l2 * OMEGA2**2 * mp.sin(t2) - l3 * w3**2 * mp.sin(t3)
          + l4 * w4**2 * mp.sin(t4))
    den = a_ * e_ - b_ * d_
    a3, a4 = (c_ * d_ - a_ * f_) / den, (c_ * e_ - b_ * f_) / den
    return [t3, t4, w3, w4, a3, a4] + condition(j)


def slider_crank(p, t2, branch):
    l2, l3, c = p
    s = (c - l2 * mp.sin(t2)) / l3
    if abs(s) > 1:
        return None
    co = branch * mp.sqrt(1 - s * s)
    t3 = mp.atan2(s, co)
    d = l2 * mp.cos(t2) + l3 * co
    j = [[-l3 * mp.sin(t3), -1], [l3 * mp.cos(t3), 0]]
    w3 = -l2 * OMEGA2 * mp.cos(t2) / (l3 * mp.cos(t3))
    dd = -l2 * OMEGA2 * mp.sin(t2) - l3 * w3 * mp.sin(t3)
    a3 = (l2 * OMEGA2**2 * mp.sin(t2) - l2 * ALPHA2 * mp.cos(t2) + l3 * w3**2 * mp.sin(t3)) / (l3 * mp.cos(t3))
    ddd = (-l2 * ALPHA2 * mp.sin(t2) - l2 * OMEGA2**2 * mp.cos(t2) - l3 * a3 * mp.sin(t3)
           - l3 * w3**2 * mp.cos(t3))
    return [t3, d, w3, dd, a3, ddd] + condition(j)


def inverted(p, t2, branch):
    l1, l2, c, g = p
    r = mp.mpc(l2 * mp.cos(t2) - l1, l2 * mp.sin(t2))
    disc = abs(r) ** 2 - (c * mp.sin(g)) ** 2
    if disc < 0:
        return None
    b = -c * mp.cos(g) + branch * mp.sqrt(disc)
    w = b * mp.expj(g) + c
    t4 = mp.arg(r) - mp.arg(w)
    u = mp.expj(t4)
    e_g = mp.expj(g)
    j1 = 1j

    def split(rhs, first, second):
        """Real x, y with x*first + y*second = rhs (complex)."""
        a = [[first.real, second.real], [first.imag, second.imag]]
        return solve2(a, [rhs.real, rhs.imag])

    # A - O4 = e^{i t4} (b e^{i g} + c), differentiated once and twice.
    rhs_v = j1 * l2 * OMEGA2 * mp.expj(t2) / u
    bd, w4 = split(rhs_v, e_g, j1 * w)
    rhs_a = ((-l2 * OMEGA2**2 + j1 * l2 * ALPHA2) * mp.expj(t2) / u
             - 2 * j1 * w4 * bd * e_g + w4**2 * w)
    bdd, a4 = split(rhs_a, e_g, j1 * w)
    # The generated Jacobian with respect to (t4, b), for the condition estimate.
    d_t4 = -(j1 * u * w)
    d_b = -(u * e_g)
    jac = [[d_t4.real, d_b.real], [d_t4.imag, d_b.imag]]
    return [t4, b, w4, bd, a4, bdd] + condition(jac)


def four_bar_limit(p):
    l1, l2, l3, l4 = p
    return mp.acos((l1 * l1 + l2 * l2 - (l3 + l4) ** 2) / (2 * l1 * l2))


def four_bar_dead_centre(p):
    """The crank angle where crank and coupler line up extended (open branch)."""
    l1, l2, l3, l4 = p
    cos4 = ((l3 + l2) ** 2 - l1 * l1 - l4 * l4) / (2 * l1 * l4)
    t4 = mp.acos(cos4)
    return mp.atan2(l4 * mp.sin(t4), l1 + l4 * mp.cos(t4))


def cases():
    """(mechanism, case, params, inputs as (input, delta), solver)."""
    out = []
    ng = ["100", "120", "90", "80"]
    limit = four_bar_limit([mp.mpf(x) for x in ng])
    out.append(("four_bar", "non-Grashof limit", ng, [(limit - mp.mpf(d), d) for d in DELTAS]))
    cr = ["180", "80", "200", "150"]
    dead = four_bar_dead_centre([mp.mpf(x) for x in cr])
    out.append(("four_bar", "crank-rocker dead centre", cr,
                [(dead + s * mp.mpf(d), d) for d in DELTAS for s in (-1, 1)]))
    out.append(("four_bar", "change point flat", ["150", "100", "200", "250"],
                [(mp.mpf(d), d) for d in DELTAS] + [(mp.mpf(0), "0")]))
    out.append(("four_bar", "parallelogram flat", ["100", "50", "100", "50"],
                [(mp.mpf(d), d) for d in DELTAS] + [(mp.mpf(0), "0")]))
    out.append(("four_bar", "kite flat", ["100", "50", "50", "100"],
                [(mp.pi - mp.mpf(d), d) for d in DELTAS] + [(mp.pi, "0")]))
    for name, scale in [("tiny (1e-6)", "1e-6"), ("huge (1e6)", "1e6")]:
        params = [str(mp.mpf(x) * mp.mpf(scale)) for x in cr]
        out.append(("four_bar", f"Example 1 scaled {name}", params, [(mp.pi / 3, "none")]))
    out.append(("four_bar", "link ratio 1e6", ["1e6", "1", "1e6", "1e6"], [(mp.mpf(1), "none")]))
    sc = ["50", "150", "20"]
    outer = mp.asin(mp.mpf(20) / 200)
    out.append(("slider_crank", "dead centre", sc,
                [(outer + s * mp.mpf(d), d) for d in DELTAS for s in (-1, 1)]))
    short = ["50", "60", "20"]
    toggle = -mp.asin(mp.mpf(40) / 50)
    out.append(("slider_crank", "rod across the slide (toggle)", short,
                [(toggle + mp.mpf(d), d) for d in DELTAS]))
    out.append(("inverted_slider_crank", "short slide", ["100", "99", "0", "0"],
                [(mp.mpf(d), d) for d in DELTAS]))
    out.append(("inverted_slider_crank", "slide near zero", ["100", "99.999999", "0", "0"],
                [(mp.mpf(d), d) for d in DELTAS]))
    out.append(("inverted_slider_crank", "offset and angle", ["150", "60", "20", "0.3"],
                [(mp.mpf(1), "none")]))
    return out


SOLVERS = {"four_bar": four_bar, "slider_crank": slider_crank, "inverted_slider_crank": inverted}


def main():
    writer = csv.writer(sys.stdout, lineterminator="\n")
    writer.writerow(["mechanism", "case", "precision", "branch", "params", "input", "delta",
                     "status", "q1", "q2", "q1_dot", "q2_dot", "q1_ddot", "q2_ddot", "condition",
                     "column1", "column2"])
    for mechanism, case, params, inputs in cases():
        for precision in ["f64", "f32"]:
            p = [rounded(mp.mpf(x), precision) for x in params]
            for raw_input, delta in inputs:
                t2 = rounded(raw_input, precision)
                for branch in (1, -1):
                    result = SOLVERS[mechanism](p, t2, branch)
                    row = [mechanism, case, precision, "open" if branch == 1 else "crossed",
                           " ".join(repr(float(x)) for x in p), repr(float(t2)), delta]
                    if result is None:
                        row += ["cannot"] + [""] * 9
                    else:
                        # A singular position has no rates.
                        status = "singular" if result[2] is None else "ok"
                        row += [status] + [
                            "" if x is None else mp.nstr(x, 25, min_fixed=1, max_fixed=0)
                            for x in result
                        ]
                    writer.writerow(row)


def sweeps():
    global OMEGA2, ALPHA2
    OMEGA2, ALPHA2 = mp.mpf(10), mp.mpf(2)
    writer = csv.writer(sys.stdout, lineterminator="\n")
    writer.writerow(["mechanism", "degree", "input", "q1", "q2", "q1_dot", "q2_dot", "q1_ddot",
                     "q2_ddot"])
    mechanisms = [
        ("four_bar", ["180", "80", "200", "150"]),
        ("slider_crank", ["50", "150", "20"]),
        ("inverted_slider_crank", ["150", "60", "20", "0.3"]),
    ]
    for mechanism, params in mechanisms:
        p = [rounded(mp.mpf(x), "f64") for x in params]
        for degree in range(360):
            t2 = rounded(mp.radians(degree), "f64")
            result = SOLVERS[mechanism](p, t2, 1)
            writer.writerow([mechanism, degree, repr(float(t2))]
                            + [mp.nstr(x, 25) for x in result[:6]])


if __name__ == "__main__":
    if sys.argv[1:] == ["sweeps"]:
        sweeps()
    else:
        main()
