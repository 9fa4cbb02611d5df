#!/usr/bin/python3
r"""Independent high-precision reference values for partial areas and volumes.

What it computes
----------------
The measure of the intersection of a closed ball (a disc in 2D) of radius R
centred at c with an axis-aligned box: an area in 2D, a volume in 3D. These
are the reference values for the closed-form C++ kernel
PeriDEAL::Quadrature::ball_box_intersection_measure and for the uniform-grid
coefficients beta of the partial-volume algorithms.

Method (deliberately naive, no closed-form area or volume formula)
-----------------------------------------------------------------
Translate so that the ball centre is the origin (exactly: the differences of
the input doubles are formed without rounding) and clip the box to
[-R, R]^dim. Then

  2D:  A = int_{x1}^{x2} L(x) dx,
       L(x) = max(0, min(y2, s) - max(y1, -s)),   s = sqrt(max(R^2 - x^2, 0)),

  3D:  V = int_{x1}^{x2} int_{y1}^{y2} L(x, y) dy dx,
       L(x, y) = max(0, min(z2, s) - max(z1, -s)), s = sqrt(max(R^2-x^2-y^2, 0)),

i.e. the length of the chord of the ball inside [z1, z2] (so boxes that
straddle z = 0 or lie below the centre are handled), integrated by nested
one-dimensional adaptive tanh-sinh quadrature (mpmath.quad). Both
integrands are only piecewise smooth, and tanh-sinh converges exponentially
only if every kink and every square-root edge singularity is an endpoint of
an integration interval, so the ranges are split at:

  * chord integral over t in (t1, t2) with s = sqrt(c - t^2) (the 2D area,
    and the inner y-integral in 3D with c = R^2 - x^2): t = 0, t = +-sqrt(c)
    (edge of the disc), t = +-sqrt(c - lo^2) and t = +-sqrt(c - hi^2) (where
    s = |lo| or s = |hi|, i.e. where the chord starts to be clipped by the
    box), lo, hi being the box limits in the chord direction;
  * outer x-integral in 3D: x = 0, x = +-R, and x = +-sqrt(R^2 - y_k^2 - z_l^2)
    for y_k in {y1, y2, 0 if y1 <= 0 <= y2}, z_l in {z1, z2, 0 if
    z1 <= 0 <= z2}: the abscissae where the inner breakpoints collide with
    each other or with the box faces, where the inner integral has
    algebraic singularities of type |x - x_k|^(1/2) or ^(3/2).

Between two consecutive breakpoints the chord length is alpha*s + beta with
alpha in {0, 1, 2} and a constant beta (which of min/max is active is read off
at the midpoint of the piece), so the chord integral over a piece is
alpha * (tanh-sinh quadrature of sqrt(c - t^2)) + beta * (piece length): only
the square root is integrated numerically, every evaluation is a plain
sqrt, and constant pieces need no quadrature at all.

Nearby singularities: tanh-sinh also loses digits (up to ~7 of 30, found in
testing) when a singularity of the analytic continuation of a piece lies
just outside it, at 1e-16 .. 1e-1 interval lengths from an endpoint
(clustered breakpoints: flat boxes, thin slabs, near-tangent cases), and
mpmath's error estimate does not notice. So every interval is also refined
geometrically (ratio 16) towards such singularities: t = +-sqrt(c) for the
chord integral, x = +-sqrt(R^2 - y^2 - z^2) for y in {y1, y2, 0},
z in {z1, z2, 0} (real or imaginary) for the outer 3D integral; see
_graded().

Error estimate
--------------
Every value is computed twice:
  * the reference value: working precision --dps (default 30 digits), axes
    in the order (x, y, z) (outer, inner, chord);
  * the check: precision --check-dps (default 34 digits), axes cyclically
    permuted, (y, z, x) in 3D and (y, x) in 2D: different breakpoints,
    different quadrature nodes, different rounding.
The check is far more accurate than the reference value, so |value - check|
is an estimate of the error of the value actually written. The summary prints
the maximum absolute and relative discrepancy per file and the largest error
estimate that mpmath.quad itself reported; a case whose quad error estimate
is not small is retried with a higher maximum degree. The target is an
absolute error below 1e-20 for every value (the script fails otherwise).

Before generating, the method is checked against known values (assertions):
the full ball/disc from a box containing it, an octant pi R^3/6, a quarter of
a spherical cap pi h^2 (3R - h)/12, a disc quadrant pi R^2/4, a half disc,
and additivity (a box split at the coordinate planes through the centre into
8 (4) pieces).

Inputs
------
All inputs are IEEE doubles (Python floats); the value of each input is the
exact double (mpf(float) is exact), and inputs are written with repr(), the
shortest string that round-trips, so strtod in C++ recovers the same double.
Random cases come from random.Random with fixed seeds, so the output is
deterministic (for a given Python 3 version; made with CPython 3.11).

Files (see README.md): beta_3d.csv, beta_2d.csv, beta_3d_large_m.csv,
boxes_3d.csv, boxes_2d.csv. Values are written with 25 significant digits.

Running
-------
  /usr/bin/python3 generate_reference.py            # full run, ~20-30 min, 1 core
  /usr/bin/python3 generate_reference.py --quick    # smoke run, ~1 min; writes
                                                    # to a temporary directory
  /usr/bin/python3 generate_reference.py --outdir D # write elsewhere

Needs mpmath (Debian: python3-mpmath; made with mpmath 1.2.1).
"""

