#!/usr/bin/python3
"""Numerical check of every closed form of doc/collocation.md.

Evaluates the closed-form moments of the collocation scheme (the L vectors of
the hybrid-collocation paper, Eqs. 47-52 and 57-60, in 1D, 2D and 3D, and the
LPS moments of the lost Appendix A) and compares each with brute-force
quadrature of the defining integral in polar/spherical coordinates
(Gauss-Legendre in r and in cos(polar angle), the trapezoidal rule in the
azimuth, the integrand evaluated in Cartesian components point by point), or
with mpmath.quad where the integral is one-dimensional.  Then it builds the
collocation weights of a bulk node of a uniform grid (delta = m h) by the
recipe of the doc (auxiliary grid, nearest distinct family nodes, weight of
Eq. 36, Q = A^-1 B) and checks that they give the exact peridynamic force
density (flux) of polynomial fields up to the order: bond-based, LPS (two
passes), diffusion; uniform and perturbed nodes.

Prints a table (formula, dimension, influence, closed form, quadrature,
relative error) and exits 1 if any relative error exceeds 1e-10.

    /usr/bin/python3 bench/collocation/check_moments.py              # < 1 min
    /usr/bin/python3 bench/collocation/check_moments.py --verbose    # every entry
    /usr/bin/python3 bench/collocation/check_moments.py --conditioning
        # the table behind the choice of n_c (condition numbers, symbol error)
    /usr/bin/python3 bench/collocation/check_moments.py --example2-spectrum
        # the spectrum of the collocation operator of the paper's Example 2

Only numpy, scipy and mpmath.  Units: lengths in units of h = 1 where a grid
is involved; the closed forms hold for any delta (checked at delta != 1).
"""

import argparse
import itertools
import math
import sys
import time

import mpmath
import numpy as np
from scipy.special import gamma as Gamma
from scipy.special import gammainc

TOL = 1e-10

# --------------------------------------------------------------------------
# Influence functions omega(s), s = |xi| / delta, and their radial moments
# M_k = int_0^1 omega(s) s^k ds (closed forms).
# --------------------------------------------------------------------------
INFLUENCE = {
    "constant": (lambda s: np.ones_like(s), lambda k: 1.0 / (k + 1)),
    "conical": (lambda s: 1.0 - s, lambda k: 1.0 / ((k + 1) * (k + 2))),
    "gaussian": (
        lambda s: np.exp(-s * s),
        lambda k: 0.5 * gammainc((k + 1) / 2.0, 1.0) * Gamma((k + 1) / 2.0),
    ),
}

SPHERE = {1: 2.0, 2: 2.0 * math.pi, 3: 4.0 * math.pi}  # |S^{d-1}|


def dfact(n):
    """(n)!! for odd n >= -1."""
    r = 1
    while n > 1:
        r *= n
        n -= 2
    return r


