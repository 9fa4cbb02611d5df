#!/usr/bin/python3
"""Body force whose exact peridynamic solution is the sine field of
bench/run_collocation_convergence.sh (the 'sine_pd' field): a reference
for the discretisation error alone, without the model's O(delta^2) part.

Linearised bond-based operator, influence omega (constant by default):
    (L u)(x) = int_B c omega(|xi|/delta) / |xi|^3 xi (xi . (u(x + xi) - u(x))) dxi.
For a plane wave u = v sin(k . x) (or cos), L u = S(k) v sin(k . x) with the
symbol S(k) = int_B c omega / |xi|^3 xi xi^T (cos(k . xi) - 1) dxi (the sine
part vanishes: the kernel is even). The field is
    u = A (f, f[, f]),  f = sin(a x) sin(a y) [sin(a z)],
a sum of plane waves (2D: f = (cos(a(x - y)) - cos(a(x + y)))/2; 3D: f =
(sin(a(x - y + z)) + sin(a(-x + y + z)) - sin(a(x + y + z)) - sin(a(-x - y + z)))/4),
so b = -L u is the same sum with S(k) (1, ..., 1) A in place of each wave's
amplitude. With these b, u is the exact solution of the PD problem on every
node with a full ball (the Dirichlet layers carry u).

c is calibrated as the library calibrates it: the PD operator of a full
ball maps quadratics to the classical operator mu (Laplace u + 2 grad div u)
(Cauchy solid: lambda = mu; 2D plane strain, nu = 1/4). For u = (x^2, 0, ..):
L u = c int omega xi_x^4 / |xi|^3 dxi = 6 mu, so c = 6 mu / int omega xi_x^4 / |xi|^3.
The quadratic field of the same bench checks this calibration in the
library to round-off.

Quadrature (independent of the C++): polar/spherical coordinates, the
integrand times the Jacobian is smooth in r (|xi|^-3 xi xi^T r^(d-1) ~ r^(d-2)
times a bounded angular factor, times (cos - 1) ~ r^2), Gauss-Legendre in r
and in cos(polar angle), the trapezoidal rule in the azimuth (spectral for
periodic integrands); the printed self-check doubles every rule.

    pd_sine_force.py DIM DELTA [--amplitude A] [--wavenumber a] [--mu MU]
        [--influence constant|conical]  -> one line: the body force expression
    pd_sine_force.py --check             -> the self-checks
"""

import argparse
import math
import sys

import numpy as np

INFLUENCE = {"constant": lambda s: np.ones_like(s), "conical": lambda s: 1.0 - s}


def ball_rule(d, delta, nr, nt, nphi):
    """Points (N, d) and weights (N,) of a product rule on the ball."""
    x, w = np.polynomial.legendre.leggauss(nr)
    r = 0.5 * delta * (x + 1)
    wr = 0.5 * delta * w
    phi = 2 * math.pi * (np.arange(nphi) + 0.5) / nphi
    wphi = np.full(nphi, 2 * math.pi / nphi)
    if d == 2:
        R, P = np.meshgrid(r, phi, indexing="ij")
        W = np.outer(wr * r, wphi)
        return np.stack([R * np.cos(P), R * np.sin(P)], axis=-1).reshape(-1, 2), W.ravel()
    t, wt = np.polynomial.legendre.leggauss(nt)
    R, T, P = np.meshgrid(r, t, phi, indexing="ij")
    S = np.sqrt(1 - T * T)
    W = (wr * r * r)[:, None, None] * wt[None, :, None] * wphi[None, None, :]
    pts = np.stack([R * S * np.cos(P), R * S * np.sin(P), R * T], axis=-1).reshape(-1, 3)
    return pts, W.ravel()


class Operator:
    def __init__(self, d, delta, mu, influence, n=(64, 48, 96)):
        self.d = d
        pts, w = ball_rule(d, delta, *n)
        r = np.linalg.norm(pts, axis=1)
        self.pts = pts
        self.k = w * INFLUENCE[influence](r / delta) / r**3  # omega / |xi|^3 dV
        self.c = 6 * mu / np.sum(self.k * pts[:, 0] ** 4)

    def symbol(self, kv):
        """S(k) (d x d)."""
        f = self.c * self.k * (np.cos(self.pts @ kv) - 1)
        return np.einsum("n,na,nb->ab", f, self.pts, self.pts)