import argparse
import itertools
import math
import os
import random
import sys
import tempfile
import time
from fractions import Fraction

import mpmath
from mpmath import mp, mpf
from mpmath.libmp import (mpf_add, mpf_mul, mpf_shift, mpf_sqrt, mpf_sub,
                          round_nearest)

SIG_DIGITS = 25          # significant digits written for values
TARGET_ABS_ERROR = 1e-20  # required: |value - check| below this for every row

GRADING_FACTOR = 16
OUTER_MIN_RATIO = mpf(10) ** -20
INNER_MIN_RATIO = mpf(10) ** -8

M_LIST = [0.3, 0.5, 0.75, 1.0, 1.25, 1.5, 2.0, 2.5, 3.0, 3.05, 3.25, 3.5,
          4.0, 4.5, 5.0, 5.5, 6.0, 7.3, 9.95, 10.0, 10.5]
M_LIST_2D = M_LIST + [20.0, 50.0]
M_LARGE = [20.0, 35.5, 50.0]


# --------------------------------------------------------------------------
# Quadrature
# --------------------------------------------------------------------------
class Stats:
    """Largest error estimate reported by mpmath.quad, number of retries."""

    def __init__(self):
        self.max_quad_err = mpf(0)
        self.retries = 0


def _quad(f, points, stats):
    """mpmath.quad (tanh-sinh) over consecutive intervals of points, with a
    retry at higher degree if the reported error estimate is not small."""
    v, err = mp.quad(f, points, error=True)
    tol = mpf(10) ** (-(mp.dps - 4)) * max(1, abs(v))
    if err > tol:
        stats.retries += 1
        v, err = mp.quad(f, points, error=True, maxdegree=10)
    if err > stats.max_quad_err:
        stats.max_quad_err = err
    return v


def _split_points(lo, hi, candidates):
    """lo, hi and +-p for p in candidates that lie strictly inside (lo, hi),
    sorted."""
    pts = {lo, hi}
    for p in candidates:
        for q in (p, -p):
            if lo < q < hi:
                pts.add(q)
    return sorted(pts)


def _graded(points, sing, min_ratio):
    """Refine consecutive intervals of points geometrically towards nearby
    singularities outside them. sing: singular points of the integrand's
    analytic pieces, as (re, im) pairs. If one lies at distance delta from
    an endpoint e of [a, b] with min_ratio < delta/(b - a) < 1/factor, the
    points e +- delta factor^j (inward, j = 0, 1, ... while below (b - a)/2)
    are added, so that no sub-interval is more than factor times longer
    than its distance to the singularity. tanh-sinh then keeps its full
    rate; without this a singularity at 1e-16 .. 1e-1 interval lengths
    beyond an endpoint costs up to ~7 digits, and mpmath's error estimate
    (which extrapolates assuming the full rate) does not notice. Much closer
    singularities act like endpoint singularities and need nothing."""
    out = [points[0]]
    for a, b in zip(points[:-1], points[1:]):
        L = b - a
        lo_d = L * min_ratio
        extra = []
        for e, inward in ((a, 1), (b, -1)):
            delta = None
            for re, im in sing:
                if im == 0 and (re - e) * inward > 0:
                    continue  # on the far side of e (or inside [a, b])
                d = mp.hypot(re - e, im)
                if d <= lo_d:
                    continue  # (practically) the endpoint's own singularity
                if delta is None or d < delta:
                    delta = d
            if delta is None:
                continue
            while delta * GRADING_FACTOR < L:
                extra.append(e + inward * delta)
                delta *= GRADING_FACTOR
        out += sorted(extra)
        out.append(b)
    return out


def _singular_points(values):
    """+-sqrt(d) for d in values as (re, im) pairs (imaginary for d < 0)."""
    sing = []
    for d in values:
        if d >= 0:
            r = mp.sqrt(d)
            sing += [(r, 0), (-r, 0)]
        else:
            sing.append((mpf(0), mp.sqrt(-d)))
    return sing


