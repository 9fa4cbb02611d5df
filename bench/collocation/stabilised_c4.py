#!/usr/bin/python3
"""Consistent stabilisation of the collocation rows (C4 is unstable with the
Eq. 36 weight, r~ = delta; doc/collocation.md Sect. 7), and an alternative.

Row of node i (cloud C_i of n_c nodes, xi_0 = 0 the node itself):
    W_j = sum_alpha L_alpha Q[alpha, j]                     (doc Sect. 6)
(A) Stabilisation T, vanishing on polynomials of degree <= k:
    T(u) = gamma sum_{j != 0} s_j [ (u_j - u_i) - (p(xi_j) - p(0)) ],  p = P Q u
    T_j  = gamma ((s - S e_0)^T (I - M Q))_j,   S = sum_l s_l,  M[l, alpha] = P_alpha(xi_l)
         = gamma ( s_j [j != 0] - delta_j0 S - sum_l s_l sum_{alpha != 0} P_alpha(xi_l) Q[alpha, j] )
    s_j  = K(|xi_j|) V_ball / (n_c - 1)  (j != 0),  s_0 = 0,   V_ball = |B_delta|
    K(r) = kappa omega(r/delta) / r^q                  diffusion, q = 2
    K(r) = c omega(r/delta) / (d r)                    bond-based (trace of c omega xi xi^T / |xi|^3, over d)
    Elasticity: T_j I_d added to the d x d blocks ("iso").  Variants: s normalised so
    that sum_j s_j xi_jx^2 = L[x^2] ("moment"); for elasticity the bond blocks
    s_j = c omega / r e_j e_j^T V_ball/(n_c-1) in place of K I ("bondblk").
(B) Alternative, positive moment-matched row (LP): W_j >= 0 for j != 0 (bond-based:
    W_j = w_j e_j e_j^T, w_j >= 0), W_0 = -sum, with the same moment equations as the
    collocation row, sum_j W_j P_alpha(xi_j) = L_alpha for 1 <= |alpha| <= k, and the
    L1 mismatch of the degree-(k+2) moments minimised (linprog/HiGHS).  The collocation
    row is the solution of the same equations of least sum W_j^2 / omega~_j.

    /usr/bin/python3 bench/collocation/stabilised_c4.py             # everything (a few minutes)
    /usr/bin/python3 bench/collocation/stabilised_c4.py --quick     # coarser k-grids
    /usr/bin/python3 bench/collocation/stabilised_c4.py --part ex2  # one part: survey variants rt15 lp pert periodic ex2 c2
"""

import argparse
import math
import os
import sys
import time

import numpy as np
from scipy.optimize import linprog

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import check_moments as cm  # noqa: E402

GRID = (0.0, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 5.0, 10.0, 20.0)
VBALL = {1: lambda R: 2 * R, 2: lambda R: math.pi * R * R, 3: lambda R: 4 / 3 * math.pi * R**3}
Q_DIFF = 2
NK = {1: 2001, 2: 201, 3: 41}
CASES = [  # (d, k, nc, m)
    (1, 4, 11, 4), (1, 4, 11, 6), (1, 4, 11, 8), (1, 4, 11, 12),
    (1, 6, 13, 6), (1, 6, 13, 12),
    (2, 4, 49, 3), (2, 4, 49, 4), (2, 4, 49, 6),
    (3, 4, 123, 3), (3, 4, 123, 4),
    (2, 2, 29, 3), (2, 2, 29, 4), (3, 2, 33, 3), (3, 2, 33, 4),
]
ROWS = [(p, i) for p in ("diff", "bond") for i in ("constant", "conical")]


# --------------------------------------------------------------------------
# Rows
# --------------------------------------------------------------------------
def cloud(d, k, m, nc, rt=1.0, pert=0.0, rng=None, x=None):
    """Bond vectors of the collocation nodes (h = 1, delta = m), Q (physical
    basis), M (rows P(xi_l)), cond(A)."""
    delta = float(m)
    if x is None:
        x = cm.lattice_family(d, m, pert=pert, rng=rng)
    xi = x - x[0]
    sel = cm.select_collocation(xi, delta, nc)
    xi = xi[sel]
    basis = cm.monomials(d, k)
    Q, cond = cm.wls(xi, basis, delta, rt * delta)
    return xi, Q, cm.monomial_matrix(xi, basis), cond


def L_of(d, k, m, infl, phys):
    delta = float(m)
    if phys == "diff":
        return cm.L_diffusion(d, infl, delta, cm.micro_diffusivity(d, infl, delta, Q_DIFF), Q_DIFF, k)
    return cm.L_bond(d, infl, delta, cm.micromodulus(d, infl, delta), k)


def base_row(d, k, m, Q, infl, phys):
    """W (n_c,) for diffusion, (n_c, d, d) for bond-based."""
    L = L_of(d, k, m, infl, phys)
    return L @ Q if phys == "diff" else np.einsum("bai,ij->jba", L, Q)


