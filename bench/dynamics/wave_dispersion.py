#!/usr/bin/env python3
"""Elastic wave in a plate: PeriDEAL's explicit dynamics against references
computed here, independently of the C++ code.

The problem (wave_dispersion.prm.in): bond-based PMB in plane stress
(nu = 1/3), constant influence, 'full' partial volumes (every neighbour cell
whose centre lies within the horizon counts with its whole area h^2), small
strain, no failure. The initial displacement u_x = A exp(-(x/w)^2), u_y = 0
at rest is a plane longitudinal pulse that splits into two halves.

References at a probe node x (derivation: doc/explicit-dynamics.md,
"Elastic wave: dispersion"):

* lattice PD, semi-discrete: the infinite lattice with the code's
  neighbours and weights,
      rho omega(k)^2 = sum_j c/|xi_j| (xi_jx/|xi_j|)^2 (1 - cos k xi_jx) h^2,
      u(x, t) = (1/pi) int_0^inf A_hat(k) cos(k x) cos(omega(k) t) dk,
  A_hat(k) = A w sqrt(pi) exp(-k^2 w^2 / 4), by composite Gauss-Legendre
  quadrature;
* lattice PD with velocity Verlet: the same with omega replaced by Omega,
  cos(Omega dt) = 1 - (omega dt)^2 / 2: the exact solution of the discrete
  problem the code solves (equal to round-off);
* continuum PD: rho omega^2 = c int_0^2pi cos^2 th (delta - sin(k delta
  cos th)/(k cos th)) d th;
* classical: d'Alembert with c_p^2 = E / ((1 - nu^2) rho), and with the
  lattice's long-wave speed c_lat (which differs from c_p by the quadrature
  error of the 'full' rule).

Subcommands:
  prm TEMPLATE DIR M W_OVER_DELTA DT_DIV [energy] [VARIANT]
      write DIR/input.prm and DIR/case.json for one case (VARIANT: one of
      VARIANTS, pmb2d by default);
  check DIR TOL_VERLET TOL_ENERGY TOL_DRIFT
      the ctest assertions on one run (tests/dynamics/wave_dispersion_check.sh);
  report OUT_DIR CASE...
      wave_dispersion.csv and wave_dispersion.png of the benchmark.
"""
import csv
import json
import math
import re
import sys

import numpy as np

E = 72e9           # Young's modulus (Pa)
RHO = 2440.0       # density (kg/m^3)
NU = 1.0 / 3.0     # the only Poisson's ratio of bond-based plane stress
A = 1e-6           # pulse amplitude (m); small strain: the problem is linear
DELTA = 3 * 2.0**-10   # horizon (m); h = DELTA / m is exact in binary
PROBES_IN_DELTA = (0, 5, 10, 20)
C_P = math.sqrt(E / ((1 - NU**2) * RHO))

# The model variants: "pmb2d" is the case above (the benchmark's); the
# others are cheap ctest variants (tests/dynamics/wave_dispersion_check.sh)
# of the same plane longitudinal pulse: LPS in 2D (plane strain) and 3D,
# bond-based in 3D (Poisson's ratio 1/4). In 3D the body is a box whose
# cross-section is sized like the plate, so that nothing from the free
# faces reaches the probes; to keep it small (m = 2, w = delta) the probes
# are fewer and nearer (0, 1.5 and 3 horizons) and the run ends once the
# peak has passed the last one.
VARIANTS = {
    "pmb2d": {"dim": 2, "lps": False, "nu": 1.0 / 3.0, "plane": "plane stress"},
    "lps2d": {"dim": 2, "lps": True, "nu": 0.3, "plane": "plane strain"},
    "pmb3d": {"dim": 3, "lps": False, "nu": 0.25, "plane": None},
    "lps3d": {"dim": 3, "lps": True, "nu": 0.3, "plane": None},
}


def moduli(variant="pmb2d"):
    """(mu, K, the planar or 3D bulk modulus kappa, c_p) of a variant; c_p
    from the P-wave modulus (plane stress: E / (1 - nu^2))."""
    v = VARIANTS[variant]
    nu = v["nu"]
    mu = E / (2 * (1 + nu))
    K = E / (3 * (1 - 2 * nu))
    if v["dim"] == 3:
        kappa = K
    elif v["plane"] == "plane strain":
        kappa = K + mu / 3
    else:
        kappa = 9 * K * mu / (3 * K + 4 * mu)
    M = E / (1 - nu**2) if v["plane"] == "plane stress" else \
        E * (1 - nu) / ((1 + nu) * (1 - 2 * nu))
    return mu, K, kappa, math.sqrt(M / RHO)


def micromodulus(delta, variant="pmb2d"):
    """c of source/models/bond_based.cc with constant influence: 8 mu /
    (pi delta^3 M2), M2 = 1/3, in 2D (9E/(pi delta^3) in plane stress);
    15 mu / (2 pi delta^4 M3), M3 = 1/4, in 3D."""
    mu = moduli(variant)[0]
    if VARIANTS[variant]["dim"] == 3:
        return 15 * mu / (2 * math.pi * delta**4 / 4)
    return 8 * mu / (math.pi * delta**3 / 3)


def stencil(m, dim=2):
    """Integer offsets o != 0 with |o| <= m: the neighbours whose cell centre
    lies in the closed horizon ball ('full' partial volumes)."""
    n = int(math.ceil(m))
    r = range(-n, n + 1)
    offsets = [(i, j) for i in r for j in r] if dim == 2 else \
        [(i, j, l) for i in r for j in r for l in r]
    return np.array([o for o in offsets if 0 < sum(x * x for x in o) <= m * m],
                    float)