def chord_integral(c, t1, t2, lo, hi, stats, min_ratio=None):
    r"""\int_{t1}^{t2} max(0, min(hi, s) - max(lo, -s)) dt, s = sqrt(c - t^2)
    (s = 0 where c < t^2): the area of the disc of radius sqrt(c) in the
    rectangle [t1, t2] x [lo, hi]. All arguments are mpf, t1 < t2, lo < hi."""
    zero = mpf(0)
    if c <= 0:
        return zero
    cands = [zero, mp.sqrt(c)]
    for b in (lo, hi):
        d = c - b * b
        if d > 0:
            cands.append(mp.sqrt(d))
    pts = _split_points(t1, t2, cands)
    sing = _singular_points([c])
    if min_ratio is None:
        min_ratio = OUTER_MIN_RATIO

    c_raw = c._mpf_
    make = mp.make_mpf

    def s_of(t):
        # sqrt(max(c - t^2, 0)) on raw mpmath numbers (the hot spot): t^2
        # exact, one rounding in the difference, one in the square root
        prec = mp.prec
        t_raw = t._mpf_
        d = mpf_sub(c_raw, mpf_mul(t_raw, t_raw), prec, round_nearest)
        if d[0] or not d[1]:  # negative or zero
            return zero
        return make(mpf_sqrt(d, prec, round_nearest))

    total = []
    for a, b in zip(pts[:-1], pts[1:]):
        # no kink inside (a, b): chord length = alpha*s + beta there
        sm = s_of((a + b) / 2)
        alpha, beta = 0, zero
        if sm >= hi:
            beta += hi
        else:
            alpha += 1
        if -sm <= lo:
            beta -= lo
        else:
            alpha += 1
        if alpha * sm + beta <= 0:
            continue  # chord misses [lo, hi] on the whole piece
        if alpha == 0:
            piece = beta * (b - a)
        else:
            # alpha*s + beta is integrated as one function (evaluated at
            # quad's raised precision): splitting it into alpha*int(s) +
            # beta*(b - a) would cancel catastrophically for thin chords
            # (s ~ -beta), e.g. tiny boxes on the sphere.
            beta_raw = beta._mpf_

            def chord(t, alpha=alpha, beta_raw=beta_raw):
                v = s_of(t)._mpf_
                if alpha == 2:
                    v = mpf_shift(v, 1)
                return make(mpf_add(v, beta_raw, mp.prec, round_nearest))

            # sqrt(c - t^2) is singular only at t = +-sqrt(c)
            piece = _quad(chord, _graded([a, b], sing, min_ratio), stats)
        total.append(piece)
    return mp.fsum(total)


def area_centred(R, x1, x2, y1, y2, stats):
    """Area of disc(0, R) cap [x1,x2]x[y1,y2]; mpf arguments."""
    x1, x2 = max(x1, -R), min(x2, R)
    y1, y2 = max(y1, -R), min(y2, R)
    if x1 >= x2 or y1 >= y2:
        return mpf(0)
    return chord_integral(mp.fmul(R, R, exact=True), x1, x2, y1, y2, stats)


def volume_centred(R, x1, x2, y1, y2, z1, z2, stats):
    """Volume of ball(0, R) cap [x1,x2]x[y1,y2]x[z1,z2]; mpf arguments."""
    zero = mpf(0)
    x1, x2 = max(x1, -R), min(x2, R)
    y1, y2 = max(y1, -R), min(y2, R)
    z1, z2 = max(z1, -R), min(z2, R)
    if x1 >= x2 or y1 >= y2 or z1 >= z2:
        return zero
    R2 = mp.fmul(R, R, exact=True)

    def inner(x):
        # inner grading only for singularities farther than 1e-8 piece
        # lengths: closer ones occur only at outer nodes within ~1e-8 of an
        # outer breakpoint, whose weights make the error negligible
        return chord_integral(R2 - x * x, y1, y2, z1, z2, stats,
                              INNER_MIN_RATIO)

    ys = [y1, y2] + ([zero] if y1 <= 0 <= y2 else [])
    zs = [z1, z2] + ([zero] if z1 <= 0 <= z2 else [])
    cands = [zero, R]
    for y in ys:
        for z in zs:
            d = R2 - y * y - z * z
            if d > 0:
                cands.append(mp.sqrt(d))
    # The analytic pieces of the inner integral are singular at
    # x^2 = R^2 - y^2 - z^2 for y in {y1, y2, 0}, z in {z1, z2, 0} (whether
    # or not 0 is in the box): real or imaginary points, used for grading.
    sing = _singular_points([R2 - y * y - z * z for y in (y1, y2, zero)
                             for z in (z1, z2, zero)])
    pts = _graded(_split_points(x1, x2, cands), sing, OUTER_MIN_RATIO)
    return _quad(inner, pts, stats)


def measure(centre, R, box, dps, order, stats):
    """Measure of ball(centre, R) cap box, box = [(lo, hi)] per axis, all
    Python floats, computed at dps digits with the axes taken in the given
    order (outer, ..., chord direction)."""
    dim = len(centre)
    with mp.workdps(dps):
        # exact differences of the doubles (mpf(float) is exact)
        lims = [(mp.fsub(mpf(box[i][0]), mpf(centre[i]), exact=True),
                 mp.fsub(mpf(box[i][1]), mpf(centre[i]), exact=True))
                for i in range(dim)]
        args = []
        for i in order:
            args += [+lims[i][0], +lims[i][1]]  # unary + rounds to dps
        Rm = mpf(R)
        if dim == 2:
            v = area_centred(Rm, *args, stats)
        else:
            v = volume_centred(Rm, *args, stats)
    return v