def s_vector(d, m, xi, infl, phys, norm="vball", k=4):
    delta = float(m)
    r = np.linalg.norm(xi, axis=1)
    i0 = int(np.argmin(r))
    rr = np.where(r > 0, r, 1.0)
    om = cm.INFLUENCE[infl][0](r / delta)
    if phys == "diff":
        K = cm.micro_diffusivity(d, infl, delta, Q_DIFF) * om / rr**Q_DIFF
    else:
        K = cm.micromodulus(d, infl, delta) * om / rr / d
    s = K * VBALL[d](delta) / (len(xi) - 1)
    s[i0] = 0.0
    if norm == "moment":  # sum_j s_j xi_jx^2 = L[x^2] (bond: trace/d)
        L = L_of(d, 2, m, infl, phys)
        ix = cm.monomials(d, 2).index((2,) + (0,) * (d - 1))
        target = L[ix] if phys == "diff" else np.trace(L[:, :, ix]) / d
        s *= target / np.sum(s * xi[:, 0] ** 2)
    return s, i0


def T_row(s, i0, M, Q):
    """gamma = 1 row of the stabilisation: (s - S e_0)^T (I - M Q)."""
    v = s.copy()
    v[i0] -= s.sum()
    return v - (v @ M) @ Q


def T_row_bondblk(d, m, xi, infl, M, Q):
    """Bond-kernel blocks: v_j = c omega/r e e^T V/(n_c-1), v_0 = -sum; T = v - Q^T (M^T v)."""
    delta = float(m)
    r = np.linalg.norm(xi, axis=1)
    i0 = int(np.argmin(r))
    rr = np.where(r > 0, r, 1.0)
    e = xi / rr[:, None]
    w = cm.micromodulus(d, infl, delta) * cm.INFLUENCE[infl][0](r / delta) / rr * VBALL[d](delta) / (len(xi) - 1)
    w[i0] = 0.0
    v = w[:, None, None] * e[:, :, None] * e[:, None, :]
    v[i0] = -v.sum(0)
    mu = np.einsum("lba,li->iba", v, M)
    return v - np.einsum("ij,iba->jba", Q, mu)


def full_row(W, T, g, d):
    if W.ndim == 1 or T.ndim == 3:
        return W + g * T
    return W + g * T[:, None, None] * np.eye(d)[None]


def lp_row(d, k, m, xi, infl, phys, objective="next", perp=False):
    """Positive moment-matched row on the cloud xi (None if infeasible).  Bond-based:
    blocks w_j e_j e_j^T (+ z_j (I - e_j e_j^T) with perp), w, z >= 0."""
    r = np.linalg.norm(xi, axis=1)
    i0 = int(np.argmin(r))
    nz = np.where(r > 0)[0]
    k2 = k + 2
    basis = cm.monomials(d, k2)
    Mb = cm.monomial_matrix(xi[nz], basis)
    ia = [i for i, a in enumerate(basis) if 1 <= sum(a) <= k]
    ib = [i for i, a in enumerate(basis) if sum(a) == k2]
    L = L_of(d, k2, m, infl, phys)
    if phys == "diff":
        atoms = np.ones((len(nz), 1, 1))
        node = np.arange(len(nz))
        comps = [(Mb.T, L)]
    else:
        e = xi[nz] / r[nz, None]
        atoms = e[:, :, None] * e[:, None, :]
        node = np.arange(len(nz))
        if perp:
            atoms = np.concatenate([atoms, np.eye(d)[None] - atoms])
            node = np.concatenate([node, node])
        comps = [(atoms[:, b, a][None, :] * Mb[node].T, L[b, a]) for b in range(d) for a in range(b, d)]
    n = len(atoms)
    Aeq = np.concatenate([A[ia] for A, _ in comps])
    beq = np.concatenate([b[ia] for _, b in comps])
    sc = np.abs(Aeq).max(axis=1)
    sc[sc == 0] = 1.0
    if objective == "sum":
        res = linprog(np.ones(n), A_eq=Aeq / sc[:, None], b_eq=beq / sc, bounds=(0, None), method="highs")
    else:
        Ah = np.concatenate([A[ib] for A, _ in comps])
        bh = np.concatenate([b[ib] for _, b in comps])
        sh = np.abs(bh).max()
        nh = len(bh)
        c = np.concatenate([1e-6 * np.ones(n) / np.abs(L).max(), np.ones(nh)])
        Aub = np.vstack([np.hstack([Ah / sh, -np.eye(nh)]), np.hstack([-Ah / sh, -np.eye(nh)])])
        res = linprog(c, A_ub=Aub, b_ub=np.concatenate([bh / sh, -bh / sh]),
                      A_eq=np.hstack([Aeq / sc[:, None], np.zeros((len(beq), nh))]), b_eq=beq / sc,
                      bounds=(0, None), method="highs")
    if res.status != 0:
        return None
    w = res.x[:n].copy()
    # polish: the equality constraints to round-off on the support (HiGHS works to ~1e-9)
    w0 = w.copy()
    for _ in range(5):
        sup = w > 1e-12 * w.max()
        w[~sup] = 0.0
        w[sup] += np.linalg.lstsq(Aeq[:, sup], beq - Aeq @ w, rcond=None)[0]
        if w.min() >= 0:
            break
    else:
        w = np.maximum(w0, 0.0)  # keep the LP's own solution (equations to ~1e-9)
    blocks = np.zeros((len(xi), d, d) if phys == "bond" else (len(xi), 1, 1))
    np.add.at(blocks, nz[node], w[:, None, None] * atoms)
    blocks[i0] = -blocks[nz].sum(0)
    row = blocks[:, 0, 0].copy() if phys == "diff" else blocks
    # symmetrise over xi -> -xi where the cloud allows it (keeps constraints, positivity, objective)
    mirror = [np.where(np.all(np.abs(xi + xi[j]) < 1e-9, axis=1))[0] for j in range(len(xi))]
    if all(len(o) == 1 for o in mirror):
        row = 0.5 * (row + row[[o[0] for o in mirror]])
    return row


