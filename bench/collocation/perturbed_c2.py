#!/usr/bin/python3
"""Spectrum of the assembled per-node C2 collocation operator (bond-based,
constant influence) on a periodic box of perturbed nodes, with and without the
stabilisation term of doc/collocation.md Sect. 7.1, against the uniform box and
the standard (meshfree, partial-volume) scheme on the same nodes.

Setup (h = 1, delta = m h, mu = 1, c = micromodulus() of check_moments.py, i.e.
the library's 3D c = 15 mu/(2 pi delta^4 M3), 2D c = 8 mu/(pi delta^3 M2)):
  * nodes: grid points g in {0..N-1}^d, x = g + U[-p, p]^d (p = 0.35), periodic
    box of side N (periodic images for families and clouds);
  * family of i: all images with |x_j - x_i| <= delta; collocation nodes:
    check_moments.select_collocation (auxiliary grid, k_a from n_c); fit:
    check_moments.wls with the Eq. 36 weight of radius r~ (r~ = delta unless
    stated); row W_j = sum_alpha L[alpha] Q[alpha, j] (d x d blocks),
    f_i = sum_j W_ij u_j (force density; the exact operator is <= 0, so an
    eigenvalue with Re > 0 is a growing mode / indefinite static operator);
  * stabilisation: stabilised_c4.s_vector (s_j = c/(d r_j) V_ball/(n_c - 1)) and
    T_row (T = v - Q^T M^T v), added as gamma T_j I_d (Sect. 7.1);
  * standard scheme: f_i = sum_j c/|xi| e e^T V_ij (u_j - u_i), xi the moved bond,
    (a) 'std frac=1': V_ij = h^d if |xi| <= delta, else 0;
    (b) 'std pv': V_ij = (F(x_i, cell_j) + F(x_j, cell_i))/2, F the fraction of
        the (fixed, unperturbed) unit cell in the ball, estimated with 6^d
        midpoint sub-points (the library's rule, neighbor_list.cc); omega = 1 for
        every bond with V_ij > 0. Both are symmetric.
  * uniform box: every row is the same stencil, so the eigenvalues are those of
    the symbol sum_j W_j exp(i k.xi_j) at the box's wavenumbers k = 2 pi n / N
    (exact for the assembled circulant operator).

Printed per case: min Re (most negative real part, h = 1, mu = 1), r+ = max Re /
|min Re|, i = max |Im| / |min Re|, n+ = number of eigenvalues with
Re > 1e-9 |min Re| (the d translations are exact zeros), s+ = largest
eigenvalue of the symmetric part (A + A^T)/2 over |min Re| (> 0: the field of
values crosses 0, bad for GMRES even without growing modes), phi = largest
angle (degrees) of a nonzero eigenvalue from the negative real axis (> 90: Re > 0).

    OMP_NUM_THREADS=1 /usr/bin/python3 perturbed_c2.py --dim 2              # ~2 min
    OMP_NUM_THREADS=1 /usr/bin/python3 perturbed_c2.py --dim 3 --seeds 1    # ~6 min per seed
    OMP_NUM_THREADS=1 /usr/bin/python3 perturbed_c2.py --dim 3 --gmres      # GMRES iterations
"""

import os

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_v, "1")

import argparse  # noqa: E402
import itertools  # noqa: E402
import math  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402
import scipy.sparse as sp  # noqa: E402
from scipy.sparse.linalg import LinearOperator, gmres  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import check_moments as cm  # noqa: E402
import stabilised_c4 as sc  # noqa: E402

INFL = "constant"
PERT = 0.35


# --------------------------------------------------------------------------
# Geometry
# --------------------------------------------------------------------------
def box(d, N, pert, rng):
    g = np.array(list(itertools.product(range(N), repeat=d)), float)
    x = g + (rng.uniform(-pert, pert, g.shape) if pert else 0.0)
    return g, x


def shifts(d, N):
    return np.array(list(itertools.product((-1, 0, 1), repeat=d)), float) * N