ORDERS = {2: ((0, 1), (1, 0)), 3: ((0, 1, 2), (1, 2, 0))}


class Reference:
    """Computes values with their check and collects discrepancies."""

    def __init__(self, dps, check_dps):
        self.dps, self.check_dps = dps, check_dps
        self.reset()

    def reset(self):
        self.stats = Stats()
        self.max_abs = mpf(0)
        self.max_rel = mpf(0)
        self.worst = None
        self.n = 0

    def __call__(self, centre, R, box):
        dim = len(centre)
        v = measure(centre, R, box, self.dps, ORDERS[dim][0], self.stats)
        w = measure(centre, R, box, self.check_dps, ORDERS[dim][1],
                    self.stats)
        with mp.workdps(self.check_dps + 10):
            d = abs(v - w)
            if d > self.max_abs:
                self.max_abs, self.worst = d, (centre, R, box)
            if w != 0 and d / abs(w) > self.max_rel:
                self.max_rel = d / abs(w)
        self.n += 1
        return v


# --------------------------------------------------------------------------
# Formatting and exact classification
# --------------------------------------------------------------------------
def fmt(v):
    """A value with SIG_DIGITS significant digits, readable by strtod."""
    if v == 0:
        return "0"
    return mp.nstr(v, SIG_DIGITS, strip_zeros=False)


def rin(x):
    """Input double -> shortest round-trip string."""
    return repr(float(x))


def classify(centre, R, box):
    """Exact (rational) classification: 0 if the nearest point of the box is
    at distance >= R (measure zero), 1 if its farthest point is within the
    closed ball (box inside), 2 otherwise (partial)."""
    R2 = Fraction(R) ** 2
    near = far = Fraction(0)
    for c, (lo, hi) in zip(centre, box):
        c, lo, hi = Fraction(c), Fraction(lo), Fraction(hi)
        dn = max(lo - c, c - hi, Fraction(0))
        df = max(abs(lo - c), abs(hi - c))
        near += dn * dn
        far += df * df
    if near >= R2:
        return 0
    if far <= R2:
        return 1
    return 2


def unit_cell(offset):
    return [(o - 0.5, o + 0.5) for o in offset]


# --------------------------------------------------------------------------
# Sanity checks against known values
# --------------------------------------------------------------------------
def sanity_checks(ref):
    pi = mp.pi
    checks = []
    st = Stats()

    def m(centre, R, box):
        return measure(centre, R, box, ref.dps, ORDERS[len(centre)][0], st)

    with mp.workdps(ref.dps + 10):
        R = 1.25
        c = (0.375, -0.5, 0.25)
        checks.append(("full ball", m(c, R, [(-5.0, 5.0)] * 3),
                       4 * pi * mpf(R) ** 3 / 3))
        checks.append(("full ball, tangent cube [-R,R]^3",
                       m((0.0, 0.0, 0.0), 3.05, [(-3.05, 3.05)] * 3),
                       4 * pi * mpf(3.05) ** 3 / 3))
        R = 1.7
        checks.append(("octant", m((0.0, 0.0, 0.0), R, [(0.0, 4.0)] * 3),
                       pi * mpf(R) ** 3 / 6))
        checks.append(("octant below centre",
                       m((0.0, 0.0, 0.0), R, [(-4.0, 0.0)] * 3),
                       pi * mpf(R) ** 3 / 6))
        R, h = 2.0, 0.75
        checks.append(("quarter spherical cap",
                       m((0.0, 0.0, 0.0), R,
                         [(0.0, R), (0.0, R), (R - h, R)]),
                       pi * mpf(h) ** 2 * (3 * mpf(R) - mpf(h)) / 12))
        checks.append(("quarter spherical cap (cap along x, below)",
                       m((0.0, 0.0, 0.0), R,
                         [(-R, -(R - h)), (-R, 0.0), (0.0, R)]),
                       pi * mpf(h) ** 2 * (3 * mpf(R) - mpf(h)) / 12))
        R = 3.05
        checks.append(("disc quadrant",
                       m((0.0, 0.0), R, [(0.0, 4.0), (0.0, 4.0)]),
                       pi * mpf(R) ** 2 / 4))
        checks.append(("half disc",
                       m((0.5, -0.25), R, [(-9.0, 9.0), (-0.25, 9.0)]),
                       pi * mpf(R) ** 2 / 2))
        checks.append(("full disc",
                       m((0.5, -0.25), R, [(-9.0, 9.0), (-9.0, 9.0)]),
                       pi * mpf(R) ** 2))
        # additivity: a box straddling the centre = sum of its 8 octant pieces
        c = (0.25, -0.5, 0.75)
        R = 2.6
        box = [(-1.0, 2.5), (-2.0, 0.5), (0.0, 3.0)]
        whole = m(c, R, box)
        parts = []
        for sx in (0, 1):
            for sy in (0, 1):
                for sz in (0, 1):
                    b = []
                    for i, s in enumerate((sx, sy, sz)):
                        b.append((box[i][0], c[i]) if s == 0
                                 else (c[i], box[i][1]))
                    parts.append(m(c, R, b))
        checks.append(("additivity over octants", whole, mp.fsum(parts)))
        c = (0.25, -0.5)
        box = [(-1.0, 2.5), (-2.0, 0.5)]
        whole = m(c, R, box)
        parts = [m(c, R, [(box[0][0], c[0]) if sx == 0 else (c[0], box[0][1]),
                          (box[1][0], c[1]) if sy == 0 else (c[1], box[1][1])])
                 for sx in (0, 1) for sy in (0, 1)]
        checks.append(("additivity over quadrants", whole, mp.fsum(parts)))
        print("Sanity checks (dps = %d):" % ref.dps)
        worst = mpf(0)
        for name, got, want in checks:
            d = abs(got - want)
            worst = max(worst, d)
            print("  %-45s error %s" % (name, mp.nstr(d, 3)))
            assert d < mpf(10) ** (-(ref.dps - 5)), (name, got, want)
    print("  all passed (max error %s)" % mp.nstr(worst, 3))
    sys.stdout.flush()