# --------------------------------------------------------------------------
# Symbols
# --------------------------------------------------------------------------
def kgrid(d, n):
    g = np.linspace(-math.pi, math.pi, n)
    return np.array(np.meshgrid(*([g] * d), indexing="ij")).reshape(d, -1).T


def symbol(R, xi, d, n):
    """sigma(k) = sum_j R_j cos(k.xi_j) (even stencils) on the n^d grid: (nk,) or (nk, d, d)."""
    kk = kgrid(d, n)
    out = np.empty((len(kk),) + R.shape[1:])
    for a in range(0, len(kk), 8192):
        C = np.cos(kk[a:a + 8192] @ xi.T)
        out[a:a + 8192] = np.tensordot(C, R, axes=(1, 0))
    return out


def eig_ext(sig):
    if sig.ndim == 1:
        return sig, sig
    ev = np.linalg.eigvalsh(sig)
    return ev[:, -1], ev[:, 0]


def evenness(R, xi):
    worst = 0.0
    for j in range(len(xi)):
        o = np.where(np.all(np.abs(xi + xi[j]) < 1e-9, axis=1))[0]
        if len(o) != 1:
            return np.inf
        worst = max(worst, float(np.max(np.abs(R[j] - R[o[0]]))))
    return worst / float(np.max(np.abs(R)))


def stab_interval_scalar(lmax, lmin, tau):
    """Exact gamma interval with max_k (lmax + gamma tau) <= 1e-9 |min| (isotropic T:
    eigenvalues shift by gamma tau(k))."""
    tol = 1e-9 * abs(lmin.min())
    pos = lmax > tol
    g_lo = 0.0
    if pos.any():
        if np.any(tau[pos] >= 0):
            return np.inf, np.nan
        g_lo = float(np.max((lmax[pos] - tol) / -tau[pos]))
    tp = tau > 1e-10 * abs(lmin.min())
    g_hi = float(np.min((tol - lmax[tp]) / tau[tp])) if tp.any() else np.inf
    return g_lo, g_hi


def stab_interval_matrix(sW, sT):
    """Same on a gamma grid (~3 % steps) for matrix-valued T."""
    gs = np.concatenate([[0.0], np.geomspace(0.01, 100, 241)])
    ok = []
    for g in gs:
        lmax, lmin = eig_ext(sW + g * sT)
        ok.append(lmax.max() <= 1e-9 * abs(lmin.min()))
    ok = np.array(ok)
    if not ok.any():
        return np.inf, np.nan
    i = int(np.argmax(ok))
    j = i
    while j + 1 < len(gs) and ok[j + 1]:
        j += 1
    return gs[i], (np.inf if j == len(gs) - 1 else gs[j])


_QUAD = {}


def exact_symbol(d, m, infl, phys, kv):
    key = (d, m, infl)
    if key not in _QUAD:
        _QUAD[key] = cm.Quad(d, infl, float(m), 0, nr=60, nphi=96, nt=48)
    Qd = _QUAD[key]
    delta = float(m)
    ph = np.cos(Qd.pts @ kv) - 1
    if phys == "diff":
        return np.sum(Qd.w * cm.micro_diffusivity(d, infl, delta, Q_DIFF) * Qd.om / Qd.r**Q_DIFF * ph)
    return np.einsum("n,na,nb->ab", Qd.w * cm.micromodulus(d, infl, delta) * Qd.om / Qd.r**3 * ph, Qd.pts, Qd.pts)


def sym_err(R, xi, d, m, infl, phys, kd):
    """Relative error of the row's symbol against the exact PD symbol, |k| delta = kd,
    direction (1, 0.37, 0.21) normalised (as the err column of the doc, Sect. 7);
    bond-based: spectral norm of the d x d difference over that of the exact."""
    dirn = np.array([1.0, 0.37, 0.21][:d])
    kv = kd / m * dirn / np.linalg.norm(dirn)
    ex = exact_symbol(d, m, infl, phys, kv)
    sg = np.tensordot(np.cos(xi @ kv), R, axes=(0, 0))
    if np.ndim(ex) == 0:
        return abs(sg - ex) / abs(ex)
    return np.linalg.norm(sg - ex, 2) / np.linalg.norm(ex, 2)


def standard_min(d, m, infl, phys, n):
    """Most negative symbol eigenvalue of the standard meshfree scheme (whole family,
    V_j = h^d = 1, no partial volumes): the explicit-step reference."""
    x = cm.lattice_family(d, m)
    xi = x - x[0]
    r = np.linalg.norm(xi, axis=1)
    nz = r > 0
    rr = np.where(nz, r, 1.0)
    om = cm.INFLUENCE[infl][0](r / m) * nz
    if phys == "diff":
        R = cm.micro_diffusivity(d, infl, float(m), Q_DIFF) * om / rr**Q_DIFF
    else:
        e = xi / rr[:, None]
        R = (cm.micromodulus(d, infl, float(m)) * om / rr)[:, None, None] * e[:, :, None] * e[:, None, :]
    R[0] = -R.sum(0)
    return eig_ext(symbol(R, xi, d, n))[1].min()


