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
  prm TEMPLATE DIR M W_OVER_DELTA DT_DIV [energy]
      write DIR/input.prm and DIR/case.json for one case;
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


def micromodulus(delta):
    """c = 8 mu / (pi delta^3 M2) of source/models/bond_based.cc (2D), with
    M2 = int_0^1 s^2 ds = 1/3 for constant influence: 9E/(pi delta^3)."""
    mu = E / (2 * (1 + NU))
    return 8 * mu / (math.pi * delta**3 / 3)


def stencil(m):
    """Integer offsets o != 0 with |o| <= m: the neighbours whose cell centre
    lies in the closed horizon disc ('full' partial volumes)."""
    n = int(math.ceil(m))
    return np.array([(i, j) for i in range(-n, n + 1)
                     for j in range(-n, n + 1) if 0 < i * i + j * j <= m * m],
                    float)


def bond_constants(m):
    """(xi, C) over the stencil: xi in metres, C = c/|xi| h^2, so that the
    linearised force density on node i is sum_j C n (n . (u_j - u_i))."""
    h = DELTA / m
    xi = stencil(m) * h
    r = np.hypot(xi[:, 0], xi[:, 1])
    return xi, micromodulus(DELTA) / r * h * h


def omega_lattice(k, m):
    xi, C = bond_constants(m)
    r2 = (xi**2).sum(axis=1)
    return np.sqrt(((C * xi[:, 0]**2 / r2)[None, :] *
                    (1 - np.cos(np.outer(k, xi[:, 0])))).sum(axis=1) / RHO)


def omega_continuum(k, n_theta=512):
    """rho omega^2 = c int_0^2pi cos^2 th (delta - sin(k delta cos th) /
    (k cos th)) d th (the radial integral done exactly), by the trapezoidal
    rule, which converges spectrally for this periodic integrand."""
    th = np.arange(n_theta) * 2 * np.pi / n_theta
    ct = np.cos(th)
    inner = DELTA * (1 - np.sinc(np.outer(k, ct) * DELTA / np.pi))
    return np.sqrt(micromodulus(DELTA) * (inner * ct**2).sum(axis=1)
                   * (2 * np.pi / n_theta) / RHO)


def long_wave_speed(m):
    """c_lat^2 = (1/2 rho) sum_j C xi_jx^4 / |xi_j|^2, the k -> 0 limit of
    the lattice relation."""
    xi, C = bond_constants(m)
    r2 = (xi**2).sum(axis=1)
    return math.sqrt((C * xi[:, 0]**4 / r2).sum() / (2 * RHO))


def max_group_speed(m):
    """Largest group speed d omega / d|k| of the lattice over directions of k
    and both branches (eigenvalues of the 2x2 acoustic tensor)."""
    xi, C = bond_constants(m)
    r2 = (xi**2).sum(axis=1)
    h = DELTA / m
    kappa = np.linspace(0, math.pi / h, 4001)
    best = 0.0
    for phi in np.linspace(0, math.pi / 4, 19):
        e = np.array([math.cos(phi), math.sin(phi)])
        one_minus_cos = 1 - np.cos(np.outer(kappa, xi @ e))
        D = [[(one_minus_cos * (C * xi[:, a] * xi[:, b] / r2)).sum(axis=1)
              / RHO for b in range(2)] for a in range(2)]
        tr, det = D[0][0] + D[1][1], D[0][0] * D[1][1] - D[0][1]**2
        disc = np.sqrt(np.maximum(tr**2 / 4 - det, 0))
        for lam in (tr / 2 + disc, tr / 2 - disc):
            best = max(best, np.max(np.diff(np.sqrt(np.maximum(lam, 0)))
                                    / np.diff(kappa)))
    return best


def gershgorin_time_step_bound(m):
    """2/sqrt(lambda_G) with lambda_G = max_c sum_j 2 C |n_c| |n|_1 / rho at
    a bulk node (doc/explicit-dynamics.md, "The time step"): the code's
    bound, recomputed to choose the steps; checked against the log."""
    xi, C = bond_constants(m)
    r = np.hypot(xi[:, 0], xi[:, 1])
    n = np.abs(xi) / r[:, None]
    lam = max((2 * C * n[:, c] * n.sum(axis=1)).sum() for c in range(2)) / RHO
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