def families(x, N, delta, only=None):
    """Per node: bond vectors of the family (periodic images), sorted by length
    (the node itself first), and the node indices."""
    d = x.shape[1]
    out = []
    S = shifts(d, N)
    for i in (range(len(x)) if only is None else only):
        xs, ids = [], []
        for s in S:
            dx = x + s - x[i]
            w = np.where(np.linalg.norm(dx, axis=1) <= delta * (1 + 1e-12))[0]
            xs.append(dx[w])
            ids.append(w)
        xs, ids = np.concatenate(xs), np.concatenate(ids)
        o = np.argsort(np.linalg.norm(xs, axis=1), kind="stable")
        out.append((xs[o], ids[o]))
    return out


# --------------------------------------------------------------------------
# Rows and operators
# --------------------------------------------------------------------------
def colloc_row(d, m, xi, k, rt, gamma):
    delta = float(m)
    basis = cm.monomials(d, k)
    Q, cond = cm.wls(xi, basis, delta, rt * delta)
    L = cm.L_bond(d, INFL, delta, cm.micromodulus(d, INFL, delta), k)
    W = np.einsum("bai,ij->jba", L, Q)
    if gamma:
        M = cm.monomial_matrix(xi, basis)
        s, i0 = sc.s_vector(d, m, xi, INFL, "bond")
        T = sc.T_row(s, i0, M, Q)
        W = sc.full_row(W, T, gamma, d)
    return W, cond


def assemble(d, m, fams, variant, nodes_n):
    """Dense (n d) x (n d) operator of per-node collocation rows; variant
    (nc, rt, gamma); returns A, the largest cond(A_i), mean cloud size."""
    nc, rt, gamma = variant
    delta = float(m)
    A = np.zeros((nodes_n * d, nodes_n * d))
    worst, sizes = 0.0, []
    for i, (xs, ids) in enumerate(fams):
        sel = cm.select_collocation(xs, delta, nc)
        W, cond = colloc_row(d, m, xs[sel], 2, rt, gamma)
        worst = max(worst, cond)
        sizes.append(len(sel))
        cols = ids[sel]
        for b in range(d):
            for a in range(d):
                np.add.at(A[i * d + b], cols * d + a, W[:, b, a])
    return A, worst, float(np.mean(sizes))


def cell_fraction(center_pts, ball_c, delta, sub):
    """Fraction of each unit cell (centres center_pts, (n, d)) inside the ball
    |y - ball_c| <= delta, with sub^d midpoint sub-points."""
    d = center_pts.shape[1]
    t = (np.arange(sub) + 0.5) / sub - 0.5
    P = np.array(list(itertools.product(t, repeat=d)))
    y = center_pts[:, None, :] + P[None, :, :] - ball_c
    return np.mean(np.sum(y * y, axis=2) <= delta * delta, axis=1)


def standard_op(d, m, g, x, N, mode, sub=6):
    """Standard scheme on the moved nodes (symmetric): mode 'frac1' or 'pv'."""
    delta = float(m)
    c = cm.micromodulus(d, INFL, delta)
    n = len(x)
    S = shifts(d, N)
    reach = delta + 0.5 * math.sqrt(d) + PERT * math.sqrt(d) + 1e-9
    V = {}
    for i in range(n):
        for s in S:
            st = tuple(s)
            if mode == "frac1":
                w = np.where(np.linalg.norm(x + s - x[i], axis=1) <= delta)[0]
                f = np.ones(len(w))
            else:
                w = np.where(np.linalg.norm(g + s - x[i], axis=1) <= reach)[0]  # cell centres of the images
                f = cell_fraction(g[w] + s, x[i], delta, sub)
            for j, fj in zip(w, f):
                if fj > 0 and not (j == i and not np.any(s)):
                    V[(i, int(j), st)] = fj
    A = np.zeros((n * d, n * d))
    rev = lambda key: (key[1], key[0], tuple(-np.array(key[2]) + 0.0))
    keys = set(V) | {rev(key) for key in V}
    for key in keys:
        i, j, st = key
        v = 0.5 * (V.get(key, 0.0) + V.get(rev(key), 0.0))  # mean of the two fractions (frac1: symmetric anyway)
        xi = x[j] + np.array(st) - x[i]
        r = np.linalg.norm(xi)
        e = xi / r
        K = c / r * v * np.outer(e, e)
        A[i * d:(i + 1) * d, j * d:(j + 1) * d] += K
        A[i * d:(i + 1) * d, i * d:(i + 1) * d] -= K
    return A