# --------------------------------------------------------------------------
# Part 1: survey of the brief's T (iso, s = vball)
# --------------------------------------------------------------------------
def survey(nk, norm="vball", rt=1.0, cases=CASES, title=""):
    print(f"\n== {title}T with s '{norm}', isotropic blocks, r~ = {rt} delta; k-grid 1D {nk[1]}, "
          f"2D {nk[2]}^2, 3D {nk[3]}^3")
    print("   r0: max+/|min| of the symbol at gamma = 0 (> 0: growing modes); [g_lo, g_hi]: exact interval of"
          " stabilising gamma;\n   g*: smallest gamma of the grid 0,.05,.1,.2,.5,1,2,5,10,20 in it; err1/err2:"
          " symbol rel. error at |k|delta = 1/2 (gamma 0 / g*);\n   min: most negative symbol eigenvalue "
          "(h = 1) at gamma 0 / g*; std: the same for the standard scheme (V = h^d)")
    print(f"{'case':>17s} {'phys':4s} {'infl':4s} {'r0':>9s} {'g_lo':>6s} {'g_hi':>6s} {'g*':>4s}"
          f" {'err1 0':>8s} {'err1 g*':>8s} {'err2 0':>8s} {'err2 g*':>8s} {'min 0':>7s} {'min g*':>7s} {'std':>7s}")
    out = []
    for d, k, nc, m in cases:
        xi, Q, M, cond = cloud(d, k, m, nc, rt)
        for phys, infl in ROWS:
            W = base_row(d, k, m, Q, infl, phys)
            s, i0 = s_vector(d, m, xi, infl, phys, norm)
            T = T_row(s, i0, M, Q)
            assert evenness(full_row(W, T, 1.0, d), xi) < 1e-10
            lmax, lmin = eig_ext(symbol(W, xi, d, nk[d]))
            tau = symbol(T, xi, d, nk[d])
            glo, ghi = stab_interval_scalar(lmax, lmin, tau)
            gst = next((g for g in GRID if glo <= g <= ghi), None)
            r0 = lmax.max() / abs(lmin.min())
            e = [sym_err(W, xi, d, m, infl, phys, kd) for kd in (1.0, 2.0)]
            es, mins = [np.nan, np.nan], np.nan
            if gst is not None:
                Ws = full_row(W, T, gst, d)
                es = [sym_err(Ws, xi, d, m, infl, phys, kd) for kd in (1.0, 2.0)]
                mins = (lmin + gst * tau).min()
            std = standard_min(d, m, infl, phys, nk[d])
            name = f"{d}D C{k} nc{len(xi)} m{m}"
            print(f"{name:>17s} {phys:4s} {infl[:4]:4s} {r0:+9.2e} {glo:6.3f} {ghi:6.3g} {gst if gst is not None else '-':>4}"
                  f" {e[0]:8.1e} {es[0]:8.1e} {e[1]:8.1e} {es[1]:8.1e} {lmin.min():7.3g} {mins:7.3g} {std:7.3g}",
                  flush=True)
            out.append(dict(d=d, k=k, m=m, nc=len(xi), phys=phys, infl=infl, glo=glo, ghi=ghi, xi=xi, W=W, T=T,
                            lmax=lmax, lmin=lmin, tau=tau))
    return out


def common_gamma(out):
    print("\n== One gamma for all?  Intersection of the stabilising intervals, and the cost at that gamma")
    groups = [("all rows", lambda o: True), ("all C4 rows", lambda o: o["k"] == 4),
              ("C4, 1D", lambda o: o["k"] == 4 and o["d"] == 1),
              ("C4, 2D+3D", lambda o: o["k"] == 4 and o["d"] > 1),
              ("C4, 2D+3D diffusion", lambda o: o["k"] == 4 and o["d"] > 1 and o["phys"] == "diff"),
              ("C4, 2D+3D bond", lambda o: o["k"] == 4 and o["d"] > 1 and o["phys"] == "bond"),
              ("C2 + C6 rows (stable at 0)", lambda o: o["k"] != 4)]
    for name, f in groups:
        sel = [o for o in out if f(o)]
        lo = max(o["glo"] for o in sel)
        hi = min(o["ghi"] for o in sel)
        arg_lo = max(sel, key=lambda o: o["glo"])
        arg_hi = min(sel, key=lambda o: o["ghi"])
        print(f"  {name:28s}: [{lo:.3g}, {hi:.3g}]  {'EMPTY' if lo > hi else ''}"
              f"   (lo set by {arg_lo['d']}D C{arg_lo['k']} m{arg_lo['m']} {arg_lo['phys']} {arg_lo['infl']};"
              f" hi by {arg_hi['d']}D C{arg_hi['k']} m{arg_hi['m']} {arg_hi['phys']} {arg_hi['infl']})")
    for g in (1.0, 1.25, 2.0, 5.0):
        okc = [o for o in out if o["glo"] <= g <= o["ghi"]]
        bad = [f"{o['d']}D C{o['k']} m{o['m']} {o['phys'][:4]} {o['infl'][:4]}" for o in out if not (o["glo"] <= g <= o["ghi"])]
        print(f"  gamma = {g:g} stabilises {len(okc)}/{len(out)} rows; not: {', '.join(bad)}")