def verlet_energy_change(t, w, m, dt, nk=4096):
    """Velocity Verlet conserves H = K + W - (dt^2/8) sum_i m_i |a_i|^2
    exactly for linear forces, so K + W changes by (dt^2/8)(S_n - S_0),
    S = sum m |a|^2. On the infinite lattice, relative to E_0 = W_0:
    (dt^2/4) int omega^4 A_hat^2 (cos^2 Omega t - 1) dk / int omega^2
    A_hat^2 dk."""
    k, wk = k_quadrature(w, nk)
    om = omega_lattice(k, m)
    weight = wk * a_hat(k, w)**2
    c2 = np.cos(np.outer(t, verlet(om, dt)))**2
    return (dt**2 / 4) * ((c2 - 1) @ (weight * om**4)) / (weight * om**2).sum()


def setup_case(template, directory, m, w_over_delta, dt_div, energy=False):
    """Sizes the plate so that nothing from its free edges reaches a probe
    before the end of the run, and writes the input and case.json."""
    m, w_over_delta, dt_div = float(m), float(w_over_delta), int(dt_div)
    h = DELTA / m
    w = w_over_delta * DELTA
    c_lat = long_wave_speed(m)
    c_max = max(C_P, c_lat, max_group_speed(m))
    bound = gershgorin_time_step_bound(m)
    if energy:
        # Long run on a small plate: the pulse reflects many times; only
        # the energy is used.
        n_cells = 64
        probes = [(0.5 * h, 0.5 * h)]
        n0 = 10000
        t_end = n0 * 0.9 * bound
        every = 10 * dt_div
    else:
        probes = [((math.floor(p * DELTA / h + 1e-9) + 0.5) * h, 0.5 * h)
                  for p in PROBES_IN_DELTA]
        x_max = probes[-1][0]
        # The right-moving half and its dispersive tail have passed the
        # farthest probe.
        t_end = (x_max + 4 * w + 4 * DELTA) / min(C_P, c_lat)
        # Free edges are disturbed from t = 0 (the pulse spans the plate in
        # y, and its stress is not zero on the top and bottom edges). The
        # disturbance travels at most at c_max, with lattice precursors
        # ahead of that front: a margin of 1.5 c_max t plus one horizon
        # (the edge layer) keeps them below 1e-13 A (measured). Left and
        # right edges: the pulse tail (6 w, exp(-36)) reaches the edge and
        # comes back to the farthest probe.
        reach = 1.5 * c_max * t_end + DELTA
        half = max(reach, (reach + 6 * w + x_max) / 2)
        n_cells = 2 * math.ceil(half / h)
        n0 = math.ceil(t_end / (0.9 * bound))
        every = dt_div
    half = n_cells // 2 * h
    steps = n0 * dt_div
    dt = t_end / steps
    fields = {"HALF": repr(half), "N": str(n_cells), "M": repr(m),
              "E": repr(E), "RHO": repr(RHO), "END": repr(t_end),
              "DT": repr(dt), "EVERY": str(every), "A": repr(A), "W": repr(w),
              "PROBES": "; ".join(f"{x!r}, {y!r}" for x, y in probes)}
    text = open(template).read()
    for key, value in fields.items():
        text = text.replace(f"@{key}@", value)
    assert not re.search(r"@[A-Z]+@", text), "unfilled field in the template"
    open(f"{directory}/input.prm", "w").write(text)
    xi = stencil(m)
    bonds = int(sum((n_cells - abs(ox)) * (n_cells - abs(oy)) for ox, oy in xi))
    json.dump({"m": m, "h": h, "delta": DELTA, "w": w,
               "w_over_delta": w_over_delta, "dt_div": dt_div,
               "energy": energy, "t_end": t_end, "steps": steps, "dt": dt,
               "half": half, "nodes": n_cells**2, "bonds": bonds,
               "probes": probes, "c_p": C_P, "c_lat": c_lat, "c_max": c_max,
               "dt_bound": bound}, open(f"{directory}/case.json", "w"),
              indent=1)


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
    res = {"steps": int(run["step"][-1]), "dt": dt}
    E0 = run["balance"][0]
    dE = run["balance"] / E0 - 1
    # No loads and no prescribed nodes: the balance is K + W.
    res["balance_is_k_plus_w"] = float(np.max(np.abs(
        run["kinetic"] + run["elastic"] - run["balance"])) / E0)
    res["energy_change"] = float(np.max(np.abs(dE)))
    res["bond_visits_ok"] = run["log_bond_visits"] == case["bonds"]
    res["dt_bound_ok"] = abs(run["log_dt_bound"] / case["dt_bound"] - 1) < 1e-5
    if case["energy"]:
        # Least-squares slope of the balance over the whole run.
        slope = np.polyfit(run["step"], dE, 1)[0]
        res["energy_drift_per_1000"] = float(slope * 1000)
        return res
    x = [p[0] for p in case["probes"]]
    lat = lambda k: omega_lattice(k, m)
    ref = {"lattice": spectral_solution(x, t, w, lat),
           "lattice_verlet": spectral_solution(x, t, w, lat, dt=dt),
           "continuum_pd": spectral_solution(x, t, w, omega_continuum),
           "classical": dalembert(x, t, w, C_P),
           "classical_clat": dalembert(x, t, w, case["c_lat"])}
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
        res["speed_over_cp"] = float(np.polyfit(times, xs, 1)[0] / C_P)
        res["arrival_over_classical"] = float(times[-1] * C_P / xs[-1])
        res["speed_lattice_over_cp"] = float(
            np.polyfit(peak_times(ref["lattice"]), xs, 1)[0] / C_P)
    # Energy: K + W follows the Verlet term (dt^2/8)(S_n - S_0); what is
    # left after removing it is the drift, fitted once the two halves have
    # separated (t >= 4 w / c_p), where the infinite-lattice prediction's
    # small mismatch at the plate's edges no longer changes.
    pred = verlet_energy_change(t, w, m, dt)
    res["energy_predicted"] = float(np.max(np.abs(pred)))
    res["energy_vs_predicted"] = float(np.max(np.abs(dE - pred)))
    late = t >= 4 * w / C_P
    res["energy_drift_per_1000"] = float(
        np.polyfit(run["step"][late], (dE - pred)[late], 1)[0] * 1000)
    return res