# --------------------------------------------------------------------------
# Data sets
# --------------------------------------------------------------------------
def wedge_cells(dim, m):
    """Wedge offsets 0 <= x <= y [<= z], last >= 1 with positive measure, in
    order (last, ..., first), with their exact class (1: inside, 2: partial)."""
    M = int(math.ceil(m)) + 1
    out = []
    if dim == 3:
        offs = [(x, y, z) for z in range(1, M + 1) for y in range(0, z + 1)
                for x in range(0, y + 1)]
    else:
        offs = [(x, y) for y in range(1, M + 1) for x in range(0, y + 1)]
    origin = (0.0,) * dim
    for o in offs:
        k = classify(origin, m, unit_cell(o))
        if k:
            out.append((o, k))
    return out


def grid_value(ref, dim, m, o, k):
    if k == 1:
        return "1"
    return fmt(ref((0.0,) * dim, m, unit_cell(o)))


def gen_beta(ref, dim, ms, quick):
    rows = []
    for m in ms:
        cells = wedge_cells(dim, m)
        if quick:
            if m not in (0.75, 3.05, 10.5, 50.0):
                continue
            cells = [c for c in cells if c[1] == 2][:1] + \
                [c for c in cells if c[1] == 1][:1]
        for o, k in cells:
            rows.append([rin(m)] + [str(c) for c in o] +
                        [grid_value(ref, dim, m, o, k)])
    return rows


def gen_beta_large(ref, quick):
    rows = []
    for m in M_LARGE:
        cells = [o for o, k in wedge_cells(3, m) if k == 2]
        rng = random.Random(1000 + int(10 * m))
        sample = set(rng.sample(cells, 150))
        # cells on the axis, face diagonal and body diagonal near the sphere
        lines = set(o for o in cells
                    if o[0] == o[1] == 0 or (o[0] == 0 and o[1] == o[2])
                    or o[0] == o[1] == o[2])
        chosen = sorted(sample | lines, key=lambda o: (o[2], o[1], o[0]))
        if quick:
            chosen = chosen[:1]
        for o in chosen:
            rows.append([rin(m)] + [str(c) for c in o] +
                        [fmt(ref((0.0, 0.0, 0.0), m, unit_cell(o)))])
    return rows


def _rand_dir(rng, dim):
    while True:
        v = [rng.gauss(0.0, 1.0) for _ in range(dim)]
        n = math.sqrt(sum(t * t for t in v))
        if n > 1e-3:
            return [t / n for t in v]


def _box_around(rng, p, sides):
    """Box with the given side lengths containing the point p (floats)."""
    box = []
    for pi_, L in zip(p, sides):
        lo = pi_ - L * rng.uniform(0.02, 0.98)
        box.append((lo, lo + L))
    return box


def _sqrt_double(x):
    """The double nearest sqrt(x) for an mpf/rational x."""
    with mp.workdps(50):
        return float(mp.sqrt(x))