def variants(nk, cases=CASES):
    print("\n== Variants of s: exact stabilising interval [g_lo, g_hi] per row "
          "(diff const | diff con | bond const | bond con)")
    print("   vball: the brief's s; moment: s rescaled so that sum s xi_x^2 = L[x^2]; bondblk (bond rows only):"
          " T from the bond-kernel blocks (grid, ~3 %)")
    for d, k, nc, m in cases:
        xi, Q, M, cond = cloud(d, k, m, nc)
        line = f"{d}D C{k} m{m:2d} "
        for norm in ("vball", "moment", "bondblk"):
            line += f" {norm}:"
            for phys, infl in ROWS:
                if norm == "bondblk" and phys == "diff":
                    continue
                W = base_row(d, k, m, Q, infl, phys)
                if norm == "bondblk":
                    T = T_row_bondblk(d, m, xi, infl, M, Q)
                    glo, ghi = stab_interval_matrix(symbol(W, xi, d, nk[d]), symbol(T, xi, d, nk[d]))
                else:
                    s, i0 = s_vector(d, m, xi, infl, phys, norm)
                    T = T_row(s, i0, M, Q)
                    lmax, lmin = eig_ext(symbol(W, xi, d, nk[d]))
                    glo, ghi = stab_interval_scalar(lmax, lmin, symbol(T, xi, d, nk[d]))
                line += f" [{glo:.2f},{ghi:.3g}]"
        print(line, flush=True)


# --------------------------------------------------------------------------
# Part 2: r~ = 1.5 delta
# --------------------------------------------------------------------------
def rt15(nk):
    print("\n== r~ = 1.5 delta (C4 cases, and 2D C2 m4), no stabilisation and with T: "
          "r0, [g_lo, g_hi], err1/err2 at gamma 0, min at gamma 0")
    print(f"{'case':>17s} {'phys':4s} {'infl':4s} {'r0 rt1.5':>9s} {'g_lo':>6s} {'g_hi':>6s} {'err1':>8s} {'err2':>8s}"
          f" {'min':>7s}")
    for d, k, nc, m in [c for c in CASES if c[1] == 4] + [(2, 2, 29, 4)]:
        xi, Q, M, cond = cloud(d, k, m, nc, 1.5)
        for phys, infl in ROWS:
            W = base_row(d, k, m, Q, infl, phys)
            s, i0 = s_vector(d, m, xi, infl, phys)
            T = T_row(s, i0, M, Q)
            lmax, lmin = eig_ext(symbol(W, xi, d, nk[d]))
            glo, ghi = stab_interval_scalar(lmax, lmin, symbol(T, xi, d, nk[d]))
            e = [sym_err(W, xi, d, m, infl, phys, kd) for kd in (1.0, 2.0)]
            print(f"{d}D C{k} nc{len(xi)} m{m:<3d} {phys:4s} {infl[:4]:4s} {lmax.max() / abs(lmin.min()):+9.2e}"
                  f" {glo:6.3f} {ghi:6.3g} {e[0]:8.1e} {e[1]:8.1e} {lmin.min():7.3g}", flush=True)


def fixed_gamma(nk, rt, gammas, cases=CASES):
    """Per row at fixed gammas: max+/|min| (<= 0: stable), err1, err2, min."""
    print(f"\n== r~ = {rt} delta, fixed gamma: per gamma 'r err1 err2 min' (r = max+/|min|, <= 0 stable)")
    tally = {g: 0 for g in gammas}
    n = 0
    for d, k, nc, m in cases:
        xi, Q, M, cond = cloud(d, k, m, nc, rt)
        for phys, infl in ROWS:
            W = base_row(d, k, m, Q, infl, phys)
            s, i0 = s_vector(d, m, xi, infl, phys)
            T = T_row(s, i0, M, Q)
            lmax, lmin = eig_ext(symbol(W, xi, d, nk[d]))
            tau = symbol(T, xi, d, nk[d])
            line = f"{d}D C{k} nc{len(xi)} m{m:<3d} {phys:4s} {infl[:4]:4s}"
            n += 1
            for g in gammas:
                a, b = (lmax + g * tau), (lmin + g * tau)
                r = a.max() / abs(b.min())
                tally[g] += r <= 1e-9
                R = full_row(W, T, g, d)
                line += (f" | {r:+8.1e} {sym_err(R, xi, d, m, infl, phys, 1.0):7.1e}"
                         f" {sym_err(R, xi, d, m, infl, phys, 2.0):7.1e} {b.min():6.3g}")
            print(line, flush=True)
    print("   stable rows: " + ", ".join(f"gamma {g:g}: {tally[g]}/{n}" for g in gammas))