def check(directory, tol_verlet, tol_energy, tol_drift):
    """The assertions of tests/dynamics/wave_dispersion_check.sh."""
    tol_verlet, tol_energy, tol_drift = map(float, (tol_verlet, tol_energy,
                                                    tol_drift))
    run = read_run(directory)
    r = analyse(run, quadrature_check=True)
    failures = []

    def verdict(ok, text):
        print(("ok:   " if ok else "FAIL: ") + text)
        if not ok:
            failures.append(text)

    verdict(r["bond_visits_ok"], f"bond visits per step {run['log_bond_visits']}"
            f" = {run['case']['bonds']} counted here (same stencil)")
    verdict(r["dt_bound_ok"], f"stability bound {run['log_dt_bound']:.6g} s ="
            f" {run['case']['dt_bound']:.6g} s recomputed here")
    verdict(r["balance_is_k_plus_w"] < 1e-10,
            f"energy_balance = kinetic + elastic (no external work) to "
            f"{r['balance_is_k_plus_w']:.1e} E_0")
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
    verdict(r["energy_vs_predicted"] <= tol_energy * r["energy_predicted"],
            f"(K + W)/E_0 - 1 follows the Verlet term (dt^2/8)(S_n - S_0) "
            f"(up to {r['energy_predicted']:.3e}) to {r['energy_vs_predicted']:.2e}"
            f" <= {tol_energy} x that")
    verdict(abs(r["energy_drift_per_1000"]) <= tol_drift,
            f"energy drift beyond it: {r['energy_drift_per_1000']:.2e} E_0 per "
            f"1000 steps (|.| <= {tol_drift:.0e})")
    print(f"pulse speed {r.get('speed_over_cp', math.nan):.4f} c_p (lattice reference "
          f"{r.get('speed_lattice_over_cp', math.nan):.4f} c_p, long-wave c_lat = "
          f"{run['case']['c_lat'] / C_P:.4f} c_p); {r['steps']} steps")
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
        setup_case(*args[:5], energy=(len(args) > 5 and args[5] == "energy"))
    elif command == "check":
        sys.exit(check(*args))
    elif command == "report":
        report(args[0], args[1:])
    else:
        sys.exit(f"unknown command {command}: prm, check or report")