def bond_constants(m, variant="pmb2d"):
    """(xi, C) over the stencil of a bond-based variant: xi in metres,
    C = c/|xi| h^d, so that the linearised force density on node i is
    sum_j C n (n . (u_j - u_i))."""
    dim = VARIANTS[variant]["dim"]
    h = DELTA / m
    xi = stencil(m, dim) * h
    r = np.sqrt((xi**2).sum(axis=1))
    return xi, micromodulus(DELTA, variant) / r * h**dim


def acoustic_tensor(kvec, m, variant="pmb2d"):
    """rho omega^2 of the plane waves u = u_hat exp(i k.x) of the infinite
    lattice are the eigenvalues of D(k) (rows of kvec: wave vectors; result
    (n_k, d, d)), 1 - cos written 2 sin^2(./2) (no cancellation at small k).

    Bond-based: D = sum_j C_j n_j n_j^T (1 - cos k.xi_j).
    LPS (constant influence, bulk node, w = h^d, m_w = sum_j |xi_j|^2 w;
    t_ij = (c_K |xi| theta_i + c_mu e_ij) / m_w, theta_i = (d / m_w) sum_j
    |xi_j| w e_ij, source/models/linear_peridynamic_solid.cc; with
    e_ij = n . u_hat (exp(i k.xi) - 1) the cosine part of theta cancels
    between xi and -xi, and so does the sine part of the bond term):
      D = (2 c_mu / m_w) sum_j w (1 - cos k.xi_j) n_j n_j^T
          + (d c_K / m_w^2) G G^T,   G = sum_j |xi_j| w sin(k.xi_j) n_j,
    with c_K = 3K - 5 mu, c_mu = 15 mu (3D), c_K = 2 kappa - 4 mu,
    c_mu = 8 mu (2D)."""
    v = VARIANTS[variant]
    dim = v["dim"]
    h = DELTA / m
    xi = stencil(m, dim) * h
    r = np.sqrt((xi**2).sum(axis=1))
    n = xi / r[:, None]
    phase = np.atleast_2d(kvec) @ xi.T
    one_minus_cos = 2 * np.sin(phase / 2)**2
    nn = n[:, :, None] * n[:, None, :]
    if not v["lps"]:
        C = micromodulus(DELTA, variant) / r * h**dim
        return np.einsum("kj,jab->kab", one_minus_cos * C, nn)
    mu, K, kappa, _ = moduli(variant)
    c_K, c_mu = (3 * K - 5 * mu, 15 * mu) if dim == 3 else \
        (2 * kappa - 4 * mu, 8 * mu)
    w = h**dim
    m_w = (r**2).sum() * w
    G = (np.sin(phase) * r * w) @ n
    return (2 * c_mu / m_w) * w * np.einsum("kj,jab->kab", one_minus_cos, nn) \
        + (dim * c_K / m_w**2) * G[:, :, None] * G[:, None, :]


def omega_lattice(k, m, variant="pmb2d"):
    """omega(k) of the longitudinal wave along x (for k along a lattice
    axis, D is diagonal by the lattice's symmetry)."""
    k = np.atleast_1d(np.asarray(k, float))
    kvec = np.zeros((len(k), VARIANTS[variant]["dim"]))
    kvec[:, 0] = k
    return np.sqrt(acoustic_tensor(kvec, m, variant)[:, 0, 0] / RHO)


def omega_continuum(k, n_theta=512):
    """rho omega^2 = c int_0^2pi cos^2 th (delta - sin(k delta cos th) /
    (k cos th)) d th (the radial integral done exactly), by the trapezoidal
    rule, which converges spectrally for this periodic integrand."""
    th = np.arange(n_theta) * 2 * np.pi / n_theta
    ct = np.cos(th)
    inner = DELTA * (1 - np.sinc(np.outer(k, ct) * DELTA / np.pi))
    return np.sqrt(micromodulus(DELTA) * (inner * ct**2).sum(axis=1)
                   * (2 * np.pi / n_theta) / RHO)


def long_wave_speed(m, variant="pmb2d"):
    """c_lat = lim omega(k)/k for k -> 0 along x: the lattice's long-wave
    speed (bond-based: c_lat^2 = (1/2 rho) sum_j C xi_jx^4 / |xi_j|^2)."""
    k = 1e-7 / DELTA  # (k xi)^2 / 12 < 1e-15: the limit to round-off
    return float(omega_lattice(k, m, variant)[0] / k)


def max_group_speed(m, variant="pmb2d"):
    """Largest group speed d omega / d|k| of the lattice over directions of k
    and all branches (eigenvalues of the acoustic tensor)."""
    dim = VARIANTS[variant]["dim"]
    h = DELTA / m
    kappa = np.linspace(0, math.pi / h, 4001)
    if dim == 2:
        directions = [(math.cos(p), math.sin(p))
                      for p in np.linspace(0, math.pi / 4, 19)]
    else:
        # The cubic lattice's fundamental sector: 0 <= z <= y <= x.
        directions = []
        for p in np.linspace(0, math.pi / 4, 10):
            for t in np.linspace(0, math.atan(math.cos(p)), 6):
                directions.append((math.cos(t) * math.cos(p),
                                   math.cos(t) * math.sin(p), math.sin(t)))
    best = 0.0
    for e in directions:
        lam = np.linalg.eigvalsh(acoustic_tensor(np.outer(kappa, e), m,
                                                 variant)) / RHO
        om = np.sqrt(np.maximum(lam, 0))
        best = max(best, np.max(np.diff(om, axis=0)
                                / np.diff(kappa)[:, None]))
    return best