# --------------------------------------------------------------------------
# Part 3: positive moment-matched rows
# --------------------------------------------------------------------------
def lp_table(nk):
    print("\n== (B) positive moment-matched row (LP) on the same cloud: max+/|min| (<= 0 by construction),"
          " err1/err2, min, entries")
    print(f"{'case':>17s} {'phys':4s} {'infl':4s} {'cloud':>6s} {'r':>9s} {'err1':>8s} {'err2':>8s} {'min':>7s}"
          f" {'nnz':>4s} {'max|WM-L|':>9s}   (collocation: err1 err2 min)")
    for d, k, nc, m in CASES:
        for phys, infl in ROWS:
            xi, Q, M, cond = cloud(d, k, m, nc)
            W = base_row(d, k, m, Q, infl, phys)
            R = lp_row(d, k, m, xi, infl, phys)
            where = "cloud"
            if R is None:  # fall back: the whole family
                x = cm.lattice_family(d, m)
                xi = x - x[0]
                R = lp_row(d, k, m, xi, infl, phys)
                where = "family"
            if R is None:
                print(f"{d}D C{k} m{m}: infeasible")
                continue
            M2 = cm.monomial_matrix(xi, cm.monomials(d, k))
            L = L_of(d, k, m, infl, phys)
            rep = np.abs(R.T @ M2 - L.T).max() / np.abs(L).max() if R.ndim == 1 else \
                np.abs(np.einsum("jba,ji->bai", R, M2) - L).max() / np.abs(L).max()
            lmax, lmin = eig_ext(symbol(R, xi, d, nk[d]))
            lw = eig_ext(symbol(W, cloud(d, k, m, nc)[0], d, nk[d]))[1].min()
            xic = cloud(d, k, m, nc)[0]
            nnz = int(np.sum(np.abs(R if R.ndim == 1 else R.reshape(len(R), -1).sum(1)) > 0)) - 1
            print(f"{d}D C{k} nc{len(xic)} m{m:<3d} {phys:4s} {infl[:4]:4s} {where:>6s} {lmax.max() / abs(lmin.min()):+9.1e}"
                  f" {sym_err(R, xi, d, m, infl, phys, 1.0):8.1e} {sym_err(R, xi, d, m, infl, phys, 2.0):8.1e}"
                  f" {lmin.min():7.3g} {nnz:4d} {rep:9.1e}   ({sym_err(W, xic, d, m, infl, phys, 1.0):.1e}"
                  f" {sym_err(W, xic, d, m, infl, phys, 2.0):.1e} {lw:.3g})", flush=True)


# --------------------------------------------------------------------------
# Part 4: perturbed clouds
# --------------------------------------------------------------------------
def perturbed_check(rng, gammas=(1.0, 5.0), n=5, rt=1.0):
    print(f"\n== Perturbed clouds, 2D C4 m = 4, pert 0.35 h, r~ = {rt} delta: rows on random quartics, "
          f"max |row.u - L.a| / max |L.a| (gamma = {', '.join(str(g) for g in gammas)}; LP row)")
    d, k, m = 2, 4, 4
    basis = cm.monomials(d, k)
    worst = worst_lp = 0.0
    print(f"{'cloud':>5s} {'n_c':>4s} {'cond A':>8s} {'phys':4s} {'infl':4s} {'gamma=0':>9s}"
          + "".join(f" {'gamma=' + str(g):>9s}" for g in gammas) + f" {'LP row':>9s} {'|T.u|/|T|1|u|':>14s}")
    for t in range(n):
        xi, Q, M, cond = cloud(d, k, m, 49, rt=rt, pert=0.35, rng=rng)
        x0 = rng.uniform(-1, 1, d)
        for phys, infl in ROWS:
            W = base_row(d, k, m, Q, infl, phys)
            s, i0 = s_vector(d, m, xi, infl, phys)
            T = T_row(s, i0, M, Q)
            Rlp = lp_row(d, k, m, xi, infl, phys)
            L = L_of(d, k, m, infl, phys)
            nc_ = 1 if phys == "diff" else d
            u = cm.Poly(d, nc_, k, rng)
            uv = u(x0 + xi)
            a = u.taylor(x0, basis)
            ex = (L @ a[0])[None] if phys == "diff" else np.einsum("bai,ai->b", L, a)
            errs = []
            for R in [W] + [full_row(W, T, g, d) for g in gammas] + [Rlp]:
                if R is None:
                    errs.append(np.nan)
                    continue
                st = (R @ uv[:, 0])[None] if phys == "diff" else np.einsum("jba,ja->b", R, uv)
                errs.append(np.abs(st - ex).max() / np.abs(ex).max())
            worst = max(worst, np.nanmax(errs[:-1]))
            worst_lp = max(worst_lp, errs[-1])
            tu = np.abs(T @ uv).max() / (np.abs(T).sum() * np.abs(uv).max())
            print(f"{t:5d} {len(xi):4d} {cond:8.1e} {phys:4s} {infl[:4]:4s}" + "".join(f" {e:9.1e}" for e in errs)
                  + f" {tu:14.1e}")
    print(f"   worst T rows {worst:.1e}: {'PASS' if worst < 1e-10 else 'FAIL'} at 1e-10;"
          f" LP rows {worst_lp:.1e}: {'PASS' if worst_lp < 1e-10 else 'FAIL'}")