def waves(d, a):
    """(wave vector, coefficient, 'sin' or 'cos') with f = sum coef trig(k . x)."""
    if d == 2:
        return [(np.array([a, -a]), 0.5, "cos"), (np.array([a, a]), -0.5, "cos")]
    return [(np.array([a, -a, a]), 0.25, "sin"), (np.array([-a, a, a]), 0.25, "sin"),
            (np.array([a, a, a]), -0.25, "sin"), (np.array([-a, -a, a]), -0.25, "sin")]


def body_force(d, delta, amplitude, a, mu, influence, n=(64, 48, 96)):
    """Per component: list of (coefficient, trig, k) of b = -L u."""
    op = Operator(d, delta, mu, influence, n)
    comps = [[] for _ in range(d)]
    for kv, coef, trig in waves(d, a):
        amp = -op.symbol(kv) @ np.full(d, amplitude * coef)
        for i in range(d):
            comps[i].append((amp[i], trig, kv))
    return comps


def expression(comps):
    names = "xyz"
    out = []
    for terms in comps:
        parts = []
        for amp, trig, kv in terms:
            arg = " + ".join(f"({kv[j]:.17g})*{names[j]}" for j in range(len(kv)))
            parts.append(f"({amp:.17g})*{trig}({arg})")
        out.append(" + ".join(parts))
    return "; ".join(out)


def evaluate(comps, x):
    res = np.zeros(len(comps))
    for i, terms in enumerate(comps):
        for amp, trig, kv in terms:
            res[i] += amp * (math.sin if trig == "sin" else math.cos)(float(kv @ x))
    return res


def check():
    ok = True
    mu, a, A = 0.4, math.pi, 1e-3
    for d in (2, 3):
        for infl in ("constant", "conical"):
            delta = 0.1
            coarse = body_force(d, delta, A, a, mu, infl, n=(32, 24, 48))
            fine = body_force(d, delta, A, a, mu, infl, n=(64, 48, 96))
            x = np.array([0.31, 0.47, 0.73][:d])
            bc, bf = evaluate(coarse, x), evaluate(fine, x)
            rel = np.max(np.abs(bc - bf)) / np.max(np.abs(bf))
            # Brute force at the point: L u(x) by the same rule, u evaluated
            # directly (no plane-wave algebra).
            op = Operator(d, delta, mu, infl)
            f = lambda y: A * np.prod(np.sin(a * y), axis=-1)
            du = f(x + op.pts) - f(x)
            Lu = op.c * np.einsum("n,na,n->a", op.k, op.pts, (op.pts @ np.ones(d)) * du)
            direct = np.max(np.abs(bf + Lu)) / np.max(np.abs(bf))
            # delta -> 0: b tends to the classical force of the bench's
            # 'sine' field, c mu a^2 (4 f - 2 cos cos) in 2D.
            small = body_force(d, 1e-3, A, a, mu, infl)
            if d == 2:
                cl = A * mu * a * a * (4 * np.prod(np.sin(a * x)) - 2 * np.prod(np.cos(a * x)))
                classical = np.full(2, cl)
            else:
                sx, sy, sz = np.sin(a * x)
                cx, cy, cz = np.cos(a * x)
                f3 = sx * sy * sz
                classical = A * mu * a * a * np.array([5 * f3 - 2 * cx * cy * sz - 2 * cx * sy * cz,
                                                       5 * f3 - 2 * cx * cy * sz - 2 * sx * cy * cz,
                                                       5 * f3 - 2 * cx * sy * cz - 2 * sx * cy * cz])
            lim = np.max(np.abs(evaluate(small, x) - classical)) / np.max(np.abs(classical))
            good = rel < 1e-12 and direct < 1e-12 and lim < 1e-5
            ok = ok and good
            print(f"{d}D {infl:8s}: rule doubled {rel:.1e}, plane waves against direct L u {direct:.1e}, "
                  f"delta = 1e-3 against the classical force {lim:.1e}: {'ok' if good else 'FAILED'}")
    return ok


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("dim", type=int, nargs="?")
    ap.add_argument("delta", type=float, nargs="?")
    ap.add_argument("--amplitude", type=float, default=1e-3)
    ap.add_argument("--wavenumber", type=float, default=math.pi)
    ap.add_argument("--mu", type=float, default=0.4)
    ap.add_argument("--influence", default="constant", choices=sorted(INFLUENCE))
    ap.add_argument("--check", action="store_true")
    args = ap.parse_args()
    if args.check:
        sys.exit(0 if check() else 1)
    if args.dim not in (2, 3) or not args.delta or args.delta <= 0:
        ap.error("give DIM (2 or 3) and DELTA > 0, or --check")
    print(expression(body_force(args.dim, args.delta, args.amplitude, args.wavenumber, args.mu, args.influence)))


if __name__ == "__main__":
    main()