def box_cases(dim):
    """The general-box cases: list of (category, centre, R, box)."""
    rng = random.Random(20240 + dim)
    cases = []
    O = (0.0,) * dim

    def add(cat, centre, R, box):
        box = [(float(a), float(b)) for a, b in box]
        cases.append((cat, tuple(float(c) for c in centre), float(R), box))

    big = dim == 2
    # 1. random boxes near the sphere, sides 1e-3 .. 10 relative to R
    for _ in range(110 if dim == 3 else 100):
        R = 10 ** rng.uniform(-1.0, 1.3)
        centre = [0.0] * dim if rng.random() < 0.3 else \
            [rng.uniform(-3, 3) for _ in range(dim)]
        u = _rand_dir(rng, dim)
        p = [c + R * t for c, t in zip(centre, u)]
        sides = [R * 10 ** rng.uniform(-3, 1) for _ in range(dim)]
        add("random_near_surface", centre, R, _box_around(rng, p, sides))
    # 2. a corner exactly on the sphere (integer Pythagorean tuples), box on
    #    every side of the corner; some with a dyadic (exact) centre shift
    if dim == 3:
        tuples = [((1, 2, 2), 3, 1.0), ((2, 3, 6), 7, 1.5),
                  ((4, 4, 7), 9, 2.5), ((1, 4, 8), 9, 0.5),
                  ((2, 6, 9), 11, 3.0)]
        shifts = [(0.0, 0.0, 0.0), (0.375, -1.25, 2.5)]
    else:
        tuples = [((3, 4), 5, 1.0), ((5, 12), 13, 2.5), ((8, 15), 17, 0.5),
                  ((20, 21), 29, 3.0), ((7, 24), 25, 1.5)]
        shifts = [(0.0, 0.0), (0.375, -1.25)]
    for ti, (corner, R, L) in enumerate(tuples):
        for si, shift in enumerate(shifts):
            signs = [1] * dim if (ti + si) % 2 == 0 else \
                [(-1) ** (i + ti) for i in range(dim)]
            cc = [s * a for s, a in zip(signs, corner)]
            # orientation: box extends + or - from the corner along each axis
            for orient in range(2 ** dim):
                if si == 1 and orient % 3 != 0:
                    continue
                box = []
                for i in range(dim):
                    a = shift[i] + cc[i]
                    box.append((a, a + L) if (orient >> i) & 1 else (a - L, a))
                add("corner_on_sphere", shift, R, box)
    # 3. tangent to the sphere: a face at distance exactly R, from outside
    #    and from inside, in every axis direction
    for R, centre in [(1.0, O), (2.5, O), (3.05, O),
                      (1.75, (0.5, -0.25, 0.125)[:dim])]:
        for axis in range(dim):
            for sgn in (1, -1):
                if R != 1.0 and (axis + (sgn > 0)) % 2:
                    continue  # half of the directions for the other radii
                face = centre[axis] + sgn * R
                for inside, (w, h) in [(False, (1.0, 0.5)), (True, (1.0, 0.5)),
                                       (True, (0.25, 0.1))]:
                    if (w, h) == (0.25, 0.1) and R in (2.5, 3.05):
                        continue
                    box = []
                    for i in range(dim):
                        if i == axis:
                            if inside == (sgn > 0):
                                box.append((face - w, face))
                            else:
                                box.append((face, face + w))
                        else:
                            box.append((centre[i] - h, centre[i] + 1.5 * h))
                    add("tangent_face_" + ("inside" if inside else "outside"),
                        centre, R, box)
    # 4. boxes straddling the centre and/or coordinate planes through it
    for i in range(24 if dim == 3 else 25):
        R = rng.uniform(0.5, 5.0)
        centre = [0.0] * dim if i % 3 == 0 else \
            [round(rng.uniform(-2, 2), 3) for _ in range(dim)]
        box = []
        for k in range(dim):
            if (i + k) % 4 != 3:    # straddles the plane through the centre
                box.append((centre[k] - R * rng.uniform(0.05, 1.5),
                            centre[k] + R * rng.uniform(0.05, 1.5)))
            else:                   # one side, possibly touching the plane
                a = centre[k] + (0.0 if i % 2 else R * rng.uniform(0, 0.8))
                box.append((a, a + R * rng.uniform(0.1, 1.2)))
        add("straddling_centre_planes", centre, R, box)
    # 5. boxes containing the whole ball
    for R, centre in [(1.0, O), (2.75, (0.37, -1.2, 3.5)[:dim]),
                      (7.3, (-0.5, 0.25, 0.125)[:dim])]:
        add("contains_ball", centre, R,
            [(c - R - 0.5, c + R + 1.25) for c in centre])
    # 6. very small boxes (sides 1e-6 .. 1e-3) straddling the sphere
    for _ in range(30 if dim == 3 else 25):
        R = rng.uniform(0.5, 5.0)
        centre = [round(rng.uniform(-1, 1), 2) for _ in range(dim)]
        u = _rand_dir(rng, dim)
        p = [c + R * t for c, t in zip(centre, u)]
        sides = [10 ** rng.uniform(-6, -3) for _ in range(dim)]
        add("tiny_box_on_sphere", centre, R, _box_around(rng, p, sides))
    # 7. very flat boxes: one side 1e-8 (straddling the surface, or inside)
    for i in range(20 if dim == 3 else 15):
        R = rng.uniform(0.5, 5.0)
        centre = [0.0] * dim if i % 2 else \
            [round(rng.uniform(-1, 1), 2) for _ in range(dim)]
        u = _rand_dir(rng, dim)
        r = R * (1.0 if i % 4 < 2 else rng.uniform(0.2, 0.9))
        p = [c + r * t for c, t in zip(centre, u)]
        sides = [R * rng.uniform(0.1, 1.5) for _ in range(dim)]
        sides[i % dim] = 1e-8
        add("flat_box", centre, R, _box_around(rng, p, sides))
    # 8. radius smaller than the box: R = 0.1 (and 0.3) in the unit box
    unit = [(0.0, 1.0)] * dim
    small_centres = [(0.37, 0.52, 0.61), (0.05, 0.5, 0.5), (0.05, 0.07, 0.5),
                     (0.03, 0.04, 0.06), (0.0, 0.5, 0.5), (0.0, 0.0, 0.0),
                     (0.0, 0.0, 0.37), (-0.1, 0.5, 0.5), (-0.06, 0.5, 0.5),
                     (1.05, 0.5, 0.5), (1.02, 0.97, 0.5), (0.9, 0.95, 0.99)]
    for c in small_centres:
        add("small_radius_in_unit_box", c[:dim], 0.1, unit)
    for c in [(0.21, 0.1, 0.8), (0.5, 0.5, 0.95), (0.8, 0.2, 0.25)]:
        add("small_radius_in_unit_box", c[:dim], 0.3, unit)
    # 9. large radius (up to 50), unit boxes near the surface
    for i in range(30 if dim == 3 else 30):
        R = [12.5, 20.0, 33.3, 50.0][i % 4]
        centre = [0.0] * dim if i % 3 else \
            [round(rng.uniform(-1, 1), 2) for _ in range(dim)]
        u = _rand_dir(rng, dim)
        p = [c + R * t for c, t in zip(centre, u)]
        if i % 2:   # grid-aligned unit cell containing p
            box = [(math.floor(t + 0.5) - 0.5, math.floor(t + 0.5) + 0.5)
                   for t in p]
        else:
            box = _box_around(rng, p, [1.0] * dim)
        if classify(centre, R, box) != 2:
            box = _box_around(rng, p, [1.0] * dim)
        add("large_radius_unit_box", centre, R, box)
    # 10. non-integer centre, unit cells of a grid around it
    for R, centre in [(3.05, (0.37, -0.21, 0.55)), (1.6, (0.37, 0.0, -0.5)),
                      (5.5, (-0.125, 0.3, 0.49))]:
        centre = centre[:dim]
        M = int(R) + 2
        rng_c = random.Random(int(100 * R))
        cells = []
        rngs = [range(-M, M + 1)] * dim
        for o in itertools.product(*rngs):
            if classify(centre, R, unit_cell(o)) == 2:
                cells.append(o)
        n = 7 if dim == 3 else 7
        for o in rng_c.sample(cells, n):
            add("noninteger_centre_unit_cell", centre, R, unit_cell(o))
    # 11. series blow-up on a uniform grid: unit cells centred at integer
    #     offsets, R = m with m^2 - x0^2 - k^2 = eps (x0 = midpoint of the
    #     x-interval, k a y-limit (and a z-limit)), eps in {0, 1e-8, 1e-4}
    blow = []
    # exact zero with two terms: (2 x0)^2 + a^2 = c^2 (a, c odd)
    for x0, k in [(2, 1.5), (6, 2.5), (4, 7.5), (12, 3.5), (10, 10.5)]:
        for eps in (0, 1e-8, 1e-4):
            target = Fraction(x0) ** 2 + Fraction(k) ** 2 + Fraction(eps)
            m = _sqrt_double(mpf(target.numerator) / target.denominator) \
                if eps else math.sqrt(float(target))
            if eps == 0:
                assert Fraction(m) ** 2 == target
            blow.append((m, x0, k, None))
    if dim == 3:
        # three terms: m^2 = x0^2 + k^2 + l^2 + eps (not exactly 0 possible
        # with half-integer limits; the nearest double)
        for x0, k, l in [(1, 1.5, 2.5), (3, 0.5, 1.5), (2, 3.5, 4.5)]:
            for eps in (0, 1e-8, 1e-4):
                target = Fraction(x0) ** 2 + Fraction(k) ** 2 + \
                    Fraction(l) ** 2 + Fraction(eps)
                m = _sqrt_double(mpf(target.numerator) / target.denominator)
                blow.append((m, x0, k, l))
    for m, x0, k, l in blow:
        sel = []
        # k as the upper and as the lower y-limit of the cell (and, 2 terms
        # in 3D, as a z-limit instead)
        for ky in (k - 0.5, k + 0.5):
            if l is None:
                sel.append((x0, int(ky)) + ((0,) if dim == 3 else ()))
                if dim == 3:
                    sel.append((x0, 0, int(ky)))
            else:
                kz = l - 0.5 if ky < k else l + 0.5
                sel.append((x0, int(ky), int(kz)))
        for o in sel:
            box = unit_cell(o)
            if classify(O, m, box) == 2:
                add("series_blowup_m2-x0^2-k^2", O, m, box)
    return cases