def periodic_box(rng, gammas=(0.0, 1.0, 5.0), nper=16, m=4, phys="diff", infl="constant", rt=1.0):
    """A periodic nper x nper box of nodes perturbed by 0.35 h, per-node rows: the
    eigenvalues of the assembled operator (T rows for each gamma, and the LP rows)."""
    d, k, nc = 2, 4, 49
    delta = float(m)
    g = np.array([(a, b) for a in range(nper) for b in range(nper)], float)
    x = g + rng.uniform(-0.35, 0.35, g.shape)
    N = len(x)
    nd = 1 if phys == "diff" else d
    A = {gm: np.zeros((N * nd, N * nd)) for gm in list(gammas) + ["LP"]}
    shifts = np.array([(a, b) for a in range(-1, 2) for b in range(-1, 2)], float) * nper
    nfall = [0, 0, 0]
    for i in range(N):
        xs, ids = [], []
        for sh in shifts:
            dx = x + sh - x[i]
            w = np.where(np.linalg.norm(dx, axis=1) <= delta * (1 + 1e-12))[0]
            xs.append(dx[w])
            ids.append(w)
        xs, ids = np.concatenate(xs), np.concatenate(ids)
        order = np.argsort(np.linalg.norm(xs, axis=1), kind="stable")
        xs, ids = xs[order], ids[order]
        sel = cm.select_collocation(xs, delta, nc)
        xi, cols = xs[sel], ids[sel]
        basis = cm.monomials(d, k)
        Q, _ = cm.wls(xi, basis, delta, rt * delta)
        M = cm.monomial_matrix(xi, basis)
        W = base_row(d, k, m, Q, infl, phys)
        s, i0 = s_vector(d, m, xi, infl, phys)
        T = T_row(s, i0, M, Q)
        rows = {gm: full_row(W, T, gm, d) for gm in gammas}
        rows["LP"] = lp_row(d, k, m, xi, infl, phys)
        colsets = {key: cols for key in rows}
        if rows["LP"] is None and phys == "bond":  # fall back 1: perpendicular atoms too
            nfall[0] += 1
            rows["LP"] = lp_row(d, k, m, xi, infl, phys, perp=True)
        if rows["LP"] is None:  # fall back 2: the whole family
            nfall[1] += 1
            rows["LP"] = lp_row(d, k, m, xs, infl, phys, perp=(phys == "bond"))
            colsets["LP"] = ids
            if rows["LP"] is None:
                nfall[2] += 1
        for key, R in rows.items():
            if R is None:
                A[key][:] = np.nan
                continue
            cols = colsets[key]
            if nd == 1:
                np.add.at(A[key][i], cols, R)
            else:
                for b in range(d):
                    for a in range(d):
                        np.add.at(A[key][i * d + b], cols * d + a, R[:, b, a])
    res = {}
    for key, Am in A.items():
        if np.isnan(Am).any():
            res[key] = None
            continue
        ev = np.linalg.eigvals(Am)
        res[key] = (ev.real.max(), ev.real.min())
    res["nfall"] = nfall
    return res


# --------------------------------------------------------------------------
# Part 5: Example 2
# --------------------------------------------------------------------------
def example2(gammas=(0.0, 0.5, 1.0, 1.25, 2.0, 5.0)):
    """check_moments.example2_spectrum with the stabilised rows and the LP row."""
    n, m = 39, 4
    h = 1.0 / n
    delta = m * h
    c = (np.arange(n) + 0.5) * h - 0.5
    P = np.stack(np.meshgrid(c, c, indexing="ij"), -1).reshape(-1, 2)
    grid = np.rint(P / h - 0.5 + n / 2).astype(int)
    index = {tuple(g): i for i, g in enumerate(grid)}
    free = np.where((np.abs(P) < 0.5 - delta + 1e-12).all(1))[0]
    pos = {g: i for i, g in enumerate(free)}
    print(f"\n== Example 2 ({len(P)} nodes, {len(free)} free, delta = 4h, q = 2, constant, K = 1): eigenvalues (1/s)")
    print(f"{'row':>5s} {'r~':>4s} {'gamma':>6s} {'max Re':>11s} {'min Re':>11s} {'2/|min Re|':>10s}")

    def spectrum(row, offs):
        A = np.zeros((len(free), len(free)))
        for r, i in enumerate(free):
            for wj, o in zip(row, offs):
                j = index[tuple(grid[i] + o)]
                if j in pos:
                    A[r, pos[j]] += wj
        ev = np.linalg.eigvals(A)
        return ev.real.max(), ev.real.min()

    for k in (2, 4):
        for rt in (1.0, 1.5):
            xi1, Q, M, _ = cloud(2, k, m, cm.DEFAULT_NC[2][k], rt)  # h = 1 units
            offs = np.rint(xi1).astype(int)
            W = base_row(2, k, m, Q, "constant", "diff") / h**2
            s, i0 = s_vector(2, m, xi1, "constant", "diff")
            T = T_row(s, i0, M, Q) / h**2
            for g in gammas:
                a, b = spectrum(W + g * T, offs)
                print(f"{'C' + str(k):>5s} {rt:4.1f} {g:6g} {a:+11.3e} {b:+11.3e} {2 / abs(b):10.2e}", flush=True)
        if k == 4:
            xi1 = cloud(2, k, m, 49)[0]
            R = lp_row(2, k, m, xi1, "constant", "diff") / h**2
            a, b = spectrum(R, np.rint(xi1).astype(int))
            print(f"{'C4 LP':>5s} {'-':>4s} {'-':>6s} {a:+11.3e} {b:+11.3e} {2 / abs(b):10.2e}")
            x = cm.lattice_family(2, m)
            a, b = spectrum(standard_row_ex2(m) / h**2, np.rint(x).astype(int))
            print(f"{'std':>5s} {'-':>4s} {'-':>6s} {a:+11.3e} {b:+11.3e} {2 / abs(b):10.2e}   (standard scheme, V = h^2)")