def gershgorin_time_step_bound(m, variant="pmb2d"):
    """2/sqrt(lambda_G) with lambda_G = max_c sum_j 2 C |n_c| |n|_1 / rho at
    a bulk node (doc/explicit-dynamics.md, "The time step"), bond-based
    only: the code's bound, recomputed to choose the steps; checked against
    the log. None for LPS (whose bound also couples through the
    dilatations): the code chooses the step."""
    if VARIANTS[variant]["lps"]:
        return None
    xi, C = bond_constants(m, variant)
    r = np.sqrt((xi**2).sum(axis=1))
    n = np.abs(xi) / r[:, None]
    lam = max((2 * C * n[:, c] * n.sum(axis=1)).sum()
              for c in range(xi.shape[1])) / RHO
    return 2 / math.sqrt(lam)


def k_quadrature(w, nk):
    """Composite 16-point Gauss-Legendre on [0, K], K = 2 sqrt(45)/w (the
    transform is below exp(-45) of its peak beyond)."""
    g, gw = np.polynomial.legendre.leggauss(16)
    edges = np.linspace(0, 2 * math.sqrt(45) / w, nk // 16 + 1)
    half = (edges[1:] - edges[:-1])[:, None] / 2
    mid = (edges[1:] + edges[:-1])[:, None] / 2
    return (mid + half * g).ravel(), (half * gw).ravel()


def a_hat(k, w):
    return A * w * math.sqrt(math.pi) * np.exp(-(k * w)**2 / 4)


def verlet(omega, dt):
    return np.arccos(1 - (omega * dt)**2 / 2) / dt


def spectral_solution(x, t, w, omega_of_k, dt=None, nk=4096):
    """u(x, t) = (1/pi) int_0^inf A_hat cos(k x) cos(omega t) dk for each x
    (rows) and t (columns); with dt, omega -> the velocity Verlet Omega."""
    k, wk = k_quadrature(w, nk)
    om = omega_of_k(k)
    if dt is not None:
        om = verlet(om, dt)
    T = np.cos(np.outer(t, om))
    return np.array([T @ (wk * a_hat(k, w) * np.cos(k * xx)) for xx in x]) \
        / math.pi


def dalembert(x, t, w, c):
    g = lambda s: A * np.exp(-(s / w)**2)
    return np.array([0.5 * (g(xx - c * t) + g(xx + c * t)) for xx in x])


def verlet_energy_change(t, w, m, dt, nk=4096, variant="pmb2d"):
    """Velocity Verlet conserves H = K + W - (dt^2/8) sum_i m_i |a_i|^2
    exactly for linear forces, so K + W changes by (dt^2/8)(S_n - S_0),
    S = sum m |a|^2. On the infinite lattice, relative to E_0 = W_0:
    (dt^2/4) int omega^4 A_hat^2 (cos^2 Omega t - 1) dk / int omega^2
    A_hat^2 dk."""
    k, wk = k_quadrature(w, nk)
    om = omega_lattice(k, m, variant)
    weight = wk * a_hat(k, w)**2
    c2 = np.cos(np.outer(t, verlet(om, dt)))**2
    return (dt**2 / 4) * ((c2 - 1) @ (weight * om**4)) / (weight * om**2).sum()


def group_speed_band(w, m, dt, variant="pmb2d", share=0.99):
    """The smallest and the largest group speed d Omega / dk (Omega:
    velocity Verlet's frequency) over the wave numbers 0 <= k <= k_share
    that carry `share` of the pulse's energy (spectral density omega^2
    A_hat^2): every part of the pulse travels at a speed in this range."""
    k, wk = k_quadrature(w, 4096)
    om = omega_lattice(k, m, variant)
    energy = np.cumsum(wk * (om * a_hat(k, w))**2)
    kk = np.linspace(0, k[np.searchsorted(energy, share * energy[-1])], 2001)
    Om = verlet(omega_lattice(kk, m, variant), dt)
    cg = np.diff(Om) / np.diff(kk)
    return float(cg.min()), float(cg.max())


def plate_forces(case, u0):
    """Force densities of the bond-based plate (the code's 'full' partial
    volumes: every neighbour node within the horizon weighs h^d; no bond
    leaves the plate) for the nodal displacement u0[i, j, c] (2D):
    f_i = sum_j C n (n . (u_j - u_i)); and the energy W = sum_i h^d 1/4
    sum_j C (n . (u_j - u_i))^2 (a pair's energy c s^2 |xi| / 2 split
    between its nodes)."""
    variant = case.get("variant", "pmb2d")
    assert not VARIANTS[variant]["lps"] and VARIANTS[variant]["dim"] == 2
    m = case["m"]
    xi, C = bond_constants(m, variant)
    offsets = stencil(m).astype(int)
    N = u0.shape[0]
    f = np.zeros_like(u0)
    energy = 0.0
    for (ox, oy), c, x in zip(offsets, C, xi):
        n = x / math.hypot(*x)
        # Pairs (i, i + o) inside the plate.
        src = (slice(max(0, -ox), N - max(0, ox)),
               slice(max(0, -oy), N - max(0, oy)))
        dst = (slice(max(0, ox), N - max(0, -ox)),
               slice(max(0, oy), N - max(0, -oy)))
        e = (u0[dst] - u0[src]) @ n
        f[src] += c * e[..., None] * n
        energy += 0.25 * c * (e**2).sum() * case["h"]**2
    return f, energy


def setup_case(template, directory, m, w_over_delta, dt_div, energy=False,
               variant="pmb2d"):
    """Sizes the plate so that nothing from its free edges reaches a probe
    before the end of the run, and writes the input and case.json."""
    m, w_over_delta, dt_div = float(m), float(w_over_delta), int(dt_div)
    v = VARIANTS[variant]
    dim = v["dim"]
    h = DELTA / m
    w = w_over_delta * DELTA
    c_p = moduli(variant)[3]
    c_lat = long_wave_speed(m, variant)
    c_max = max(c_p, c_lat, max_group_speed(m, variant))
    bound = gershgorin_time_step_bound(m, variant)
    probes_in_delta = PROBES_IN_DELTA if dim == 2 else (0, 1.5, 3)
    if energy:
        # Long run on a small plate: the pulse reflects many times; only
        # the energy is used.
        n_cells = [64] * dim
        probes = [(0.5 * h,) * dim]
        n0 = 10000
        t_end = n0 * 0.9 * bound
        every = 10 * dt_div
    else:
        probes = [((math.floor(p * DELTA / h + 1e-9) + 0.5) * h,)
                  + (0.5 * h,) * (dim - 1) for p in probes_in_delta]
        x_max = probes[-1][0]
        # The right-moving half and its dispersive tail have passed the
        # farthest probe (in 3D only the peak, by 2 w + 2 delta: the box
        # grows with the cube of the run's time).
        t_end = (x_max + (4 if dim == 2 else 2) * (w + DELTA)) / min(c_p, c_lat)
        # Free edges are disturbed from t = 0 (the pulse spans the plate in
        # y, and its stress is not zero on the top and bottom edges). The
        # disturbance travels at most at c_max, with lattice precursors
        # ahead of that front: a margin of 1.5 c_max t plus one horizon
        # (the edge layer) keeps them below 1e-13 A (measured). Left and
        # right edges: the pulse tail (6 w, exp(-36)) reaches the edge and
        # comes back to the farthest probe. (The 2D plate is square; the
        # 3D box only as long in x as that needs.)
        # (In 3D the runs are short, and 1.5 c_max t is a smaller margin:
        # four horizons more keep the faces' disturbance below 1e-10 A.)
        reach = 1.5 * c_max * t_end + (DELTA if dim == 2 else 5 * DELTA)
        along = (reach + 6 * w + x_max) / 2
        if dim == 2:
            along = max(reach, along)
        n_cells = [2 * math.ceil(along / h)] + \
            [2 * math.ceil(reach / h)] * (dim - 1)
        n0 = math.ceil(t_end / (0.9 * bound)) if bound else None
        every = dt_div
    halves = [n // 2 * h for n in n_cells]
    # LPS: the code's step (0.9 x its bound, 'Time step = 0'), dt_div = 1.
    steps = n0 * dt_div if n0 else None
    dt = t_end / steps if steps else 0.0
    plane = f"    set Plane model = {v['plane']}\n" if v["plane"] else ""
    fields = {"DIM": str(dim),
              "LOWER": ", ".join(repr(-x) for x in halves),
              "UPPER": ", ".join(repr(x) for x in halves),
              "SUBDIVISIONS": ", ".join(str(n) for n in n_cells),
              "MODEL": "linear peridynamic solid" if v["lps"] else "bond-based",
              "NU": repr(v["nu"]), "PLANE": plane, "M": repr(m),
              "E": repr(E), "RHO": repr(RHO), "END": repr(t_end),
              "DT": repr(dt), "EVERY": str(every), "A": repr(A), "W": repr(w),
              "VARIABLES": "x,y,t" if dim == 2 else "x,y,z,t",
              "ZEROS": "; 0" * (dim - 1),
              "PROBES": "; ".join(", ".join(repr(x) for x in p)
                                  for p in probes)}
    text = open(template).read()
    for key, value in fields.items():
        text = text.replace(f"@{key}@", value)
    assert not re.search(r"@[A-Z]+@", text), "unfilled field in the template"
    open(f"{directory}/input.prm", "w").write(text)
    bonds = int(sum(np.prod([n - abs(o) for n, o in zip(n_cells, offset)])
                    for offset in stencil(m, dim)))
    json.dump({"variant": variant, "m": m, "h": h, "delta": DELTA, "w": w,
               "w_over_delta": w_over_delta, "dt_div": dt_div,
               "energy": energy, "t_end": t_end, "steps": steps, "dt": dt,
               "half": halves[0], "halves": halves,
               "nodes": int(np.prod(n_cells)), "n_cells": n_cells,
               "bonds": bonds, "probes": probes, "c_p": c_p, "c_lat": c_lat,
               "c_max": c_max, "dt_bound": bound},
              open(f"{directory}/case.json", "w"), indent=1)


def read_run(directory):
    case = json.load(open(f"{directory}/case.json"))
    rows = list(csv.DictReader(open(f"{directory}/out/energies.csv")))
    col = lambda name: np.array([float(r[name]) for r in rows])
    run = {"case": case, "step": col("step").astype(int),
           "kinetic": col("kinetic_energy"), "elastic": col("elastic_energy"),
           "balance": col("energy_balance"),
           "u": np.array([col(f"probe{p}_ux") for p in
                          range(len(case["probes"]))])}
    steps = run["step"][-1]
    # The code's step: End time over the whole number of steps.
    run["dt"] = case["t_end"] / steps
    run["t"] = run["step"] * run["dt"]
    log = open(f"{directory}/log").read()
    run["log_bond_visits"] = int(re.search(r"(\d+) bond visits per step",
                                           log).group(1))
    run["log_dt_bound"] = float(re.search(r"stability bound ([0-9.e+-]+) s",
                                          log).group(1))
    section = re.search(r"\| time steps\s*\|\s*\d+\s*\|\s*([0-9.e+-]+)s", log)
    run["steps_s"] = float(section.group(1)) if section else float("nan")
    total = re.search(r"total wall time ([0-9.e+-]+) s", log)
    run["wall_s"] = float(total.group(1)) if total else float("nan")
    try:
        run["process_s"] = float(open(f"{directory}/wall_seconds").read())
    except OSError:
        run["process_s"] = float("nan")
    return run


def analyse(run, quadrature_check=False):
    """Errors (max over probes and rows, relative to A), arrival speed and
    energy figures of one run."""
    case, t, U = run["case"], run["t"], run["u"]
    m, w, dt = case["m"], case["w"], run["dt"]
    variant = case.get("variant", "pmb2d")
    c_p = case.get("c_p", C_P)
    res = {"steps": int(run["step"][-1]), "dt": dt}
    E0 = run["balance"][0]
    dE = run["balance"] / E0 - 1
    # No loads and no prescribed nodes: the balance is K + W.
    res["balance_is_k_plus_w"] = float(np.max(np.abs(
        run["kinetic"] + run["elastic"] - run["balance"])) / E0)
    res["energy_change"] = float(np.max(np.abs(dE)))
    # Released from rest, each mode of the linear problem follows
    # q_n = q_0 cos(Omega t_n), so S_n = sum omega^4 q_n^2 <= S_0 and K + W
    # = E_0 + (dt^2/8)(S_n - S_0) never exceeds E_0.
    res["energy_rise"] = float(np.max(dE))
    # LPS counts its dilatation pass as well.
    passes = 2 if VARIANTS[variant]["lps"] else 1
    res["bond_visits_ok"] = run["log_bond_visits"] == passes * case["bonds"]
    res["dt_bound_ok"] = case["dt_bound"] is None or \
        abs(run["log_dt_bound"] / case["dt_bound"] - 1) < 1e-5
    if case["energy"]:
        # Least-squares slope of the balance over the whole run.
        slope = np.polyfit(run["step"], dE, 1)[0]
        res["energy_drift_per_1000"] = float(slope * 1000)
        # The lower end: K + W >= E_0 - (dt^2/8) S_0, with S_0 and E_0
        # summed here over the plate's nodes (bond-based 2D).
        h = case["h"]
        N = case["n_cells"][0]
        x = (np.arange(N) + 0.5) * h - case["halves"][0]
        u0 = np.zeros((N, N, 2))
        u0[:, :, 0] = (A * np.exp(-(x / w)**2))[:, None]
        f, W0 = plate_forces(case, u0)
        S0 = h**2 * (f**2).sum() / RHO
        res["energy_lower_bound"] = float(-(dt**2 / 8) * S0 / W0)
        res["energy_lowest"] = float(np.min(dE))
        res["e0_error"] = float(abs(E0 / W0 - 1))
        return res
    x = [p[0] for p in case["probes"]]
    lat = lambda k: omega_lattice(k, m, variant)
    ref = {"lattice": spectral_solution(x, t, w, lat),
           "lattice_verlet": spectral_solution(x, t, w, lat, dt=dt),
           "classical": dalembert(x, t, w, c_p),
           "classical_clat": dalembert(x, t, w, case["c_lat"])}
    if variant == "pmb2d":
        ref["continuum_pd"] = spectral_solution(x, t, w, omega_continuum)
    run["ref"] = ref
    for name, R in ref.items():
        res["err_" + name] = float(np.max(np.abs(U - R)) / A)
    res["lattice_vs_classical"] = float(
        np.max(np.abs(ref["lattice"] - ref["classical"])) / A)
    res["lattice_vs_classical_clat"] = float(
        np.max(np.abs(ref["lattice"] - ref["classical_clat"])) / A)
    res["verlet_vs_semi"] = float(
        np.max(np.abs(ref["lattice"] - ref["lattice_verlet"])) / A)
    if quadrature_check:
        fine = spectral_solution(x, t, w, lat, nk=8192)
        res["quadrature"] = float(np.max(np.abs(fine - ref["lattice"])) / A)
    # Arrival: time of the peak at the probes far enough from the start
    # (x >= 1.2 w, so that the two halves no longer overlap there; a
    # parabola through the largest sample and its neighbours), speed by a
    # least-squares line through (t_peak, x).
    far = [p for p in range(len(x)) if x[p] >= 1.2 * w and x[p] > 0]

    def peak_times(V):
        times = []
        for p in far:
            i = min(max(int(np.argmax(V[p])), 1), len(t) - 2)
            y0, y1, y2 = V[p][i - 1:i + 2]
            times.append(t[i] + (t[1] - t[0]) * 0.5 * (y0 - y2)
                         / (y0 - 2 * y1 + y2))
        return times
    if len(far) >= 2:
        xs = [x[p] for p in far]
        times = peak_times(U)
        res["speed_over_cp"] = float(np.polyfit(times, xs, 1)[0] / c_p)
        res["arrival_over_classical"] = float(times[-1] * c_p / xs[-1])
        res["speed_lattice_over_cp"] = float(
            np.polyfit(peak_times(ref["lattice"]), xs, 1)[0] / c_p)
        res["speed_lattice_verlet_over_cp"] = float(
            np.polyfit(peak_times(ref["lattice_verlet"]), xs, 1)[0] / c_p)
        low, high = group_speed_band(w, m, dt, variant)
        res["group_speed_band_over_cp"] = (low / c_p, high / c_p)
    # Energy: K + W follows the Verlet term (dt^2/8)(S_n - S_0); what is
    # left after removing it is the drift, fitted once the two halves have
    # separated (t >= 4 w / c_p), where the infinite-lattice prediction's
    # small mismatch at the plate's edges no longer changes.
    pred = verlet_energy_change(t, w, m, dt, variant=variant)
    res["energy_predicted"] = float(np.max(np.abs(pred)))
    res["energy_vs_predicted"] = float(np.max(np.abs(dE - pred)))
    late = t >= 4 * w / c_p
    res["energy_drift_per_1000"] = float(
        np.polyfit(run["step"][late], (dE - pred)[late], 1)[0] * 1000)
    return res


def check(directory, tol_verlet, tol_energy, tol_drift):
    """The assertions of tests/dynamics/wave_dispersion_check.sh."""
    tol_verlet, tol_energy, tol_drift = map(float, (tol_verlet, tol_energy,
                                                    tol_drift))
    run = read_run(directory)
    r = analyse(run, quadrature_check=not run["case"]["energy"])
    failures = []

    def verdict(ok, text):
        print(("ok:   " if ok else "FAIL: ") + text)
        if not ok:
            failures.append(text)

    passes = 2 if VARIANTS[run["case"].get("variant", "pmb2d")]["lps"] else 1
    verdict(r["bond_visits_ok"], f"bond visits per step {run['log_bond_visits']}"
            f" = {passes} x {run['case']['bonds']} counted here (same stencil)")
    if run["case"]["dt_bound"] is not None:
        verdict(r["dt_bound_ok"], f"stability bound {run['log_dt_bound']:.6g} s ="
                f" {run['case']['dt_bound']:.6g} s recomputed here")
    verdict(r["balance_is_k_plus_w"] < 1e-10,
            f"energy_balance = kinetic + elastic (no external work) to "
            f"{r['balance_is_k_plus_w']:.1e} E_0")
    # The CSV's 12 significant digits of K and W: 1e-10 E_0 is round-off.
    verdict(r["energy_rise"] <= 1e-10,
            f"K + W never above E_0 (released from rest: S_n <= S_0): largest "
            f"(K + W)/E_0 - 1 = {r['energy_rise']:.1e} <= 1e-10")
    if run["case"]["energy"]:
        verdict(r["e0_error"] <= 1e-10,
                f"E_0 = the energy summed here over the plate's bonds to "
                f"{r['e0_error']:.1e} (<= 1e-10)")
        lower = r["energy_lower_bound"]
        verdict(r["energy_lowest"] >= lower * (1 + 1e-8),
                f"over {r['steps']} steps (K + W)/E_0 - 1 stays above "
                f"-(dt^2/8) S_0/E_0 = {lower:.4e} (S_0 = sum m |a_0|^2 summed "
                f"here): lowest {r['energy_lowest']:.4e}")
        verdict(abs(r["energy_drift_per_1000"]) <= tol_drift,
                f"slope of K + W: {r['energy_drift_per_1000']:.2e} E_0 per "
                f"1000 steps (|.| <= {tol_drift:.0e})")
        return 1 if failures else 0
    verdict(r["quadrature"] < 1e-3 * tol_verlet,
            f"reference quadrature converged: 4096 vs 8192 nodes differ by "
            f"{r['quadrature']:.1e} A (< {1e-3 * tol_verlet:.0e} A)")
    verdict(r["err_lattice_verlet"] <= tol_verlet,
            f"probes vs lattice PD + velocity Verlet: {r['err_lattice_verlet']:.2e}"
            f" A <= {tol_verlet:.0e} A")
    d = r["verlet_vs_semi"]
    verdict(abs(r["err_lattice"] - d) <= tol_verlet,
            f"probes vs semi-discrete lattice PD: {r['err_lattice']:.4e} A, the "
            f"velocity Verlet error {d:.4e} A predicted")
    for name, key in (("c_p", "classical"), ("c_lat", "classical_clat")):
        d = r["lattice_vs_" + key]
        verdict(d >= 100 * tol_verlet and r["err_" + key] >= 0.5 * d,
                f"probes vs d'Alembert with {name}: {r['err_' + key]:.3e} A, "
                f">= half the dispersion the lattice predicts ({d:.3e} A, "
                f"itself >= 100 x {tol_verlet:.0e})")
    # The infinite-lattice prediction misses the plate's edge rows, by 0.4 %
    # of it for pmb2d (doc/explicit-dynamics.md); the LPS edge nodes (their
    # own weighted volumes) and the 3D boxes' four faces miss more, and the
    # 3D runs are too short for a slope: there the exact bound above holds.
    if run["case"].get("variant", "pmb2d") == "pmb2d":
        verdict(r["energy_vs_predicted"] <= tol_energy * r["energy_predicted"],
                f"(K + W)/E_0 - 1 follows the Verlet term (dt^2/8)(S_n - S_0) "
                f"(up to {r['energy_predicted']:.3e}) to "
                f"{r['energy_vs_predicted']:.2e} <= {tol_energy} x that")
        verdict(abs(r["energy_drift_per_1000"]) <= tol_drift,
                f"energy drift beyond it: {r['energy_drift_per_1000']:.2e} E_0 "
                f"per 1000 steps (|.| <= {tol_drift:.0e})")
    # Pulse speed: the peak's least-squares speed through the far probes.
    # (a) The same estimator on the exact discrete solution: the probes
    # agree with it to tol_verlet A, so the peak times agree to about
    # tol_verlet A / (|u''| dt^2) of a step; 1e-6 c_p is far above that and
    # far below the dispersion (b).
    # (b) Every spectral part of the pulse travels at its group speed
    # d Omega / dk, so the peak speed lies within the group speeds of the
    # wave numbers that carry 99 % of the pulse's energy.
    speed = r["speed_over_cp"]
    ref_speed = r["speed_lattice_verlet_over_cp"]
    verdict(abs(speed - ref_speed) <= 1e-6,
            f"pulse speed {speed:.7f} c_p = the same estimate on lattice PD + "
            f"Verlet, {ref_speed:.7f} c_p, to 1e-6 c_p")
    low, high = r["group_speed_band_over_cp"]
    verdict(low <= speed <= high,
            f"pulse speed within the group speeds of the pulse's spectrum "
            f"(99 % of its energy): {low:.4f} <= {speed:.4f} <= {high:.4f} c_p")
    c_lat = run["case"]["c_lat"] / run["case"]["c_p"]
    verdict(abs(speed - 1) >= 1e-4 and abs(speed - c_lat) >= 1e-4,
            f"the dispersion shows in the speed: {speed:.4f} c_p differs from c_p"
            f" and from the long-wave speed c_lat = {c_lat:.4f} c_p by >= 1e-4 c_p")
    print(f"pulse speed {speed:.4f} c_p (lattice reference "
          f"{r['speed_lattice_over_cp']:.4f} c_p, with Verlet {ref_speed:.4f} "
          f"c_p, long-wave c_lat = {c_lat:.4f} c_p); {r['steps']} steps")
    return 1 if failures else 0


COLUMNS = ["case", "m", "h", "delta", "w", "w_over_delta", "dt", "steps",
           "nodes", "wall_s", "time_steps_s", "err_lattice",
           "err_lattice_verlet", "err_continuum_pd", "err_classical",
           "err_classical_clat", "lattice_vs_classical", "speed_over_cp",
           "speed_lattice_over_cp", "arrival_over_classical",
           "energy_change", "energy_predicted", "energy_drift_per_1000_steps"]


def report(out, names):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    runs, rows = {}, []
    for name in names:
        run = read_run(f"{out}/{name}")
        r = analyse(run, quadrature_check=(name == names[0]))
        runs[name] = (run, r)
        c = run["case"]
        if not (r["bond_visits_ok"] and r["dt_bound_ok"]):
            print(f"warning: {name}: stencil or stability bound differ from "
                  f"this script's")
        rows.append({"case": name, "m": c["m"], "h": c["h"],
                     "delta": c["delta"], "w": c["w"],
                     "w_over_delta": c["w_over_delta"], "dt": r["dt"],
                     "steps": r["steps"], "nodes": c["nodes"],
                     "wall_s": run["process_s"],
                     "time_steps_s": run["steps_s"],
                     "err_lattice": r.get("err_lattice", ""),
                     "err_lattice_verlet": r.get("err_lattice_verlet", ""),
                     "err_continuum_pd": r.get("err_continuum_pd", ""),
                     "err_classical": r.get("err_classical", ""),
                     "err_classical_clat": r.get("err_classical_clat", ""),
                     "lattice_vs_classical": r.get("lattice_vs_classical", ""),
                     "speed_over_cp": r.get("speed_over_cp", ""),
                     "speed_lattice_over_cp": r.get("speed_lattice_over_cp", ""),
                     "arrival_over_classical": r.get("arrival_over_classical",
                                                     ""),
                     "energy_change": r["energy_change"],
                     "energy_predicted": r.get("energy_predicted", ""),
                     "energy_drift_per_1000_steps": r["energy_drift_per_1000"]})
        if "quadrature" in r:
            print(f"{name}: reference quadrature 4096 vs 8192 nodes: "
                  f"{r['quadrature']:.1e} A")
    fmt = lambda v: (f"{v:.4g}" if isinstance(v, float) else str(v))
    with open(f"{out}/wave_dispersion.csv", "w") as f:
        f.write(",".join(COLUMNS) + "\n")
        for row in rows:
            f.write(",".join(fmt(row[k]) for k in COLUMNS) + "\n")

    fig, ax = plt.subplots(2, 3, figsize=(16, 9))
    waves = [n for n in names if not runs[n][0]["case"]["energy"]]
    # (a) probe histories of the most dispersive case.
    show = min(waves, key=lambda n: runs[n][0]["case"]["w_over_delta"])
    run, r = runs[show]
    case, t = run["case"], run["t"]
    tau = t * C_P / DELTA
    for p, (x, _) in enumerate(case["probes"]):
        ax[0, 0].plot(tau, run["u"][p] / A, "o", ms=3, color=f"C{p}",
                      label=f"PeriDEAL, x = {x / DELTA:.1f} delta")
        ax[0, 0].plot(tau, run["ref"]["lattice"][p] / A, "-", color=f"C{p}")
        ax[0, 0].plot(tau, run["ref"]["classical"][p] / A, "--", color="k",
                      lw=0.8)
    ax[0, 0].set_title(f"{show}: probes (dots), lattice PD (lines), "
                       f"d'Alembert c_p (dashed)", fontsize=9)
    ax[0, 0].set_xlabel("t c_p / delta")
    ax[0, 0].set_ylabel("u_x / A")
    ax[0, 0].legend(fontsize=7)
    # (b) the farthest probe, zoomed.
    p = len(case["probes"]) - 1
    ax[0, 1].plot(tau, run["u"][p] / A, "ko", ms=3, label="PeriDEAL")
    for key, style, label in (("lattice", "b-", "lattice PD"),
                              ("continuum_pd", "g-.", "continuum PD"),
                              ("classical", "r--", "d'Alembert, c_p"),
                              ("classical_clat", "m:", "d'Alembert, c_lat")):
        ax[0, 1].plot(tau, run["ref"][key][p] / A, style, label=label)
    i = int(np.argmax(run["u"][p]))
    ax[0, 1].set_xlim(tau[i] - 12 * case["w"] / DELTA,
                      tau[i] + 6 * case["w"] / DELTA)
    ax[0, 1].set_title(f"{show}: probe at x = "
                       f"{case['probes'][p][0] / DELTA:.1f} delta", fontsize=9)
    ax[0, 1].set_xlabel("t c_p / delta")
    ax[0, 1].legend(fontsize=7)
    # (c) dispersion relations and the pulses' spectra.
    kd = np.linspace(1e-3, 4.0, 400)
    k = kd / DELTA
    for mm in sorted({runs[n][0]["case"]["m"] for n in waves}):
        ax[0, 2].plot(kd, omega_lattice(k, mm) / (C_P * k),
                      label=f"lattice, m = {mm:g}")
    ax[0, 2].plot(kd, omega_continuum(k) / (C_P * k), "k--",
                  label="continuum PD")
    for wd in sorted({runs[n][0]["case"]["w_over_delta"] for n in waves}):
        ax[0, 2].fill_between(kd, 0.6, 0.6 + 0.3 * np.exp(-(kd * wd)**2 / 4),
                              alpha=0.15, label=f"|A_hat|, w = {wd:g} delta")
    ax[0, 2].set_xlabel("k delta")
    ax[0, 2].set_ylabel("phase speed omega / (c_p k)")
    ax[0, 2].legend(fontsize=7)
    # (d) error against wall time.
    for n in waves:
        run, r = runs[n]
        ax[1, 0].loglog(run["process_s"], r["err_lattice"], "bo")
        ax[1, 0].loglog(run["process_s"], r["err_classical"], "rs")
        ax[1, 0].annotate(n, (run["process_s"], r["err_lattice"]), fontsize=7)
        ax[1, 0].annotate(n, (run["process_s"], r["err_classical"]),
                          fontsize=7)
    ax[1, 0].plot([], [], "bo", label="vs lattice PD (semi-discrete)")
    ax[1, 0].plot([], [], "rs", label="vs d'Alembert, c_p")
    ax[1, 0].set_xlabel("wall time of the run [s] (1 process, 1 thread)")
    ax[1, 0].set_ylabel("max |u - u_ref| / A")
    ax[1, 0].legend(fontsize=7)
    # (e) error against dt, for the dt series.
    series = sorted((n for n in waves if runs[n][0]["case"]["m"] == 3 and
                     runs[n][0]["case"]["w_over_delta"] == 2),
                    key=lambda n: -runs[n][1]["dt"])
    dts = np.array([runs[n][1]["dt"] for n in series])
    for key, style, label in (("err_lattice", "bo-", "vs lattice PD"),
                              ("err_classical", "rs-", "vs d'Alembert, c_p"),
                              ("err_lattice_verlet", "k^-",
                               "vs lattice PD + Verlet")):
        ax[1, 1].loglog(dts, [runs[n][1][key] for n in series], style,
                        label=label)
    if len(series):
        e0 = runs[series[0]][1]["err_lattice"]
        ax[1, 1].loglog(dts, e0 * (dts / dts[0])**2, "b:", label="dt^2")
    ax[1, 1].set_xlabel("dt [s]")
    ax[1, 1].set_ylabel("max |u - u_ref| / A")
    ax[1, 1].set_title("m = 3, w = 2 delta", fontsize=9)
    ax[1, 1].legend(fontsize=7)
    # (f) energy balance of the long runs.
    for n in names:
        run, r = runs[n]
        if run["case"]["energy"]:
            ax[1, 2].plot(run["t"] * 1e3,
                          run["balance"] / run["balance"][0] - 1, lw=0.6,
                          label=f"{n}: dt = {r['dt']:.3g} s, "
                          f"{r['steps']} steps")
    ax[1, 2].set_xlabel("t [ms] (pulse reflected many times)")
    ax[1, 2].set_ylabel("(K + W) / E_0 - 1")
    ax[1, 2].legend(fontsize=7)
    for a in ax.flat:
        a.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(f"{out}/wave_dispersion.png", dpi=110)


if __name__ == "__main__":
    command, args = sys.argv[1], sys.argv[2:]
    if command == "prm":
        # prm TEMPLATE DIR M W_OVER_DELTA DT_DIV [energy] [VARIANT]
        extra = args[5:]
        variants = [a for a in extra if a in VARIANTS]
        setup_case(*args[:5], energy="energy" in extra,
                   variant=variants[0] if variants else "pmb2d")
    elif command == "check":
        sys.exit(check(*args))
    elif command == "report":
        report(args[0], args[1:])
    else:
        sys.exit(f"unknown command {command}: prm, check or report")