def gen_boxes(ref, dim, quick):
    cases = box_cases(dim)
    if quick:
        seen, q = set(), []
        for c in cases:
            if c[0] not in seen:
                seen.add(c[0])
                q.append(c)
        cases = q
    rows = []
    cats = {}
    for cat, centre, R, box in cases:
        v = ref(centre, R, box)
        # exact classes must come out exactly (0) or to the box measure
        k = classify(centre, R, box)
        if k == 0:
            assert v == 0, (cat, centre, R, box, v)
        elif k == 1:
            with mp.workdps(ref.dps):
                meas = mpf(1)
                for lo, hi in box:
                    meas *= mp.fsub(mpf(hi), mpf(lo), exact=True)
                assert abs(v - meas) < mpf(10) ** (-(ref.dps - 6)) * \
                    max(1, meas), (cat, v, meas)
        else:
            assert v > 0
        rows.append([rin(c) for c in centre] + [rin(R)] +
                    [rin(t) for lh in box for t in lh] + [fmt(v)])
        cats[cat] = cats.get(cat, 0) + 1
    return rows, cats


# --------------------------------------------------------------------------
def write_csv(path, header, rows):
    with open(path, "w") as f:
        f.write(",".join(header) + "\n")
        for r in rows:
            f.write(",".join(r) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true",
                    help="tiny smoke run (a few rows per file), written to a "
                    "temporary directory unless --outdir is given")
    ap.add_argument("--outdir", default=None,
                    help="output directory (default: this script's directory)")
    ap.add_argument("--dps", type=int, default=30,
                    help="working precision of the values (digits)")
    ap.add_argument("--check-dps", type=int, default=34,
                    help="working precision of the check computation")
    args = ap.parse_args()
    outdir = args.outdir or (tempfile.mkdtemp(prefix="perideal_ref_")
                             if args.quick else
                             os.path.dirname(os.path.abspath(__file__)))
    os.makedirs(outdir, exist_ok=True)
    print("mpmath %s (backend %s), Python %s" % (
        mpmath.__version__, mpmath.libmp.BACKEND, sys.version.split()[0]))
    print("values at dps = %d; check at dps = %d with permuted axes" %
          (args.dps, args.check_dps))
    ref = Reference(args.dps, args.check_dps)
    t_all = time.time()
    sanity_checks(ref)

    jobs = [
        ("beta_3d.csv", ["m", "x", "y", "z", "beta"],
         lambda: gen_beta(ref, 3, M_LIST, args.quick)),
        ("beta_2d.csv", ["m", "x", "y", "beta"],
         lambda: gen_beta(ref, 2, M_LIST_2D, args.quick)),
        ("beta_3d_large_m.csv", ["m", "x", "y", "z", "beta"],
         lambda: gen_beta_large(ref, args.quick)),
        ("boxes_3d.csv", ["cx", "cy", "cz", "R", "x1", "x2", "y1", "y2",
                          "z1", "z2", "volume"],
         lambda: gen_boxes(ref, 3, args.quick)),
        ("boxes_2d.csv", ["cx", "cy", "R", "x1", "x2", "y1", "y2", "area"],
         lambda: gen_boxes(ref, 2, args.quick)),
    ]
    summary = []
    for name, header, gen in jobs:
        ref.reset()
        t0 = time.time()
        out = gen()
        rows, cats = out if isinstance(out, tuple) else (out, None)
        write_csv(os.path.join(outdir, name), header, rows)
        dt = time.time() - t0
        line = ("%-20s %4d rows, %4d by quadrature: max |value-check| %s, "
                "max rel %s, max quad err est %s, retries %d, %.0f s" % (
                    name, len(rows), ref.n, mp.nstr(ref.max_abs, 2),
                    mp.nstr(ref.max_rel, 2),
                    mp.nstr(ref.stats.max_quad_err, 2), ref.stats.retries, dt))
        print(line)
        if cats:
            print("    categories: " + ", ".join(
                "%s %d" % kv for kv in cats.items()))
        if ref.worst is not None:
            print("    worst case: centre %s R %r box %s" % ref.worst)
        sys.stdout.flush()
        summary.append((name, ref.max_abs))
        assert ref.max_abs < TARGET_ABS_ERROR, name
    print("total %.0f s; all files within |error| < %g; written to %s" % (
        time.time() - t_all, TARGET_ABS_ERROR, outdir))


if __name__ == "__main__":
    main()