def omega_angular(beta):
    """Closed form of int_{S^{d-1}} n^beta dS: zero unless every exponent is
    even; else S_{d-1} prod (beta_i - 1)!! / (d (d+2) ... (d + |beta| - 2))."""
    if any(b % 2 for b in beta):
        return 0.0
    d = len(beta)
    num = 1
    for b in beta:
        num *= dfact(b - 1)
    den = 1
    for j in range(sum(beta) // 2):
        den *= d + 2 * j
    return SPHERE[d] * num / den


def ball(d, infl, delta, p, beta):
    """Closed form of int_{|xi|<delta} omega(|xi|/delta) |xi|^p xi^beta dV
    = delta^(p+|beta|+d) M_(p+|beta|+d-1) Omega(beta) (a principal value 0
    when Omega(beta) = 0)."""
    ang = omega_angular(beta)
    if ang == 0.0:
        return 0.0
    k = p + sum(beta) + d - 1
    assert k >= 0, "divergent moment"
    return delta ** (k + 1) * INFLUENCE[infl][1](k) * ang


def monomials(d, k):
    """Complete monomial basis up to order k, graded, x-power first:
    3D order 2 is 1, x, y, z, x^2, xy, xz, y^2, yz, z^2 (Eq. 33)."""
    out = []
    for n in range(k + 1):
        if d == 1:
            out.append((n,))
        elif d == 2:
            for a in range(n, -1, -1):
                out.append((a, n - a))
        else:
            for a in range(n, -1, -1):
                for b in range(n - a, -1, -1):
                    out.append((a, b, n - a - b))
    return out


def mono_name(a):
    names = "xyz"
    s = "".join(names[i] + (f"^{e}" if e > 1 else "") for i, e in enumerate(a) if e)
    return s or "1"


def unit(d, a):
    return tuple(1 if i == a else 0 for i in range(d))


def add(*ts):
    return tuple(sum(x) for x in zip(*ts))


# --------------------------------------------------------------------------
# Constants of the code (source/models/*.cc), so that the collocation scheme
# solves the same continuum problem as the standard scheme.
# --------------------------------------------------------------------------
def micromodulus(d, infl, delta, mu=1.0, E=1.0):
    """Bond-based c: 3D 15 mu/(2 pi delta^4 M3), 2D 8 mu/(pi delta^3 M2)
    (bond_based.cc); 1D E/(delta^2 M1) (the paper's Example 1, c = 2E/delta^2
    for omega = 1)."""
    M = INFLUENCE[infl][1]
    if d == 3:
        return 15 * mu / (2 * math.pi * delta**4 * M(3))
    if d == 2:
        return 8 * mu / (math.pi * delta**3 * M(2))
    return E / (delta**2 * M(1))


def micro_diffusivity(d, infl, delta, q, K=1.0):
    """kappa = 2 d K / (S_{d-1} delta^(d+2-q) M_(d+1-q)) (diffusion_kernel.cc)."""
    return 2 * d * K / (SPHERE[d] * delta ** (d + 2 - q) * INFLUENCE[infl][1](d + 1 - q))


def lps_constants(d, K, mu):
    """c_K, c_mu of linear_peridynamic_solid.cc (2D: plane strain,
    planar bulk modulus K + mu/3)."""
    if d == 3:
        return 3 * K - 5 * mu, 15 * mu
    kp = K + mu / 3.0
    return 2 * kp - 4 * mu, 8 * mu


def weighted_volume(d, infl, delta):
    """m = int omega |xi|^2 dV = S_{d-1} delta^(d+2) M_(d+1)."""
    return SPHERE[d] * delta ** (d + 2) * INFLUENCE[infl][1](d + 1)


# --------------------------------------------------------------------------
# Closed-form L vectors.
# --------------------------------------------------------------------------
def L_bond(d, infl, delta, c, k):
    """L[b, a, alpha] = c int omega xi_b xi_a xi^alpha / |xi|^3 dV: force
    component b from displacement component a, monomial alpha (Eqs. 47-52);
    alpha = 0 gives 0 (p(xi) - p(0))."""
    B = monomials(d, k)
    L = np.zeros((d, d, len(B)))
    for b in range(d):
        for a in range(d):
            for i, al in enumerate(B):
                if sum(al):
                    L[b, a, i] = c * ball(d, infl, delta, -3, add(al, unit(d, a), unit(d, b)))
    return L


def L_diffusion(d, infl, delta, kappa, q, k):
    """L_C[alpha] = kappa int omega xi^alpha / |xi|^q dV (Eqs. 57-60)."""
    B = monomials(d, k)
    return np.array([kappa * ball(d, infl, delta, -q, al) if sum(al) else 0.0 for al in B])


def L_lps(d, infl, delta, K, mu, k):
    """The LPS moments (Appendix A of the doc):
    T[a, alpha]    = (d/m) int omega xi_a xi^alpha dV       (dilatation row)
    Kf[b, alpha]   = (c_K/m) int omega xi_b xi^alpha dV     (dilatation force)
    G[b, a, alpha] = (2 c_mu/m) int omega xi_b xi_a xi^alpha / |xi|^2 dV."""
    B = monomials(d, k)
    m = weighted_volume(d, infl, delta)
    cK, cmu = lps_constants(d, K, mu)
    T = np.zeros((d, len(B)))
    G = np.zeros((d, d, len(B)))
    for a in range(d):
        for i, al in enumerate(B):
            if sum(al):
                T[a, i] = d / m * ball(d, infl, delta, 0, add(al, unit(d, a)))
                for b in range(d):
                    G[b, a, i] = 2 * cmu / m * ball(d, infl, delta, -2, add(al, unit(d, a), unit(d, b)))
    Kf = cK / d * T
    return T, Kf, G


# --------------------------------------------------------------------------
# Brute-force quadrature over the ball |xi| < delta.
# --------------------------------------------------------------------------
def ball_quadrature(d, delta, nr=60, nphi=64, nt=48):
    """Points (N, d) and weights (N,) in polar/spherical coordinates."""
    x, w = np.polynomial.legendre.leggauss(nr)
    r = 0.5 * delta * (x + 1)
    wr = 0.5 * delta * w
    if d == 1:
        pts = np.concatenate([r, -r])[:, None]
        return pts, np.concatenate([wr, wr])
    phi = 2 * math.pi * np.arange(nphi) / nphi
    wphi = np.full(nphi, 2 * math.pi / nphi)
    if d == 2:
        R, P = np.meshgrid(r, phi, indexing="ij")
        W = np.outer(wr * r, wphi)
        pts = np.stack([R * np.cos(P), R * np.sin(P)], axis=-1).reshape(-1, 2)
        return pts, W.ravel()
    t, wt = np.polynomial.legendre.leggauss(nt)  # t = cos(polar angle)
    R, T, P = np.meshgrid(r, t, phi, indexing="ij")
    S = np.sqrt(1 - T * T)
    W = (wr * r * r)[:, None, None] * wt[None, :, None] * wphi[None, None, :]
    pts = np.stack([R * S * np.cos(P), R * S * np.sin(P), R * T], axis=-1).reshape(-1, 3)
    return pts, W.ravel()


def monomial_matrix(pts, basis):
    E = np.array(basis)
    return np.prod(pts[:, None, :] ** E[None, :, :], axis=2)


class Quad:
    """Brute-force evaluation of the same integrals."""

    def __init__(self, d, infl, delta, k, **kw):
        self.d, self.delta = d, delta
        self.pts, self.w = ball_quadrature(d, delta, **kw)
        self.r = np.linalg.norm(self.pts, axis=1)
        self.om = INFLUENCE[infl][0](self.r / delta)
        self.P = monomial_matrix(self.pts, monomials(d, k))
        self.P -= monomial_matrix(np.zeros((1, d)), monomials(d, k))  # p(xi) - p(0)

    def integrate(self, kernel):
        """int kernel(xi) (p(xi) - p(0)) dV, kernel (N,) -> (n_p,)."""
        return (self.w * kernel) @ self.P

    def L_bond(self, c):
        d = self.d
        return np.array([[self.integrate(c * self.om * self.pts[:, b] * self.pts[:, a] / self.r**3)
                          for a in range(d)] for b in range(d)])

    def L_diffusion(self, kappa, q):
        return self.integrate(kappa * self.om / self.r**q)

    def L_lps(self, m, cK, cmu):
        d = self.d
        T = np.array([self.integrate(d / m * self.om * self.pts[:, a]) for a in range(d)])
        Kf = np.array([self.integrate(cK / m * self.om * self.pts[:, b]) for b in range(d)])
        G = np.array([[self.integrate(2 * cmu / m * self.om * self.pts[:, b] * self.pts[:, a] / self.r**2)
                       for a in range(d)] for b in range(d)])
        return T, Kf, G


# --------------------------------------------------------------------------
# Reporting.
# --------------------------------------------------------------------------
class Report:
    def __init__(self, verbose):
        self.verbose = verbose
        self.rows = 0
        self.worst = 0.0
        self.failed = []
        print(f"{'formula':56s} {'d':>1s} {'influence':9s} {'closed form':>23s} {'quadrature':>23s} {'rel. error':>10s}")
        print("-" * 128)

    def row(self, formula, d, infl, closed, quad, scale=None, show=True):
        scale = max(abs(closed), abs(scale or 0.0), 1e-300)
        err = abs(closed - quad) / scale
        self.rows += 1
        self.worst = max(self.worst, err)
        if err > TOL:
            self.failed.append((formula, d, infl, closed, quad, err))
        if show or self.verbose or err > TOL:
            flag = "  FAIL" if err > TOL else ""
            print(f"{formula:56s} {d:1d} {infl:9s} {closed:23.16e} {quad:23.16e} {err:10.2e}{flag}")
        return err

    def group(self, formula, d, infl, closed, quad, labels):
        """Every entry of a vector; prints the largest entry and the worst
        relative error (scale: the largest entry of the vector)."""
        closed = np.asarray(closed).ravel()
        quad = np.asarray(quad).ravel()
        scale = np.max(np.abs(closed))
        errs = np.abs(closed - quad) / scale
        for i in range(len(closed)):
            self.rows += 1
            if errs[i] > TOL:
                self.failed.append((f"{formula} [{labels[i]}]", d, infl, closed[i], quad[i], errs[i]))
            if self.verbose or errs[i] > TOL:
                flag = "  FAIL" if errs[i] > TOL else ""
                print(f"{formula + ' [' + labels[i] + ']':56s} {d:1d} {infl:9s} {closed[i]:23.16e} {quad[i]:23.16e} {errs[i]:10.2e}{flag}")
        self.worst = max(self.worst, errs.max())
        i = int(np.argmax(errs))
        nz = int(np.sum(np.abs(closed) > 1e-14 * scale))
        if not self.verbose:
            text = f"{formula} ({nz}/{len(closed)} nonzero; worst {labels[i]})"
            print(f"{text[:56]:56s} {d:1d} {infl:9s} {closed[i]:23.16e} {quad[i]:23.16e} {errs[i]:10.2e}")

    def header(self, title):
        print(f"\n== {title}")


# --------------------------------------------------------------------------
# Part 1: the L vectors and the paper's constants.
# --------------------------------------------------------------------------
def check_bond_based(rep, delta):
    rep.header("Bond-based L vectors (Eqs. 47-52): L[b,a,alpha] = c int omega xi_b xi_a xi^alpha / |xi|^3")
    mu = 1.3
    for infl in ("constant", "conical"):
        d = 3
        c = micromodulus(d, infl, delta, mu=mu)
        Q = Quad(d, infl, delta, 4)
        Lq = Q.L_bond(c)
        B = monomials(d, 2)
        i_x2, i_y2, i_xy = B.index((2, 0, 0)), B.index((0, 2, 0)), B.index((1, 1, 0))
        paper = math.pi * c * delta**4 / (5 if infl == "constant" else 25)
        rep.row("Eq.52 kappa = pi c delta^4/" + ("5" if infl == "constant" else "25") + " (L_u[x^2]_x)",
                3, infl, paper, Lq[0, 0, i_x2])
        rep.row("Eq.51 L_u[y^2]_x = kappa/3", 3, infl, paper / 3, Lq[0, 0, i_y2])
        rep.row("Eq.51 L_u[xy]_y = kappa/3", 3, infl, paper / 3, Lq[1, 0, i_xy])
        rep.row("kappa with the code's c = 6 mu (Navier, l=mu)", 3, infl, 6 * mu, Lq[0, 0, i_x2])
    for infl in ("constant", "conical"):
        d = 2
        c = micromodulus(d, infl, delta, mu=mu)
        Q = Quad(d, infl, delta, 4)
        Lq = Q.L_bond(c)
        M2 = INFLUENCE[infl][1](2)
        rep.row("2D kappa = 3 pi c delta^3 M2/4 (L_u[x^2]_x)", 2, infl, 3 * math.pi * c * delta**3 * M2 / 4,
                Lq[0, 0, monomials(2, 2).index((2, 0))])
        E = 8 * mu / 3  # plane stress, nu = 1/3
        paper_c = (9 if infl == "constant" else 36) * E / (math.pi * delta**3)
        # Eq. 17 by flux matching on the quadrature: L_u[x^2]_x = 6 mu.
        c_quad = 6 * mu / (Lq[0, 0, monomials(2, 2).index((2, 0))] / c)
        rep.row("Eq.17 c = " + ("9" if infl == "constant" else "36") + "E/(pi delta^3) plane stress", 2, infl, paper_c, c_quad)
    for infl in ("constant", "conical"):
        d = 1
        E = 0.7
        c = micromodulus(d, infl, delta, E=E)
        Q = Quad(d, infl, delta, 6)
        Lq = Q.L_bond(c)
        rep.row("1D L[x^2] = 2 c delta^2 M1 = 2E", 1, infl, 2 * E, Lq[0, 0, 2])
        if infl == "constant":
            cp = 2 * E / delta**2
            rep.row("Eq.63 c = 2E/delta^2; L[x^4]/4! = c delta^4/48", 1, infl, cp * delta**4 / 48, Lq[0, 0, 4] / 24)
            rep.row("Eq.63 L[x^6]/6! = c delta^6/2160", 1, infl, cp * delta**6 / 2160, Lq[0, 0, 6] / 720)
    for d, k in ((1, 6), (2, 4), (3, 4)):
        B = monomials(d, k)
        labels = [f"f{'xyz'[b]} u{'xyz'[a]} {mono_name(al)}" for b in range(d) for a in range(d) for al in B]
        for infl in ("constant", "conical", "gaussian"):
            c = micromodulus(d, infl, delta, mu=mu, E=0.7)
            rep.group(f"L_bond order {k}", d, infl, L_bond(d, infl, delta, c, k),
                      Quad(d, infl, delta, k).L_bond(c), labels)


def check_diffusion(rep, delta):
    rep.header("Diffusion L vectors (Eqs. 57-60): L_C[alpha] = mu int omega xi^alpha / |xi|^q")
    for infl in ("constant", "conical"):
        Q = Quad(3, infl, delta, 2)
        for q in (0, 1, 2, 3):
            mu_ = 0.9
            Lq = Q.L_diffusion(mu_, q)
            den = (15 - 3 * q) if infl == "constant" else (3 * q * q - 33 * q + 90)
            paper = 4 * math.pi * mu_ * delta ** (5 - q) / den
            rep.row(f"Eq.60 kappa_C q={q} 4 pi mu delta^(5-q)/({'15-3q' if infl == 'constant' else '3q^2-33q+90'})",
                    3, infl, paper, Lq[monomials(3, 2).index((2, 0, 0))])
    for infl in ("constant", "conical"):
        Q = Quad(2, infl, delta, 2)
        for q in (0, 1, 2, 3):
            Lq = Q.L_diffusion(1.0, q)
            den = (4 - q) if infl == "constant" else (4 - q) * (5 - q)
            rep.row(f"2D kappa_C q={q} = pi mu delta^(4-q)/{'(4-q)' if infl == 'constant' else '((4-q)(5-q))'}",
                    2, infl, math.pi * delta ** (4 - q) / den, Lq[monomials(2, 2).index((2, 0))])
        # Eq. 25 by flux matching on the quadrature.
        I2 = np.sum(Q.w * Q.om * Q.r ** (2 - 2))
        paper = (4 if infl == "constant" else 12) / (math.pi * delta**2)
        rep.row(f"Eq.25 kappa = {4 if infl == 'constant' else 12}K/(pi delta^2) (2D, q=2)", 2, infl, paper, 2 * 2 / I2)
    for infl in ("constant", "conical"):
        Q = Quad(1, infl, delta, 2)
        for q in (0, 1, 2):
            Lq = Q.L_diffusion(1.0, q)
            den = (3 - q) if infl == "constant" else (3 - q) * (4 - q)
            rep.row(f"1D kappa_C q={q} = 2 mu delta^(3-q)/{'(3-q)' if infl == 'constant' else '((3-q)(4-q))'}",
                    1, infl, 2 * delta ** (3 - q) / den, Lq[2])
    for d, k in ((1, 6), (2, 4), (3, 4)):
        B = monomials(d, k)
        labels = [mono_name(al) for al in B]
        for infl in ("constant", "conical", "gaussian"):
            Q = Quad(d, infl, delta, k)
            for q in ((0, 1, 2) if d == 1 else (0, 1, 2, 3)):
                kap = micro_diffusivity(d, infl, delta, q)
                rep.group(f"L_C order {k} q={q}", d, infl, L_diffusion(d, infl, delta, kap, q, k),
                          Q.L_diffusion(kap, q), labels)


def check_lps(rep, delta):
    rep.header("LPS moments (Appendix A): m, dilatation row T, force rows Kf (dilatation) and G (extension)")
    K, mu = 1.7, 0.6
    for d in (2, 3):
        for infl in ("constant", "conical", "gaussian"):
            Q = Quad(d, infl, delta, 4)
            m_quad = np.sum(Q.w * Q.om * Q.r**2)
            if infl == "gaussian" and d == 3:
                closed = (1.5 * math.sqrt(math.pi) * math.erf(1) - 5 / math.e) * math.pi * delta**5
                name = "m = (3/2 sqrt(pi) erf1 - 5/e) pi delta^5"
            elif infl == "gaussian":
                closed = math.pi * (1 - 2 / math.e) * delta**4
                name = "m = pi (1 - 2/e) delta^4"
            else:
                closed = weighted_volume(d, infl, delta)
                name = "m = S delta^(d+2) M_(d+1)"
            rep.row(name, d, infl, closed, m_quad)
            T, Kf, G = L_lps(d, infl, delta, K, mu, 4)
            Tq, Kq, Gq = Q.L_lps(weighted_volume(d, infl, delta), *lps_constants(d, K, mu))
            B = monomials(d, 4)
            lab1 = [f"{'xyz'[a]} {mono_name(al)}" for a in range(d) for al in B]
            lab2 = [f"f{'xyz'[b]} u{'xyz'[a]} {mono_name(al)}" for b in range(d) for a in range(d) for al in B]
            rep.group("LPS T (dilatation row), order 4", d, infl, T, Tq, lab1)
            rep.group("LPS Kf (dilatation force), order 4", d, infl, Kf, Kq, lab1)
            rep.group("LPS G (extension force), order 4", d, infl, G, Gq, lab2)
            # The named entries of the doc.
            i_x3 = B.index(unit(d, 0)[:0] + (3,) + (0,) * (d - 1))
            m = weighted_volume(d, infl, delta)
            M = INFLUENCE[infl][1]
            rep.row("T_x[x^3] = 3 S delta^(d+4) M_(d+3)/(d+2) d/m", d, infl,
                    3 * d * SPHERE[d] * delta ** (d + 4) * M(d + 3) / (d * (d + 2)) / m, Tq[0, i_x3])
            i_xx = B.index((2,) + (0,) * (d - 1))
            cK, cmu = lps_constants(d, K, mu)
            rep.row("G_xx[x^2] = 6 mu (c_mu/(d(d+2)) = mu)", d, infl, 6 * mu, Gq[0, 0, i_xx])


def check_paper_sources(rep):
    rep.header("Manufactured sources of the examples")
    # Eq. 69: 1D, c = 2/delta^2 (E = 1), u = sin(pi x/10), delta = 6.
    mpmath.mp.dps = 30
    delta, x0 = mpmath.mpf(6), mpmath.mpf("3.7")
    c = 2 / delta**2
    k = mpmath.pi / 10
    integral = mpmath.quad(lambda s: c * (mpmath.sin(k * (x0 + s)) - mpmath.sin(k * x0)) / s, [0, delta]) + \
        mpmath.quad(lambda s: c * (mpmath.sin(k * (x0 - s)) - mpmath.sin(k * x0)) / s, [0, delta])
    b = 2 * c * (mpmath.euler - mpmath.ci(k * delta) + mpmath.log(k * delta)) * mpmath.sin(k * x0)
    rep.row("Eq.69 b = 2c(gamma - Ci(pi d/10) + ln(pi d/10))sin", 1, "constant", float(b), float(-integral))
    # Eq. 73: 2D, q = 2, omega = 1, delta = 4/39, the spatial part of the source.
    delta = 4.0 / 39
    kap = micro_diffusivity(2, "constant", delta, 2, K=1.0)
    f = lambda x, y: x * x * y * y + x**3 * y + x**4 + x * y**3 + y**4
    X, Y = 0.13, -0.21
    Q = Quad(2, "constant", delta, 1, nr=40, nphi=32)
    flux = np.sum(Q.w * kap / Q.r**2 * (f(X + Q.pts[:, 0], Y + Q.pts[:, 1]) - f(X, Y)))
    paper = math.pi * kap * delta**2 / 16 * (7 * delta**2 + 56 * X * X + 48 * X * Y + 56 * Y * Y)
    rep.row("Eq.73 (1/16) pi mu delta^2 (7d^2+56x^2+48xy+56y^2)", 2, "constant", paper, flux)


# --------------------------------------------------------------------------
# Part 2: collocation weights.
# --------------------------------------------------------------------------
DEFAULT_NC = {1: {2: 5, 4: 11, 6: 13}, 2: {2: 29, 4: 49}, 3: {2: 33, 4: 123}}


def aux_count(d, k):
    r = range(-k, k + 1)
    return sum(1 for a in itertools.product(r, repeat=d) if sum(x * x for x in a) <= k * k)


def aux_grid(d, k, delta):
    """Auxiliary Cartesian grid (Remark 2): spacing delta/k, the points of the
    ball, ordered by distance from the centre, then lexicographically."""
    pts = [a for a in itertools.product(range(-k, k + 1), repeat=d) if sum(x * x for x in a) <= k * k]
    pts.sort(key=lambda a: (sum(x * x for x in a), a))
    return np.array(pts, float) * (delta / k)


def aux_spacing_index(d, nc):
    """k of the auxiliary grid (spacing delta/k) whose point count in the
    ball is closest to the requested n_c (Remark 2); ties: the larger k."""
    best = 1
    k = 1
    while True:
        if abs(aux_count(d, k) - nc) <= abs(aux_count(d, best) - nc):
            best = k
        if aux_count(d, k) > nc:
            return best
        k += 1


def select_collocation(xi, delta, nc):
    """xi: bond vectors of the family (the source node included, xi = 0).
    Returns the indices of the collocation nodes: the union, over the points
    of the auxiliary grid, of the family nodes nearest to each point; a tie
    goes to the node nearer to the source, and a tie that remains (nodes
    symmetric to each other) takes all of them, so that on a uniform grid
    the set has the symmetry of the grid."""
    d = xi.shape[1]
    aux = aux_grid(d, aux_spacing_index(d, nc), delta)
    r0 = np.linalg.norm(xi, axis=1)
    tol = 1e-9 * delta
    chosen = set()
    for a in aux:
        dist = np.linalg.norm(xi - a, axis=1)
        near = np.where(dist <= dist.min() + tol)[0]
        near = near[r0[near] <= r0[near].min() + tol]
        chosen.update(int(j) for j in near)
    return np.array(sorted(chosen, key=lambda j: (r0[j], tuple(xi[j]))))


def eq36_weight(r, rt):
    """Eq. 36: (1 - exp(64 - 16 r^2/rt^2)) / (1 - exp(64))."""
    return np.expm1(64 - 16 * (r / rt) ** 2) / np.expm1(64)


def wls(xi_c, basis, delta, rt=None):
    """Q = A^-1 B in the physical basis p(xi), computed through the QR
    factorisation of W^1/2 M in the scaled basis p(xi/delta); cond(A) in the
    scaled basis."""
    rt = delta if rt is None else rt
    M = monomial_matrix(xi_c / delta, basis)
    w = eq36_weight(np.linalg.norm(xi_c, axis=1), rt)
    A = M.T @ (w[:, None] * M)
    sw = np.sqrt(w)
    Qr, R = np.linalg.qr(sw[:, None] * M)
    Qs = np.linalg.solve(R, Qr.T * sw[None, :])
    scale = np.array([delta ** -sum(a) for a in basis])
    return Qs * scale[:, None], np.linalg.cond(A)


def lattice_family(d, m, center=None, pert=0.0, rng=None, reach=1.0):
    """Nodes of a uniform grid (h = 1) around the origin, optionally perturbed
    by a uniform random offset in [-pert, pert]^d; returns the positions of
    the nodes within reach*m of the source node (at index 0)."""
    R = int(math.ceil(reach * m)) + 1
    offs = np.array(list(itertools.product(range(-R, R + 1), repeat=d)), float)
    x = offs.copy()
    if pert:
        x += rng.uniform(-pert, pert, size=x.shape)
    i0 = int(np.where(np.all(offs == 0, axis=1))[0][0])
    order = np.argsort(np.linalg.norm(x - x[i0], axis=1), kind="stable")
    x = x[order]
    x = x[np.linalg.norm(x - x[0], axis=1) <= reach * m * (1 + 1e-12)]
    return x


def node_row(x_all, i, delta, basis, nc):
    """Collocation nodes (indices into x_all) and Q of node i."""
    xi = x_all - x_all[i]
    fam = np.where(np.linalg.norm(xi, axis=1) <= delta * (1 + 1e-12))[0]
    sel = fam[select_collocation(xi[fam], delta, nc)]
    Q, cond = wls(xi[sel], basis, delta)
    return sel, Q, cond


class Poly:
    """A polynomial field: coefficients per component, {exponent: value}."""

    def __init__(self, d, ncomp, degree, rng):
        self.d = d
        self.terms = [{a: rng.uniform(-1, 1) for a in monomials(d, degree)} for _ in range(ncomp)]

    def __call__(self, x):
        x = np.atleast_2d(x)
        return np.array([sum(v * np.prod(x ** np.array(a), axis=1) for a, v in t.items()) for t in self.terms]).T

    def taylor(self, x, basis):
        """Coefficient of xi^alpha in u(x + xi), for alpha in basis (per component)."""
        out = np.zeros((len(self.terms), len(basis)))
        for c, t in enumerate(self.terms):
            for a, v in t.items():
                for i, al in enumerate(basis):
                    if all(al[j] <= a[j] for j in range(self.d)):
                        coef = v
                        for j in range(self.d):
                            coef *= math.comb(a[j], al[j]) * x[j] ** (a[j] - al[j])
                        out[c, i] += coef
        return out


def dilatation_poly(u, T, basis):
    """theta(y) = sum_a sum_alpha T[a,alpha] coef_alpha(u_a at y): returned as
    a Poly with one component (degree of u minus one)."""
    d = u.d
    th = Poly.__new__(Poly)
    th.d = d
    acc = {}
    for a, t in enumerate(u.terms):
        for g, v in t.items():
            for i, al in enumerate(basis):
                if sum(al) and all(al[j] <= g[j] for j in range(d)):
                    coef = v * T[a, i]
                    for j in range(d):
                        coef *= math.comb(g[j], al[j])
                    e = tuple(g[j] - al[j] for j in range(d))
                    acc[e] = acc.get(e, 0.0) + coef
    th.terms = [acc]
    return th


def poly_deriv(terms, axis):
    out = {}
    for a, v in terms.items():
        if a[axis]:
            b = tuple(e - (i == axis) for i, e in enumerate(a))
            out[b] = out.get(b, 0.0) + v * a[axis]
    return out


def poly_eval(terms, x):
    return sum(v * np.prod(np.asarray(x, float) ** np.array(a)) for a, v in terms.items())


def poly_add(*ts):
    out = {}
    for t in ts:
        for a, v in t.items():
            out[a] = out.get(a, 0.0) + v
    return out


def poly_lap(terms, d):
    return poly_add(*[poly_deriv(poly_deriv(terms, i), i) for i in range(d)])


def check_operator_forms(rep, rng):
    """The tensor forms of the doc for a quartic field u:
    bond-based  f = mu (Lap u + 2 grad div u)
                    + mu l_B^2 (Lap^2 u + 4 grad Lap div u),  l_B^2 = delta^2 M_(d+2) / (4 (d+4) M_d);
    LPS         theta = (1 + l_T^2 Lap) div u,                  l_T^2 = delta^2 M_(d+3) / (2 (d+2) M_(d+1)),
                f = mu (Lap u + 2 grad div u) + (c_K/d) (1 + 2 l_T^2 Lap) grad div u
                    + mu l_G^2 (Lap^2 u + 4 grad Lap div u),  l_G^2 = delta^2 M_(d+3) / (4 (d+4) M_(d+1))."""
    rep.header("Operator forms on quartic fields (closed forms of the doc against the L vectors applied to the field)")
    mu, K = 1.3, 1.7
    for d in (2, 3):
        for infl in ("constant", "conical", "gaussian"):
            delta = 1.37
            M = INFLUENCE[infl][1]
            u = Poly(d, d, 4, rng)
            x0 = rng.uniform(-1, 1, d)
            basis = monomials(d, 4)
            coef = u.taylor(x0, basis)
            div = poly_add(*[poly_deriv(u.terms[a], a) for a in range(d)])
            lap_u = [poly_lap(u.terms[a], d) for a in range(d)]
            lap2_u = [poly_lap(t, d) for t in lap_u]
            lapdiv = poly_lap(div, d)
            grad_div = [poly_eval(poly_deriv(div, b), x0) for b in range(d)]
            grad_lapdiv = [poly_eval(poly_deriv(lapdiv, b), x0) for b in range(d)]
            # bond-based
            c = micromodulus(d, infl, delta, mu=mu)
            fL = np.einsum("bai,ai->b", L_bond(d, infl, delta, c, 4), coef)
            lB2 = delta**2 * M(d + 2) / (4 * (d + 4) * M(d))
            fF = [mu * (poly_eval(lap_u[b], x0) + 2 * grad_div[b]) + mu * lB2 * (poly_eval(lap2_u[b], x0) + 4 * grad_lapdiv[b])
                  for b in range(d)]
            for b in range(d):
                rep.row(f"BB quartic: mu(Lap u+2 grad div u)+mu lB^2(...) f{'xyz'[b]}", d, infl, fF[b], fL[b],
                        scale=max(abs(v) for v in fF), show=(b == 0))
            # LPS
            cK, cmu = lps_constants(d, K, mu)
            fE, th = lps_exact(u, d, infl, delta, K, mu, 4, x0)
            lT2 = delta**2 * M(d + 3) / (2 * (d + 2) * M(d + 1))
            lG2 = delta**2 * M(d + 3) / (4 * (d + 4) * M(d + 1))
            rep.row("LPS quartic: theta = (1 + lT^2 Lap) div u", d, infl,
                    poly_eval(div, x0) + lT2 * poly_eval(lapdiv, x0), float(th(x0)[0, 0]))
            fF = [mu * (poly_eval(lap_u[b], x0) + 2 * grad_div[b]) + cK / d * (grad_div[b] + 2 * lT2 * grad_lapdiv[b])
                  + mu * lG2 * (poly_eval(lap2_u[b], x0) + 4 * grad_lapdiv[b]) for b in range(d)]
            for b in range(d):
                rep.row(f"LPS quartic: tensor form f{'xyz'[b]}", d, infl, fF[b], fE[b],
                        scale=max(abs(v) for v in fF), show=(b == 0))


def check_stencils(rep, rng):
    rep.header("Collocation weights of a bulk node (delta = m h, Eq. 36 weight, rt = delta): "
               "stencil result against the exact PD value")
    mu, K = 1.3, 1.7
    xc = {1: np.array([0.3]), 2: np.array([0.3, -0.7]), 3: np.array([0.3, -0.7, 0.45])}
    cases = [  # (d, order, m, influence)
        (2, 2, 3, "constant"), (3, 2, 3, "constant"),
        (2, 4, 4, "conical"), (3, 4, 3, "constant"),
        (1, 2, 6, "constant"), (1, 4, 6, "conical"), (1, 6, 6, "constant"),
    ]
    for d, k, m, infl in cases:
        delta = float(m)
        basis = monomials(d, k)
        nc = DEFAULT_NC[d][k]
        x = lattice_family(d, m)
        sel, Q, cond = node_row(x, 0, delta, basis, nc)
        xi = x[sel]
        c = micromodulus(d, infl, delta, mu=mu, E=0.7)
        L = L_bond(d, infl, delta, c, k)
        W = np.einsum("bai,ij->jba", L, Q)  # one d x d block per collocation node
        u = Poly(d, d, k, rng)
        x0 = xc[d]
        f_stencil = np.einsum("jba,ja->b", W, u(x0 + xi))
        coef = u.taylor(x0, basis)
        f_closed = np.einsum("bai,ai->b", L, coef)
        # Brute-force quadrature of the PD integral of this field.
        Qd = Quad(d, infl, delta, 0)
        du = u(x0 + Qd.pts) - u(x0)
        kern = c * Qd.om / Qd.r**3 * Qd.w
        f_quad = np.einsum("n,nb,na,na->b", kern, Qd.pts, Qd.pts, du) if d > 1 else \
            np.array([np.sum(kern * Qd.pts[:, 0] ** 2 * du[:, 0])])
        sc = np.max(np.abs(f_closed))
        name = f"BB C{k} n_c={len(sel)} m={m} (cond A {cond:.1e})"
        for b in range(d):
            rep.row(f"{name} f{'xyz'[b]}: stencil", d, infl, f_closed[b], f_stencil[b], scale=sc)
            rep.row(f"{name} f{'xyz'[b]}: quadrature", d, infl, f_closed[b], f_quad[b], scale=sc, show=False)
        if k == 2 and d > 1:
            # The closed form of a quadratic field: Navier with lambda = mu.
            H = np.zeros((d, d, d))
            for a in range(d):
                for al, v in u.terms[a].items():
                    if sum(al) == 2:
                        i, j = [t for t in range(d) for _ in range(al[t])]
                        H[a, i, j] += v
                        H[a, j, i] += v
            lap = np.einsum("aii->a", H)
            graddiv = np.einsum("aab->b", H)
            navier = mu * lap + 2 * mu * graddiv
            for b in range(d):
                rep.row(f"BB quadratic = mu Lap u + 2 mu grad div u, f{'xyz'[b]}", d, infl, navier[b], f_stencil[b],
                        scale=np.max(np.abs(navier)))
        # Weights sum to zero (constants give no force) and are symmetric
        # blocks; the uniform stencil is invariant under xi -> -xi.
        rep.row(f"BB C{k} m={m}: sum of the weight blocks", d, infl, 0.0, float(np.max(np.abs(W.sum(axis=0)))),
                scale=float(np.max(np.abs(W))), show=False)
    # Diffusion: the paper's Example 2 (q = 2, constant, delta = 4h) with C4,
    # n_c = 49: the quartic manufactured field is reproduced exactly (Eq. 73).
    d, k, m = 2, 4, 4
    delta = float(m)
    basis = monomials(d, k)
    x = lattice_family(d, m)
    sel, Q, cond = node_row(x, 0, delta, basis, DEFAULT_NC[d][k])
    kap = micro_diffusivity(d, "constant", delta, 2)
    wC = L_diffusion(d, "constant", delta, kap, 2, k) @ Q
    f = lambda p: p[:, 0] ** 2 * p[:, 1] ** 2 + p[:, 0] ** 3 * p[:, 1] + p[:, 0] ** 4 + p[:, 0] * p[:, 1] ** 3 + p[:, 1] ** 4
    X = np.array([0.3, -0.7])
    exact = 14 * X[0] ** 2 + 12 * X[0] * X[1] + 14 * X[1] ** 2 + 56 * delta**2 / 32  # K (Lap f + delta^2/32 Lap^2 f)
    rep.row(f"Diffusion C4 n_c={len(sel)} m=4 q=2: Example 2 field", 2, "constant", exact, wC @ f(X + x[sel]))
    for d, infl, q in ((3, "conical", 1), (1, "constant", 2)):
        k = 4 if d == 3 else 6
        m = 3 if d == 3 else 6
        basis = monomials(d, k)
        x = lattice_family(d, m)
        sel, Q, cond = node_row(x, 0, float(m), basis, DEFAULT_NC[d][k])
        kap = micro_diffusivity(d, infl, float(m), q)
        LC = L_diffusion(d, infl, float(m), kap, q, k)
        u = Poly(d, 1, k, rng)
        X = xc[d]
        rep.row(f"Diffusion C{k} n_c={len(sel)} m={m} q={q}: random poly", d, infl,
                float(LC @ u.taylor(X, basis)[0]), float((LC @ Q) @ u(X + x[sel])[:, 0]))
    check_lps_stencils(rep, rng, K, mu, xc)
    check_perturbed(rep, rng, mu, xc)
    # Negative control (not a check): C2 weights are not exact for a quartic.
    d, m = 2, 3
    x = lattice_family(d, m)
    sel, Q, _ = node_row(x, 0, float(m), monomials(d, 2), DEFAULT_NC[d][2])
    c = micromodulus(d, "constant", float(m), mu=mu)
    L2 = L_bond(d, "constant", float(m), c, 2)
    L4 = L_bond(d, "constant", float(m), c, 4)
    u = Poly(d, d, 4, rng)
    f_st = np.einsum("bai,ij,ja->b", L2, Q, u(xc[d] + x[sel]))
    f_ex = np.einsum("bai,ai->b", L4, u.taylor(xc[d], monomials(d, 4)))
    print(f"(control, not a check: C2 weights on a quartic field, 2D m=3: relative deviation "
          f"{np.max(np.abs(f_st - f_ex)) / np.max(np.abs(f_ex)):.1e})")


def lps_exact(u, d, infl, delta, K, mu, k, x0):
    basis = monomials(d, k)
    T, Kf, G = L_lps(d, infl, delta, K, mu, k)
    th = dilatation_poly(u, T, basis)
    return np.einsum("bi,i->b", Kf, th.taylor(x0, basis)[0]) + np.einsum("bai,ai->b", G, u.taylor(x0, basis)), th


def check_lps_stencils(rep, rng, K, mu, xc):
    """Two passes on the infinite uniform grid: theta at every collocation
    node j of i from j's own (shared) stencil, then the force of i."""
    for d, k, m, infl, pert in ((2, 2, 3, "constant", 0.0), (3, 2, 3, "gaussian", 0.0),
                                (2, 4, 4, "conical", 0.0), (2, 4, 4, "constant", 0.35)):
        delta = float(m)
        basis = monomials(d, k)
        nc = DEFAULT_NC[d][k]
        T, Kf, G = L_lps(d, infl, delta, K, mu, k)
        u = Poly(d, d, k, rng)
        x0 = xc[d]
        x = lattice_family(d, m, pert=pert, rng=rng, reach=2.0)
        sel, Q, cond = node_row(x, 0, delta, basis, nc)
        theta = []
        for j in sel:
            sj, Qj, _ = node_row(x, j, delta, basis, nc)
            theta.append(np.einsum("ai,ij,ja->", T, Qj, u(x0 + x[sj] - x[0])))
        theta = np.array(theta)
        f_stencil = np.einsum("bi,ij,j->b", Kf, Q, theta) + np.einsum("bai,ij,ja->b", G, Q, u(x0 + x[sel] - x[0]))
        f_exact, th = lps_exact(u, d, infl, delta, K, mu, k, x0)
        sc = np.max(np.abs(f_exact))
        kind = "perturbed 0.35h" if pert else "uniform"
        for b in range(d):
            rep.row(f"LPS C{k} 2-pass n_c={len(sel)} m={m} {kind} f{'xyz'[b]}", d, infl, f_exact[b], f_stencil[b], scale=sc)
        # theta of the source node against the exact dilatation.
        th_i = np.einsum("ai,ij,ja->", T, Q, u(x0 + x[sel] - x[0]))
        rep.row(f"LPS C{k} theta_i (pass 1) {kind}", d, infl, float(th(x0)[0, 0]), float(th_i),
                scale=max(1.0, abs(float(th(x0)[0, 0]))), show=False)
        if k == 2:
            # Quadratic field: the continuum LPS force is Navier.
            H = np.zeros((d, d, d))
            for a in range(d):
                for al, v in u.terms[a].items():
                    if sum(al) == 2:
                        i, j = [t for t in range(d) for _ in range(al[t])]
                        H[a, i, j] += v
                        H[a, j, i] += v
            lam_mu = K + mu / 3.0  # 3D: K + mu/3; 2D plane strain: planar K = K + mu/3
            navier = mu * np.einsum("aii->a", H) + lam_mu * np.einsum("aab->b", H)
            for b in range(d):
                rep.row(f"LPS quadratic = mu Lap u + (K+mu/3) grad div u f{'xyz'[b]}", d, infl, navier[b], f_exact[b],
                        scale=np.max(np.abs(navier)), show=(b == 0))
    # Brute-force nested quadrature of the LPS force of a quartic field (2D,
    # conical), theta(x + xi) itself by quadrature at every outer point.
    d, infl, delta = 2, "conical", 1.3
    u = Poly(d, d, 4, rng)
    x0 = xc[d]
    f_exact, _ = lps_exact(u, d, infl, delta, K, mu, 4, x0)
    Qo = Quad(d, infl, delta, 0, nr=8, nphi=16)
    m = weighted_volume(d, infl, delta)
    cK, cmu = lps_constants(d, K, mu)

    def theta_at(y):
        out = np.empty(len(y))
        for n, yy in enumerate(y):
            e = u(yy + Qo.pts) - u(yy)
            out[n] = d / m * np.sum(Qo.w * Qo.om * np.einsum("na,na->n", Qo.pts, e))
        return out

    th_out = theta_at(x0 + Qo.pts)
    fK = cK / m * np.einsum("n,nb->b", Qo.w * Qo.om * th_out, Qo.pts)  # int omega r n theta(x+xi)
    e = u(x0 + Qo.pts) - u(x0)
    fG = 2 * cmu / m * np.einsum("n,nb,na,na->b", Qo.w * Qo.om / Qo.r**2, Qo.pts, Qo.pts, e)
    for b in range(d):
        rep.row(f"LPS quartic force, nested quadrature f{'xyz'[b]}", d, infl, f_exact[b], fK[b] + fG[b],
                scale=np.max(np.abs(f_exact)))


def check_perturbed(rep, rng, mu, xc):
    """Per-node rows on perturbed nodes (0.35 h): still exact for the order."""
    for d, k, m, infl in ((2, 2, 4, "constant"), (2, 4, 4, "conical"), (3, 2, 4, "conical"), (3, 4, 4, "constant"),
                          (1, 6, 7, "constant")):
        delta = float(m)
        basis = monomials(d, k)
        x = lattice_family(d, m, pert=0.35, rng=rng)
        sel, Q, cond = node_row(x, 0, delta, basis, DEFAULT_NC[d][k])
        c = micromodulus(d, infl, delta, mu=mu, E=0.7)
        L = L_bond(d, infl, delta, c, k)
        u = Poly(d, d, k, rng)
        x0 = xc[d]
        f_st = np.einsum("bai,ij,ja->b", L, Q, u(x0 + x[sel] - x[0]))
        f_ex = np.einsum("bai,ai->b", L, u.taylor(x0, basis))
        sc = np.max(np.abs(f_ex))
        for b in range(d):
            rep.row(f"BB C{k} n_c={len(sel)} m={m} perturbed 0.35h (cond {cond:.0e}) f{'xyz'[b]}", d, infl,
                    f_ex[b], f_st[b], scale=sc, show=(b == 0))


# --------------------------------------------------------------------------
# Part 3 (optional): the table behind the choice of n_c.
# --------------------------------------------------------------------------
def bulk_symbol(W, xi, d, n=None):
    """Largest and smallest real part of the eigenvalues of the Fourier
    symbol sigma(k) = sum_j W_j exp(i k.xi_j) of a bulk stencil (h = 1) over
    the Brillouin zone [-pi, pi]^d (W: (n_c,) or (n_c, d, d))."""
    n = n or (20 if d == 3 else 81)
    g = np.linspace(-math.pi, math.pi, n)
    kk = np.array(np.meshgrid(*([g] * d), indexing="ij")).reshape(d, -1).T
    E = np.exp(1j * kk @ xi.T)
    if W.ndim == 1:
        ev = E @ W
    else:
        ev = np.linalg.eigvals(np.einsum("nj,jba->nba", E, W)).ravel()
    return ev.real.max(), ev.real.min()


def conditioning_table(rng):
    print("\nThe table behind the choice of n_c and of the weight radius rt, bulk node of a uniform grid (h = 1):\n"
          "  cond A: condition number of A_i (scaled basis p(xi/delta), Eq. 36 weight), uniform and the largest of\n"
          "          10 clouds perturbed by up to 0.35 h;\n"
          "  err kd: relative error of the collocation diffusion operator (q = 2, constant) on cos(k.x), |k| delta =\n"
          "          1 and 2, against the exact PD symbol;\n"
          "  max+/|min|: the largest real part of the bulk symbol (bond-based, constant omega) over the Brillouin\n"
          "          zone, over the magnitude of the most negative one (> 0: the operator has growing modes).")
    print(f"{'d':>1s} {'C':>2s} {'n_p':>3s} {'n_c':>4s} {'m':>2s} {'family':>6s} {'rt/delta':>8s} {'cond A':>9s} {'pert.':>9s}"
          f" {'err kd=1':>9s} {'kd=2':>9s} {'max+/|min|':>10s}")
    for d, k, ncs, ms in ((1, 2, (3, 5), (6, 12)), (1, 4, (5, 7, 11), (6, 12)), (1, 6, (7, 9, 13), (6, 12)),
                          (2, 2, (13, 29), (3, 4, 6)), (2, 4, (29, 49), (4, 6)),
                          (3, 2, (33, 123), (3, 4)), (3, 4, (123, 257), (3, 4))):
        basis = monomials(d, k)
        for nc in ncs:
            for m in ms:
                delta = float(m)
                x = lattice_family(d, m)
                if len(x) < nc:
                    continue
                for rt in (1.0, 1.5):
                    xi = x - x[0]
                    sel = select_collocation(xi, delta, nc)
                    Q, cu = wls(xi[sel], basis, delta, rt * delta)
                    cp = 0.0
                    for _ in range(10):
                        xp = lattice_family(d, m, pert=0.35, rng=rng)
                        sp = select_collocation(xp - xp[0], delta, nc)
                        cp = max(cp, wls(xp[sp] - xp[0], basis, delta, rt * delta)[1])
                    kap = micro_diffusivity(d, "constant", delta, 2)
                    w = L_diffusion(d, "constant", delta, kap, 2, k) @ Q
                    Qd = Quad(d, "constant", delta, 0, nr=40, nphi=48, nt=32)
                    dirn = np.array([1.0, 0.37, 0.21][:d])
                    dirn /= np.linalg.norm(dirn)
                    errs = []
                    for kd in (1.0, 2.0):
                        kv = kd / delta * dirn
                        exact = np.sum(Qd.w * kap / Qd.r**2 * (np.cos(Qd.pts @ kv) - 1))
                        colloc = w @ (np.cos(xi[sel] @ kv))
                        errs.append(abs(colloc - exact) / abs(exact))
                    c = micromodulus(d, "constant", delta, mu=1.0, E=1.0)
                    W = np.einsum("bai,ij->jba", L_bond(d, "constant", delta, c, k), Q)
                    smax, smin = bulk_symbol(W, xi[sel], d)
                    print(f"{d:1d} {k:2d} {len(basis):3d} {len(sel):4d} {m:2d} {len(x):6d} {rt:8.1f} {cu:9.2e} {cp:9.2e}"
                          f" {errs[0]:9.2e} {errs[1]:9.2e} {smax / abs(smin):+10.1e}")


def example2_spectrum():
    """The semi-discrete operator of the paper's Example 2 (2D diffusion,
    q = 2, constant omega, 39 x 39 nodes on (-0.5, 0.5)^2, delta = 4 h,
    Dirichlet layers delta thick), collocation on every free node: the
    largest real part of its eigenvalues (> 0: growing modes, whatever the
    time step)."""
    n, m = 39, 4
    h = 1.0 / n
    delta = m * h
    c = (np.arange(n) + 0.5) * h - 0.5
    P = np.stack(np.meshgrid(c, c, indexing="ij"), -1).reshape(-1, 2)
    grid = np.rint(P / h - 0.5 + n / 2).astype(int)
    index = {tuple(g): i for i, g in enumerate(grid)}
    free = np.where((np.abs(P) < 0.5 - delta + 1e-12).all(1))[0]
    pos = {g: i for i, g in enumerate(free)}
    print(f"\nExample 2 (Table 2), {len(P)} nodes, {len(free)} free: eigenvalues of the collocation operator")
    for k in (2, 4):
        for rt in (1.0, 1.5):
            xi = lattice_family(2, m) * h
            sel = select_collocation(xi, delta, DEFAULT_NC[2][k])
            Q, _ = wls(xi[sel], monomials(2, k), delta, rt * delta)
            w = L_diffusion(2, "constant", delta, micro_diffusivity(2, "constant", delta, 2), 2, k) @ Q
            offs = np.rint(xi[sel] / h).astype(int)
            A = np.zeros((len(free), len(free)))
            for r, i in enumerate(free):
                for wj, o in zip(w, offs):
                    j = index[tuple(grid[i] + o)]
                    if j in pos:
                        A[r, pos[j]] += wj
            ev = np.linalg.eigvals(A)
            print(f"  C{k} n_c={len(sel)} rt={rt} delta: largest real part {ev.real.max():+.3e} /s, "
                  f"most negative {ev.real.min():.3e} /s (K = 1)")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--verbose", action="store_true", help="print every entry of every vector")
    ap.add_argument("--conditioning", action="store_true", help="also print the table behind the choice of n_c")
    ap.add_argument("--example2-spectrum", action="store_true",
                    help="also print the largest real eigenvalue of the collocation operator of Example 2 (10 s)")
    args = ap.parse_args()
    t0 = time.time()
    rng = np.random.default_rng(23)
    rep = Report(args.verbose)
    delta = 1.37  # any horizon: the closed forms carry the powers of delta
    check_bond_based(rep, delta)
    check_diffusion(rep, delta)
    check_lps(rep, delta)
    check_paper_sources(rep)
    check_operator_forms(rep, rng)
    check_stencils(rep, rng)
    if args.conditioning:
        conditioning_table(rng)
    if args.example2_spectrum:
        example2_spectrum()
    print(f"\n{rep.rows} comparisons, worst relative error {rep.worst:.2e} (tolerance {TOL:g}), "
          f"{time.time() - t0:.1f} s")
    if rep.failed:
        print(f"FAILED: {len(rep.failed)} comparisons above {TOL:g}")
        for f in rep.failed[:20]:
            print("  ", f)
        return 1
    print("all closed forms and collocation weights agree")
    return 0


if __name__ == "__main__":
    sys.exit(main())