def uniform_eigs(d, m, N, variant):
    """Eigenvalues of the uniform periodic box through the symbol."""
    nc, rt, gamma = variant
    g, x = box(d, N, 0.0, None)
    xs, _ = families(x, N, float(m), only=[0])[0]
    sel = cm.select_collocation(xs, float(m), nc)
    W, _ = colloc_row(d, m, xs[sel], 2, rt, gamma)
    kk = 2 * math.pi * np.array(list(itertools.product(range(N), repeat=d))) / N
    E = np.exp(1j * kk @ xs[sel].T)
    return np.linalg.eigvals(np.einsum("nj,jba->nba", E, W)).ravel(), len(sel)


def uniform_std_eigs(d, m, N):
    delta = float(m)
    c = cm.micromodulus(d, INFL, delta)
    x = cm.lattice_family(d, m)
    xi = x - x[0]
    r = np.linalg.norm(xi, axis=1)
    nz = r > 0
    rr = np.where(nz, r, 1.0)
    e = xi / rr[:, None]
    R = (c * nz / rr)[:, None, None] * e[:, :, None] * e[:, None, :]
    R[0] = -R.sum(0)
    kk = 2 * math.pi * np.array(list(itertools.product(range(N), repeat=d))) / N
    E = np.exp(1j * kk @ xi.T)
    return np.linalg.eigvals(np.einsum("nj,jba->nba", E, R)).ravel()


def stats(ev, A=None):
    mn = ev.real.min()
    s = abs(mn)
    out = dict(min=mn, rpos=ev.real.max() / s, im=np.abs(ev.imag).max() / s,
               npos=int(np.sum(ev.real > 1e-9 * s)), spos=np.nan)
    nz = ev[np.abs(ev) > 1e-9 * s]
    out["phi"] = float(np.degrees(np.max(np.abs(np.angle(-nz)))))
    if A is not None:
        out["spos"] = np.linalg.eigvalsh(0.5 * (A + A.T))[-1] / s
    return out


def line(name, st, extra=""):
    return (f"{name:34s} {st['min']:9.3f} {st['rpos']:+10.2e} {st['im']:9.2e} {st['npos']:5d}"
            f" {st['spos']:+9.2e} {st['phi']:6.1f} {extra}")


HEAD = f"{'operator':34s} {'min Re':>9s} {'r+':>10s} {'i':>9s} {'n+':>5s} {'s+':>9s} {'phi':>6s} notes"


# --------------------------------------------------------------------------
# GMRES
# --------------------------------------------------------------------------
def gmres_iters(A, rng, eps=1e-3, tol=1e-8, restart=50, maxit=20000):
    """K = -A + eps mean(diag(-A)) I, Jacobi-preconditioned GMRES(restart) on a
    random right-hand side; inner iterations to a relative (preconditioned)
    residual tol, and the final true relative residual."""
    K = -A
    K = K + eps * np.mean(np.diag(K)) * np.eye(len(K))
    Ks = sp.csr_matrix(np.where(np.abs(K) > 0, K, 0.0))
    dinv = 1.0 / Ks.diagonal()
    Mpre = LinearOperator(Ks.shape, matvec=lambda v: dinv * v)
    b = rng.standard_normal(len(K))
    count = [0]

    def cb(_):
        count[0] += 1

    x, info = gmres(Ks, b, tol=tol, atol=0.0, restart=restart, maxiter=maxit // restart + 1, M=Mpre,
                    callback=cb, callback_type="pr_norm")
    res = np.linalg.norm(b - Ks @ x) / np.linalg.norm(b)
    return count[0], res, info