def standard_row_ex2(m):
    x = cm.lattice_family(2, m)
    r = np.linalg.norm(x, axis=1)
    R = np.where(r > 0, cm.micro_diffusivity(2, "constant", float(m), 2) / np.where(r > 0, r, 1) ** 2, 0.0)
    R[0] = -R.sum()
    return R


# --------------------------------------------------------------------------
# Part c2: the order-2 lattice row, the paper's against the stabilised one
# --------------------------------------------------------------------------
C2_CASES = [(1, 5, 3), (1, 5, 6), (2, 29, 3), (2, 29, 4), (2, 29, 6), (3, 33, 3), (3, 33, 4)]


def c2_lattice(nk):
    """Doc Sect. 7.3: for each C2 lattice row, the paper's (r~ = delta) and the
    stabilised one (r~ = 1.5 delta, gamma = 1.25): the relative symbol error at
    |k| delta = 1 and 3, the most negative symbol value over that of the
    standard meshfree scheme (whole family, V_j = h^d; the explicit step goes
    like its inverse square root) and the largest symbol value over |min|
    (> 0: growing modes)."""
    print("\n== C2 lattice rows: paper (r~ = delta) | stabilised (r~ = 1.5 delta, gamma = 1.25)")
    print(f"  {'d':>1s} {'m':>2s} {'row':14s} {'err kd=1':>17s} {'err kd=3':>17s} {'min/min_std':>11s} {'max/|min|':>19s}")
    for d, nc, m in C2_CASES:
        n = nk[d] if d < 3 else min(nk[d], 25)
        for phys in ("diff", "bond"):
            for infl in ("constant", "conical"):
                smin = standard_min(d, m, infl, phys, n)
                res = []
                for rt, g in ((1.0, 0.0), (1.5, 1.25)):
                    xi, Q, M, _ = cloud(d, 2, m, nc, rt)
                    W = base_row(d, 2, m, Q, infl, phys)
                    if g:
                        s, i0 = s_vector(d, m, xi, infl, phys)
                        W = full_row(W, T_row(s, i0, M, Q), g, d)
                    lmax, lmin = eig_ext(symbol(W, xi, d, n))
                    res.append((sym_err(W, xi, d, m, infl, phys, 1.0), sym_err(W, xi, d, m, infl, phys, 3.0),
                                lmin.min() / smin, lmax.max() / abs(lmin.min())))
                a, b = res
                print(f"  {d} {m:2d} {phys + ' ' + infl:14s} {a[0]:.1e} | {b[0]:.1e}  {a[1]:.1e} | {b[1]:.1e}"
                      f"  {a[2]:4.2f} | {b[2]:4.2f}  {a[3]:+.0e} | {b[3]:+.0e}", flush=True)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--part", default="all")
    args = ap.parse_args()
    nk = {1: 501, 2: 81, 3: 21} if args.quick else NK
    rng = np.random.default_rng(2024)
    t0 = time.time()
    p = args.part
    if p in ("all", "survey"):
        out = survey(nk, title="(A) ")
        common_gamma(out)
    if p in ("all", "variants"):
        variants(nk)
    if p in ("all", "rt15"):
        out15 = survey(nk, rt=1.5, title="(A') r~ = 1.5 delta: ")
        common_gamma(out15)
    if p in ("all", "fixed"):
        fixed_gamma(nk, 1.0, (1.0, 2.0, 5.0))
        fixed_gamma(nk, 1.5, (0.0, 1.0, 1.25, 2.0))
    if p in ("all", "lp"):
        lp_table(nk)
    if p in ("all", "pert"):
        perturbed_check(rng)
        perturbed_check(rng, gammas=(1.0, 1.25), rt=1.5)
    if p in ("all", "periodic"):
        print("\n== Periodic 16 x 16 box, 2D C4 m = 4, nodes perturbed by 0.35 h, per-node rows: "
              "max Re / min Re of the eigenvalues")
        for rt, gms, phys, nbox in ((1.0, (0.0, 1.0, 5.0), "diff", 3), (1.0, (0.0, 1.0, 5.0), "bond", 2),
                                     (1.5, (0.0, 1.0, 1.25), "diff", 2), (1.5, (0.0, 1.0, 1.25), "bond", 2)):
            print(f"  r~ = {rt} delta")
            for t in range(nbox):
                r = periodic_box(rng, gammas=gms, phys=phys, rt=rt)
                nf = r.pop("nfall")
                print(f"  {phys} constant box {t} (LP fall-backs: {nf[0]} perp atoms, {nf[1]} whole family, {nf[2]} infeasible): " + "  ".join(
                    f"{'g=' + str(key) if key != 'LP' else 'LP'}: {v[0]:+.2e}/{v[1]:.2e}" if v else f"{key}: infeasible"
                    for key, v in r.items()), flush=True)
    if p in ("all", "ex2"):
        example2()
    if p in ("all", "c2"):
        c2_lattice(nk)
    print(f"\n{time.time() - t0:.0f} s")


if __name__ == "__main__":
    main()