# --------------------------------------------------------------------------
def variants(d, big_nc):
    nc = cm.DEFAULT_NC[d][2]
    v = [(f"C2 nc{nc} r~=d (paper)", (nc, 1.0, 0.0)),
         (f"C2 nc{nc} r~=d g=0.1", (nc, 1.0, 0.1)),
         (f"C2 nc{nc} r~=d g=0.25", (nc, 1.0, 0.25)),
         (f"C2 nc{nc} r~=d g=0.5", (nc, 1.0, 0.5)),
         (f"C2 nc{nc} r~=1.5d g=0", (nc, 1.5, 0.0)),
         (f"C2 nc{nc} r~=1.5d g=1.25", (nc, 1.5, 1.25)),
         (f"C2 nc{big_nc} r~=d", (big_nc, 1.0, 0.0))]
    return v


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--dim", type=int, default=2)
    ap.add_argument("--m", type=int, default=3)
    ap.add_argument("--N", type=int, default=None)
    ap.add_argument("--seeds", type=int, nargs="*", default=[1, 2, 3])
    ap.add_argument("--only", type=str, nargs="*", default=None, help="variant indices (0..6), 'std'")
    ap.add_argument("--gmres", action="store_true")
    ap.add_argument("--no-uniform", action="store_true")
    args = ap.parse_args()
    d, m = args.dim, args.m
    N = args.N or (10 if d == 3 else 24)
    big_nc = 123 if d == 3 else 49
    V = variants(d, big_nc)
    sel_v = [int(s) for s in args.only if s != "std"] if args.only is not None else list(range(len(V)))
    do_std = args.only is None or "std" in args.only
    t0 = time.time()
    print(f"== {d}D, m = {m}, periodic box {N}^{d} nodes ({N**d * d} unknowns), bond-based, constant omega, "
          f"mu = 1, h = 1, pert {PERT} h")
    if args.gmres:
        print(f"   GMRES(50), Jacobi, K = -A + 1e-3 mean(diag(-A)) I, random rhs (seed 7), tol 1e-8 (preconditioned"
              f" residual), max 20000 iterations")
    print(HEAD)
    if not args.no_uniform and not args.gmres:
        for name, v in [V[i] for i in sel_v]:
            ev, n_c = uniform_eigs(d, m, N, v)
            print(line("uniform  " + name, stats(ev), f"n_c={n_c} (symbol)"), flush=True)
        if do_std:
            print(line("uniform  std", stats(uniform_std_eigs(d, m, N)), "(symbol)"), flush=True)
    if args.gmres and not args.no_uniform:
        g, x = box(d, N, 0.0, None)
        fams = families(x, N, float(m))
        for name, v in [V[i] for i in sel_v]:
            A, _, _ = assemble(d, m, fams, v, len(x))
            it, res, info = gmres_iters(A, np.random.default_rng(7))
            print(f"uniform  {name:34s} GMRES its {it:6d}  true res {res:.1e}  info {info}", flush=True)
        if do_std:
            A = standard_op(d, m, g, x, N, "frac1")
            it, res, info = gmres_iters(A, np.random.default_rng(7))
            print(f"uniform  {'std':34s} GMRES its {it:6d}  true res {res:.1e}  info {info}", flush=True)
    for seed in args.seeds:
        rng = np.random.default_rng(seed)
        g, x = box(d, N, PERT, rng)
        fams = families(x, N, float(m))
        for name, v in [V[i] for i in sel_v]:
            t1 = time.time()
            A, cond, mean_nc = assemble(d, m, fams, v, len(x))
            if args.gmres:
                it, res, info = gmres_iters(A, np.random.default_rng(7))
                print(f"seed {seed}   {name:34s} GMRES its {it:6d}  true res {res:.1e}  info {info}", flush=True)
                continue
            st = stats(np.linalg.eigvals(A), A)
            print(line(f"seed {seed}  {name}", st, f"mean n_c {mean_nc:.1f}, max cond A {cond:.1e},"
                                                  f" {time.time() - t1:.0f} s"), flush=True)
        if do_std:
            for mode in ("frac1", "pv"):
                A = standard_op(d, m, g, x, N, mode)
                if args.gmres:
                    it, res, info = gmres_iters(A, np.random.default_rng(7))
                    print(f"seed {seed}   {'std ' + mode:34s} GMRES its {it:6d}  true res {res:.1e}  info {info}",
                          flush=True)
                    continue
                asym = np.abs(A - A.T).max() / np.abs(A).max()
                ev = np.linalg.eigvalsh(0.5 * (A + A.T))
                st = stats(ev.astype(complex), None)
                st["spos"] = st["rpos"]
                print(line(f"seed {seed}  std {mode}", st, f"(symmetric, asym {asym:.0e})"), flush=True)
    print(f"{time.time() - t0:.0f} s")


if __name__ == "__main__":
    main()
