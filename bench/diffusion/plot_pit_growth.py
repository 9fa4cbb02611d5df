#!/usr/bin/env python3
"""Tables and figures of bench/diffusion/run_pit_growth.sh.

    /usr/bin/python3 bench/diffusion/plot_pit_growth.py DIR

DIR holds runs.csv and runs/<case>/ (history.csv, solution.pvd and the
PVTU/VTU files, read here: deal.II's binary, zlib-compressed VTU, one cell
per node, the node at the centre of its cell). Writes DIR/pit_growth.csv
(one row per case), DIR/stefan_reference.csv, the PNGs below, and prints
the tables (markdown).

References (SS304: K = 8.6e-10 m^2/s, C_sat = 4600, C_solid = 142900
mol/m^3; doc/corrosion-model.md section 4), all for the depth s from the pit
mouth (C = 0) with an initial electrolyte layer s0:
  - exact 1D Stefan problem, C_t = K C_xx on 0 < x < s(t), C(0) = 0,
    C(s) = C_sat, (C_solid - C_sat) s' = K C_x(s), C(x, 0) = 0: solved here
    on the fixed domain xi = x/s (Landau transformation) by the method of
    lines (central differences, N = 800, BDF); 48.637 um at 40 s for s0 = 10
    um (doc: 48.64 by an enthalpy scheme);
  - quasi-steady (linear profile): s^2 = s0^2 + 2 K St t, St = C_sat /
    (C_solid - C_sat);
  - the issue's formula d^2 = 2 K (C_sat / C_solid) t (s0 = 0; 47.06 um at
    40 s).
If DIR/inputs/weights_2d_m4.csv (perideal-weights --dim 2 --m-ratio 4) is
there, the long-wave diffusivity K_h of the discrete operator (m = 4) and the
exact solution with K_h (s depends on K t only) are printed too. The strip
errors are extrapolated to an infinite width (linear in delta / W) and then
to delta -> 0.
Depth measures of a strip (depth below the initial surface y = 0; s = s0 +
depth):
  - max: the history's pit_depth, the far edge of the deepest converted
    node (steps of h);
  - mean: pit_volume_with_damage / W, converted area plus the dissolved
    fraction phi = (C_solid - C)/(C_solid - C_sat) of the metal nodes,
    averaged over the strip width W (the front position by mass);
  - centre, edge: the same per column from the PVTU output, for the
    column(s) at the centre line and at the free sides.
"""
import csv
import math
import os
import sys
import xml.etree.ElementTree as ET

import numpy as np

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

K = 8.6e-10
C_SAT = 4600.0
C_SOLID = 142900.0
VALENCE = 2.19
FARADAY = 96485.33212
ST = C_SAT / (C_SOLID - C_SAT)


# ---------------------------------------------------------------- references
def stefan(s0, t_end, n=800, n_out=801):
    """Exact 1D Stefan problem with C = 0 at x = 0 and C(x, 0) = 0 in
    (0, s0): times and s(t) (m)."""
    from scipy.integrate import solve_ivp
    from scipy.sparse import diags
    xi = np.linspace(0, 1, n + 1)
    dx = xi[1] - xi[0]

    def rhs(_, y):
        s = y[-1]
        u = np.empty(n + 1)
        u[0], u[-1], u[1:-1] = 0, C_SAT, y[:-1]
        ux = (3 * u[-1] - 4 * u[-2] + u[-3]) / (2 * dx)
        sdot = K * ux / s / (C_SOLID - C_SAT)
        du = (K * (u[2:] - 2 * u[1:-1] + u[:-2]) / dx**2 / s**2
              + xi[1:-1] * sdot / s * (u[2:] - u[:-2]) / (2 * dx))
        return np.append(du, sdot)

    sparsity = diags([1, 1, 1], [-1, 0, 1], shape=(n, n)).tolil()
    sparsity[-1, :] = 1
    sparsity[:, -1] = 1
    y0 = np.append(np.zeros(n - 1), s0)
    times = np.linspace(0, t_end, n_out)
    atol = np.append(np.full(n - 1, 1e-10 * C_SAT), 1e-16)
    sol = solve_ivp(rhs, (0, t_end), y0, method="BDF", t_eval=times,
                    jac_sparsity=sparsity, rtol=1e-8, atol=atol)
    assert sol.success, sol.message
    return sol.t, sol.y[-1]


def quasi_steady(s0, t):
    return np.sqrt(s0**2 + 2 * K * ST * np.asarray(t))


def issue_formula(t):
    return np.sqrt(2 * K * C_SAT / C_SOLID * np.asarray(t))


def long_wave_factor(path, dim, m, q=2):
    """K_h / K of the discrete operator for long waves (constant influence,
    flux exponent q): (1 / 2d) sum_j mu_j beta_j h^d |xi_j|^2 / K over the
    complete neighbourhood of perideal-weights (spacing 1, delta = m), with
    kappa = 2 d K / (S_{d-1} delta^(d+2-q) M_{d+1-q}), M_n = 1 / (n + 1)."""
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    xi, beta = data[:, :dim], data[:, dim]
    r = np.linalg.norm(xi, axis=1)
    sphere = {1: 2.0, 2: 2 * math.pi, 3: 4 * math.pi}[dim]
    kappa = 2 * dim / (sphere * m ** (dim + 2 - q) / (dim + 2 - q))
    return float(np.sum(kappa * r ** (2 - q) * beta) / (2 * dim))


# ---------------------------------------------------------------- VTU input
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                ".."))
from pd_vtu import read_pvtu  # noqa: E402


def read_series(run_dir):
    """[(time, pvtu path)] of the run's solution.pvd."""
    pvd = os.path.join(run_dir, "solution.pvd")
    if not os.path.exists(pvd):
        return []
    root = ET.parse(pvd).getroot()
    return [(float(d.get("timestep")), os.path.join(run_dir, d.get("file")))
            for d in root.find("Collection").findall("DataSet")]


def read_history(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


# ---------------------------------------------------------------- measures
def column_depths(x, f, h, axis_depth=1):
    """Per column (x value): the smooth depth below y = 0 (sum of phi h over
    initially-metal nodes, y < 0) and the max depth (deepest electrolyte node
    below y = 0, far edge)."""
    y = x[:, axis_depth]
    below = y < 0
    cols = np.round(x[:, 0] / h * 2).astype(int)
    phi = f["corrosion_damage"]
    out = {}
    for c in np.unique(cols):
        sel = (cols == c) & below
        smooth = float(np.sum(phi[sel])) * h
        conv = sel & (f["phase"] == 0)
        deepest = float(-y[conv].min() + h / 2) if conv.any() else 0.0
        out[c * h / 2] = (smooth, deepest)
    return out


def shape_measures(x, f, h, dim):
    """Depth (far edge of the deepest converted node below 0) and width
    (2 max lateral distance of a converted node, far edge) of the pit."""
    z = x[:, dim - 1]
    conv = (z < 0) & (f["phase"] == 0)
    if not conv.any():
        return 0.0, 0.0
    lateral = (np.abs(x[conv, 0]) if dim == 2 else
               np.hypot(x[conv, 0], x[conv, 1]))
    return float(-z[conv].min() + h / 2), float(2 * (lateral.max() + h / 2))


def grid_image(x, values, h, ax0, ax1, select=None):
    """values on the regular grid of nodes (axes ax0, ax1)."""
    if select is not None:
        x, values = x[select], values[select]
    i = np.round((x[:, ax0] - x[:, ax0].min()) / h).astype(int)
    j = np.round((x[:, ax1] - x[:, ax1].min()) / h).astype(int)
    img = np.full((j.max() + 1, i.max() + 1), np.nan)
    img[j, i] = values
    extent = [x[:, ax0].min() - h / 2, x[:, ax0].max() + h / 2,
              x[:, ax1].min() - h / 2, x[:, ax1].max() + h / 2]
    return img, [e * 1e6 for e in extent]


# ---------------------------------------------------------------- main
def fmt(v, digits=2):
    return "-" if v is None or (isinstance(v, float) and math.isnan(v)) \
        else "%.*f" % (digits, v)


def main():
    if len(sys.argv) != 2:
        print(__doc__)
        sys.exit(2)
    out = sys.argv[1]
    with open(os.path.join(out, "runs.csv")) as f:
        runs = list(csv.DictReader(f))
    for r in runs:
        for k in ("delta_um", "width_um", "layer_um", "end_time", "wall_s",
                  "current_density", "interface_diffusivity", "time_step"):
            r[k] = float(r[k])
        for k in ("m", "dim", "nodes", "steps", "ranks", "threads"):
            r[k] = int(r[k])
        r["safety"] = float(r.get("safety_factor") or 0.9)
        r["h"] = r["delta_um"] * 1e-6 / r["m"]
        r["dir"] = os.path.join(out, "runs", r["name"])
        r["hist"] = read_history(os.path.join(r["dir"], "history.csv"))

    strips = [r for r in runs if r["kind"] == "strip"]
    diffusion = [r for r in strips if not r["name"].startswith("b_")]
    activation = [r for r in strips if r["name"].startswith("b_")]
    shapes = [r for r in runs if r["kind"].startswith("shape")]

    # references
    s0 = 10e-6
    t_end = max(r["end_time"] for r in diffusion) if diffusion else 40.0
    t_ref, s_ref = stefan(s0, t_end)
    with open(os.path.join(out, "stefan_reference.csv"), "w") as f:
        f.write("time,stefan_s0_10um,quasi_steady_s0_10um,issue_formula_s0_0\n")
        for t, s in zip(t_ref, s_ref):
            f.write("%.6g,%.9e,%.9e,%.9e\n" % (t, s, quasi_steady(s0, t),
                                               issue_formula(t)))

    def stefan_at(t):
        return float(np.interp(t, t_ref, s_ref))

    # s(t) depends on K t only: the exact solution for the discrete
    # operator's long-wave diffusivity K_h is s(t K_h / K)
    k_h = None
    weights = os.path.join(out, "inputs", "weights_2d_m4.csv")
    if os.path.exists(weights):
        k_h = long_wave_factor(weights, 2, 4)

    table = []
    # ------------------------------------------------------------ (a)
    for r in diffusion:
        hist = r["hist"]
        W = r["width_um"] * 1e-6
        s_layer = r["layer_um"] * 1e-6
        r["s_max"] = s_layer + hist["pit_depth"]
        r["s_mean"] = s_layer + hist["pit_volume_with_damage"] / W
        T = hist["time"][-1]
        centre = edge = None
        series = read_series(r["dir"])
        r["vtu_t"], r["vtu_centre"], r["vtu_edge"] = [], [], []
        max_c = 0.0
        for t, path in series:
            x, fld = read_pvtu(path)
            e = fld["phase"] == 0
            max_c = max(max_c, float(fld["concentration"][e].max()) / C_SAT)
            cols = column_depths(x, fld, r["h"])
            xs = np.array(sorted(cols))
            mid = xs[np.argsort(np.abs(xs - W / 2))[:2]]
            ends = xs[[0, -1]]
            r["vtu_t"].append(t)
            r["vtu_centre"].append(s_layer + np.mean([cols[c][0] for c in mid]))
            r["vtu_edge"].append(s_layer + np.mean([cols[c][0] for c in ends]))
        if series:
            centre, edge = r["vtu_centre"][-1], r["vtu_edge"][-1]
        ref = stefan_at(T)
        # s^2 = a + 2 K_fit St t over the last three quarters: the growth
        # rate as an effective diffusivity, relative to the same fit of the
        # exact solution (which gives 0.989 K and sqrt(a) = 10.11 um on
        # [10, 40] s), and sqrt(a) as an effective initial depth
        fit = hist["time"] >= 0.25 * T
        slope, a = np.polyfit(hist["time"][fit], r["s_mean"][fit] ** 2, 1)
        ref_fit = t_ref >= 0.25 * T
        slope_ref = np.polyfit(t_ref[ref_fit], s_ref[ref_fit] ** 2, 1)[0]
        r["row"] = dict(
            case=r["name"], model=r["interface"], delta_um=r["delta_um"],
            m=r["m"], width_um=r["width_um"], T=T,
            s_max_um=r["s_max"][-1] * 1e6, s_mean_um=r["s_mean"][-1] * 1e6,
            s_centre_um=centre * 1e6 if centre else float("nan"),
            s_edge_um=edge * 1e6 if edge else float("nan"),
            stefan_um=ref * 1e6,
            quasi_steady_um=float(quasi_steady(s0, T)) * 1e6,
            issue_um=float(issue_formula(T)) * 1e6,
            err_max_pct=100 * (r["s_max"][-1] / ref - 1),
            err_mean_pct=100 * (r["s_mean"][-1] / ref - 1),
            err_centre_pct=100 * (centre / ref - 1) if centre else float("nan"),
            K_fit_over_K=slope / (2 * K * ST),
            K_fit_over_stefan_fit=slope / slope_ref,
            s0_fit_um=math.sqrt(a) * 1e6 if a > 0 else float("nan"),
            stefan_s0_fit_um=math.sqrt(np.polyfit(
                t_ref[ref_fit], s_ref[ref_fit] ** 2, 1)[1]) * 1e6,
            ranks=r["ranks"], threads=r["threads"], nodes=r["nodes"],
            steps=r["steps"], dt=r["time_step"], safety=r["safety"],
            model_limited=r["model_limited"], wall_s=r["wall_s"],
            max_c_over_c_sat=max_c)
        table.append(r["row"])

    if diffusion:
        fig, axes = plt.subplots(1, 2, figsize=(13, 5))
        ax = axes[0]
        ax.plot(t_ref, s_ref * 1e6, "k-", lw=2,
                label="exact Stefan, s0 = 10 um")
        ax.plot(t_ref, quasi_steady(s0, t_ref) * 1e6, "k--",
                label="quasi-steady s^2 = s0^2 + 2K St t")
        ax.plot(t_ref, issue_formula(t_ref) * 1e6, "k:",
                label="d^2 = 2K (C_sat/C_solid) t (s0 = 0)")
        widest = {}
        for r in diffusion:
            key = (r["interface"], r["delta_um"])
            if r["ranks"] == 1 and r["safety"] == 0.9 and \
                    r["width_um"] > widest.get(key, 0):
                widest[key] = r["width_um"]
        for r in diffusion:
            if r["ranks"] > 1 or r["safety"] != 0.9 or \
                    r["width_um"] < widest[(r["interface"], r["delta_um"])]:
                continue
            line, = ax.plot(r["hist"]["time"], r["s_mean"] * 1e6, lw=1,
                            label="%s (mean)" % r["name"])
            ax.plot(r["hist"]["time"], r["s_max"] * 1e6, lw=0.6, ls="--",
                    color=line.get_color())
            if r["vtu_t"]:
                ax.plot(r["vtu_t"], np.array(r["vtu_centre"]) * 1e6, "o",
                        ms=3, color=line.get_color())
        ax.set_xlabel("time (s)")
        ax.set_ylabel("pit depth from the mouth s = s0 + depth (um)")
        ax.set_title("(a) diffusion control, widest strip of each interface "
                     "and delta:\nmean (solid), max (dashed), centre line "
                     "(dots)", fontsize=9)
        ax.legend(fontsize=6)
        ax.grid(alpha=0.3)
        ax = axes[1]
        for r in diffusion:
            if r["ranks"] > 1:
                continue
            ref = np.interp(r["hist"]["time"], t_ref, s_ref)
            keep = r["hist"]["time"] > 0.5
            ax.plot(r["hist"]["time"][keep],
                    100 * (r["s_mean"][keep] / ref[keep] - 1),
                    lw=0.5 + r["width_um"] / r["delta_um"] / 8,
                    color={1: "C2", 2: "C0", 4: "C1"}.get(
                        int(r["delta_um"]), "k"),
                    ls=(":" if r["safety"] != 0.9 else
                        "-" if r["interface"] == "dr" else "--"),
                    label=r["name"])
        ax.axhline(0, color="k", lw=0.5)
        ax.set_xlabel("time (s)")
        ax.set_ylabel("mean depth s / exact Stefan - 1 (%)")
        ax.set_title("all strips (colour: delta; solid: dr, dashed: id, dotted: "
                     "safety factor 0.3; thicker: wider)", fontsize=9)
        ax.legend(fontsize=5, ncol=2)
        ax.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(os.path.join(out, "depth_vs_time.png"), dpi=130)
        plt.close(fig)

        fig, ax = plt.subplots(figsize=(8.5, 4.8))
        groups = {}
        for row in table:
            if row["ranks"] == 1 and row["safety"] == 0.9:
                groups.setdefault(row["model"], {}).setdefault(
                    row["width_um"] / row["delta_um"], []).append(row)
        markers = {4: "v", 8: "o", 16: "^"}
        colours = {"dr": "C0", "id": "C3"}
        for model, by_width in sorted(groups.items()):
            for ratio, rows in sorted(by_width.items()):
                rows.sort(key=lambda q_: q_["delta_um"])
                d = [q_["delta_um"] for q_ in rows]
                ax.plot(d, [q_["err_mean_pct"] for q_ in rows], "-",
                        marker=markers.get(ratio, "o"), color=colours.get(
                            model, "k"), alpha=0.4 + 0.6 * min(ratio, 16) / 16,
                        label="%s, W = %g delta, mean" % (model, ratio))
                ax.plot(d, [q_["err_centre_pct"] for q_ in rows], ":",
                        marker=markers.get(ratio, "o"), mfc="none",
                        color=colours.get(model, "k"),
                        label="%s, W = %g delta, centre line" % (model, ratio))
            # W -> infinity (linear in delta / W) where two widths or more
            by_delta = {}
            for ratio, rows in by_width.items():
                for q_ in rows:
                    by_delta.setdefault(q_["delta_um"], []).append(q_)
            inf = []
            for delta, rows in sorted(by_delta.items()):
                if len(rows) >= 2:
                    inv = [q_["delta_um"] / q_["width_um"] for q_ in rows]
                    inf.append((delta, np.polyfit(
                        inv, [q_["err_mean_pct"] for q_ in rows], 1)[1]))
            if inf:
                ax.plot([a for a, _ in inf], [b for _, b in inf], "*--",
                        ms=12, color=colours.get(model, "k"),
                        label="%s, W -> infinity (mean)" % model)
        if k_h is not None:
            T = table[0]["T"]
            ax.plot([0], [100 * (stefan_at(T * k_h) / stefan_at(T) - 1)],
                    "kD", label="exact Stefan with K_h = %.3f K (m = 4)" % k_h)
        ax.axhline(0, color="k", lw=0.5)
        ax.set_xlim(-0.1, 2.2)
        ax.set_xlabel("horizon delta (um), m = 4")
        ax.set_ylabel("depth s at the end / exact Stefan - 1 (%)")
        ax.set_title("(a) error at the end time against delta and strip "
                     "width W", fontsize=9)
        ax.legend(fontsize=6, loc="center left", bbox_to_anchor=(1.01, 0.5))
        ax.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(os.path.join(out, "error_vs_delta.png"), dpi=130)
        plt.close(fig)

    # ------------------------------------------------------------ (b)
    q = None
    act_rows = []
    for r in activation:
        hist = r["hist"]
        W = r["width_um"] * 1e-6
        q = r["current_density"] / (VALENCE * FARADAY)
        v = q / (C_SOLID - C_SAT)
        t = hist["time"]
        mean_depth = hist["pit_volume_with_damage"] / W
        # dissolved per unit area: metal lost minus what converted nodes
        # took with them (about C_sat each)
        dissolved = (hist["metal_amount"][0] - hist["metal_amount"]
                     - C_SAT * hist["pit_volume"]) / W
        fit = t >= 0.25 * t[-1]
        v_max = np.polyfit(t[fit], hist["pit_depth"][fit], 1)[0]
        v_mean = np.polyfit(t[fit], mean_depth[fit], 1)[0]
        q_meas = np.polyfit(t[fit], dissolved[fit], 1)[0]
        r["act"] = (t, hist["pit_depth"], mean_depth, dissolved)
        act_rows.append(dict(
            case=r["name"], delta_um=r["delta_um"], m=r["m"],
            width_um=r["width_um"], T=t[-1], v_um_s=v * 1e6,
            v_max_um_s=v_max * 1e6, v_mean_um_s=v_mean * 1e6,
            depth_end_um=hist["pit_depth"][-1] * 1e6,
            vt_um=v * t[-1] * 1e6, q=q, q_meas=q_meas,
            q_ratio=q_meas / q, wall_s=r["wall_s"], steps=r["steps"],
            nodes=r["nodes"], dt=r["time_step"]))
    if activation:
        fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
        t_line = np.linspace(0, max(r["end_time"] for r in activation), 50)
        v = q / (C_SOLID - C_SAT)
        axes[0].plot(t_line, v * t_line * 1e6, "k-", lw=2,
                     label="v t, v = i/(nF)/(C_solid - C_sat)")
        axes[1].plot(t_line, q * t_line, "k-", lw=2, label="i/(nF) t")
        for r in activation:
            t, dmax, dmean, diss = r["act"]
            line, = axes[0].plot(t, dmean * 1e6, lw=1,
                                 label="%s (mean)" % r["name"])
            axes[0].plot(t, dmax * 1e6, lw=0.8, ls="--",
                         color=line.get_color(), label="%s (max)" % r["name"])
            axes[1].plot(t, diss, lw=1, label=r["name"])
        axes[0].set_ylabel("depth below the initial surface (um)")
        axes[1].set_ylabel("dissolved metal per unit area (mol/m^2)")
        for ax in axes:
            ax.set_xlabel("time (s)")
            ax.grid(alpha=0.3)
            ax.legend(fontsize=7)
        axes[0].set_title("(b) activation control, i = 5.1 kA/m^2",
                          fontsize=9)
        fig.tight_layout()
        fig.savefig(os.path.join(out, "activation.png"), dpi=130)
        plt.close(fig)

    # ------------------------------------------------------------ (c)
    shape_rows = []
    for r in shapes:
        dim = r["dim"]
        series = read_series(r["dir"])
        ts, depth, width = [], [], []
        last = None
        for t, path in series:
            x, fld = read_pvtu(path)
            d, w = shape_measures(x, fld, r["h"], dim)
            ts.append(t)
            depth.append(d)
            width.append(w)
            last = (x, fld)
        r["shape"] = (ts, depth, width, last)
        hist = r["hist"]
        shape_rows.append(dict(
            case=r["name"], dim=dim, model=r["interface"],
            delta_um=r["delta_um"], m=r["m"], T=hist["time"][-1],
            depth_um=depth[-1] * 1e6 if depth else float("nan"),
            width_um=width[-1] * 1e6 if width else float("nan"),
            history_depth_um=hist["pit_depth"][-1] * 1e6,
            volume=hist["pit_volume"][-1], nodes=r["nodes"],
            steps=r["steps"], dt=r["time_step"], ranks=r["ranks"],
            threads=r["threads"], wall_s=r["wall_s"]))
    if shapes:
        fig, ax = plt.subplots(figsize=(6.5, 4.5))
        for r in shapes:
            ts, depth, width, _ = r["shape"]
            line, = ax.plot(ts, np.array(depth) * 1e6, "o-",
                            label="%s depth" % r["name"])
            ax.plot(ts, np.array(width) * 1e6, "s--", mfc="none",
                    color=line.get_color(), label="%s width" % r["name"])
        ax.set_xlabel("time (s)")
        ax.set_ylabel("pit depth / width below the film (um)")
        ax.set_title("(c) pit from an opening in a passive film", fontsize=9)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(os.path.join(out, "pit_shape_growth.png"), dpi=130)
        plt.close(fig)

        fig, axes = plt.subplots(len(shapes), 2,
                                 figsize=(11, 3.6 * len(shapes)),
                                 squeeze=False)
        for row, r in zip(axes, shapes):
            x, fld = r["shape"][3]
            h = r["h"]
            if r["dim"] == 2:
                sel = None
                title = "%s: 2D, t = %g s" % (r["name"], r["end_time"])
            else:
                yv = x[:, 1]
                plane = yv[np.argmin(np.abs(yv))]
                sel = np.abs(yv - plane) < 0.25 * h
                title = "%s: 3D section y = %.2g um, t = %g s" % (
                    r["name"], plane * 1e6, r["end_time"])
            ax1 = r["dim"] - 1
            conc = np.where(fld["phase"] == 0, fld["concentration"] / C_SAT,
                            np.nan)
            img, extent = grid_image(x, conc, h, 0, ax1, sel)
            cmap = plt.get_cmap("viridis").copy()
            cmap.set_bad("0.75")
            im = row[0].imshow(img, origin="lower", extent=extent,
                               vmin=0, vmax=1.1, cmap=cmap)
            plt.colorbar(im, ax=row[0], label="C / C_sat (electrolyte)")
            row[0].set_title(title + ": concentration (grey: metal, film)",
                             fontsize=8)
            # metal shaded by its dissolved fraction phi, electrolyte and
            # film in flat colours
            phi = fld["corrosion_damage"]
            shade = np.where(fld["phase"] == 1, 0.25 + 0.5 * phi,
                             np.where(fld["phase"] == 0, 1.0, 0.0))
            img, extent = grid_image(x, shade, h, 0, ax1, sel)
            im = row[1].imshow(img, origin="lower", extent=extent, vmin=0,
                               vmax=1, cmap="cividis")
            cb = plt.colorbar(im, ax=row[1], ticks=[0, 0.25, 0.75, 1])
            cb.ax.set_yticklabels(["passive film", "metal, phi = 0",
                                   "metal, phi = 1", "electrolyte"],
                                  fontsize=7)
            row[1].set_title(title + ": phase", fontsize=8)
            for ax in row:
                ax.set_xlabel("x (um)")
                ax.set_ylabel("%s (um)" % ("y" if r["dim"] == 2 else "z"))
        fig.tight_layout()
        fig.savefig(os.path.join(out, "pit_shape.png"), dpi=130)
        plt.close(fig)

    # ------------------------------------------------------------ wall times
    fig, ax = plt.subplots(figsize=(8, 4))
    names = [r["name"] for r in runs]
    ax.barh(names, [r["wall_s"] for r in runs])
    for i, r in enumerate(runs):
        ax.text(r["wall_s"], i, " %.1f s (%d x %d, %d nodes, %d steps)" % (
            r["wall_s"], r["ranks"], r["threads"], r["nodes"], r["steps"]),
            va="center", fontsize=6)
    ax.set_xscale("log")
    ax.set_xlabel("wall time (s)")
    ax.invert_yaxis()
    fig.tight_layout()
    fig.savefig(os.path.join(out, "wall_time.png"), dpi=130)
    plt.close(fig)

    # ------------------------------------------------------------ processes
    mpi = []
    by_name = {r["name"]: r for r in runs}
    for r in runs:
        if r["ranks"] > 1 and r["name"].endswith("_np%d" % r["ranks"]):
            base = by_name.get(r["name"][:-len("_np%d" % r["ranks"])])
            if base is None:
                continue
            a, b = base["hist"], r["hist"]
            n = min(len(a["time"]), len(b["time"]))
            worst = {}
            for k in a:
                if k in b:
                    scale = max(np.abs(a[k][:n]).max(), 1e-300)
                    worst[k] = float(np.abs(a[k][:n] - b[k][:n]).max() / scale)
            mpi.append((base["name"], r["name"], len(a["time"]),
                        len(b["time"]), worst))

    # ------------------------------------------------------------ tables
    with open(os.path.join(out, "pit_growth.csv"), "w") as f:
        rows = table + act_rows + shape_rows
        keys = []
        for row in rows:
            keys += [k for k in row if k not in keys]
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        for row in rows:
            w.writerow(row)

    if table:
        T = table[0]["T"]
        print("\n(a) diffusion control, strip, s0 = 10 um; depth s from the "
              "mouth at t = %g s: exact Stefan %.2f um, quasi-steady %.2f um, "
              "d^2 = 2K(C_sat/C_solid)t %.2f um; K_fit / K: the slope of s^2 "
              "(mean depth) against t over the last three quarters, over that "
              "of the exact solution; s0 fit: sqrt of the intercept (exact "
              "solution: %.2f um); max C / C_sat: the largest electrolyte "
              "concentration in the PVTU output (overshoot above C_sat)\n" % (
                  T, table[0]["stefan_um"], table[0]["quasi_steady_um"],
                  table[0]["issue_um"], table[0]["stefan_s0_fit_um"]))
        print("| case | interface | delta (um) | m | W (um) | s max (um) | "
              "s mean (um) | s centre (um) | s edge (um) | err max | "
              "err mean | err centre | K_fit / K | s0 fit (um) | "
              "max C / C_sat | ranks x threads | nodes | steps | dt (s) | "
              "wall (s) |")
        print("|" + "---|" * 20)
        for q_ in table:
            print("| %s | %s | %g | %d | %g | %s | %s | %s | %s | %s %% | "
                  "%s %% | %s %% | %.4f | %.2f | %.2f | %d x %d | %d | %d | "
                  "%.3g%s | %.1f |" % (
                      q_["case"], q_["model"], q_["delta_um"], q_["m"],
                      q_["width_um"], fmt(q_["s_max_um"]),
                      fmt(q_["s_mean_um"]), fmt(q_["s_centre_um"]),
                      fmt(q_["s_edge_um"]), fmt(q_["err_max_pct"]),
                      fmt(q_["err_mean_pct"]), fmt(q_["err_centre_pct"]),
                      q_["K_fit_over_stefan_fit"], q_["s0_fit_um"],
                      q_["max_c_over_c_sat"], q_["ranks"], q_["threads"], q_["nodes"], q_["steps"],
                      q_["dt"], (" (model)" if q_["model_limited"] == "yes"
                                 else "") + ("" if q_["safety"] == 0.9 else
                                             ", safety %g" % q_["safety"]),
                      q_["wall_s"]))
    extrapolated = []
    if table:
        groups = {}
        for q_ in table:
            if q_["ranks"] == 1 and q_["safety"] == 0.9:
                groups.setdefault((q_["model"], q_["delta_um"]), []).append(q_)
        for (model, delta), rows in sorted(groups.items()):
            if len(rows) < 2:
                continue
            inv = np.array([q_["delta_um"] / q_["width_um"] for q_ in rows])
            e = np.array([q_["err_mean_pct"] for q_ in rows])
            kf = np.array([q_["K_fit_over_stefan_fit"] for q_ in rows])
            ce, e0 = np.polyfit(inv, e, 1)
            ck, k0 = np.polyfit(inv, kf, 1)
            extrapolated.append((model, delta, sorted(q_["width_um"] for q_ in rows),
                                 e0, ce, k0, ck))
        if k_h is not None:
            T = table[0]["T"]
            print("\nlong-wave diffusivity of the discrete operator (2D, m = 4, "
                  "q = 2, constant influence, exact partial volumes): K_h / K "
                  "= %.4f; exact Stefan with K_h at t = %g s: %.2f um (%+.2f %%)"
                  % (k_h, T, stefan_at(T * k_h) * 1e6,
                     100 * (stefan_at(T * k_h) / stefan_at(T) - 1)))
        if extrapolated:
            print("\nstrip width: err mean = e_inf + c delta / W (least squares "
                  "over the widths), K_fit / K = k_inf + c' delta / W\n")
            print("| interface | delta (um) | widths (um) | e_inf (%) | c (%) "
                  "| k_inf | c' |")
            print("|" + "---|" * 7)
            for model, delta, widths, e0, ce, k0, ck in extrapolated:
                print("| %s | %g | %s | %+.2f | %.1f | %.4f | %.3f |" % (
                    model, delta, ", ".join("%g" % w for w in widths), e0, ce,
                    k0, ck))
            print()
            for model in sorted(set(e[0] for e in extrapolated)):
                pts = sorted((e[1], e[3], e[5]) for e in extrapolated
                             if e[0] == model)
                if len(pts) < 2:
                    continue
                d = np.array([p_[0] for p_ in pts])
                e = np.array([p_[1] for p_ in pts])
                k = np.array([p_[2] for p_ in pts])
                lin_e = np.polyfit(d[:2], e[:2], 1)
                lin_k = np.polyfit(d[:2], k[:2], 1)
                text = ("%s, W -> infinity, delta -> 0 (m = 4): linear through "
                        "delta = %g, %g um: err %+.2f %%, K_fit / K %.4f"
                        % (model, d[0], d[1], lin_e[1], lin_k[1]))
                if len(pts) >= 3:
                    text += ("; quadratic through delta = %s um: err %+.2f %%, "
                             "K_fit / K %.4f" % (
                                 ", ".join("%g" % x_ for x_ in d),
                                 np.polyfit(d, e, 2)[2],
                                 np.polyfit(d, k, 2)[2]))
                print(text)

    if act_rows:
        print("\n(b) activation control, i = 5.1e3 A/m^2: v = %.4f um/s, "
              "q = i/(nF) = %.5f mol/(m^2 s)\n" % (
                  act_rows[0]["v_um_s"], act_rows[0]["q"]))
        print("| case | delta (um) | m | W (um) | depth at %g s (um) | v t "
              "(um) | v fit max (um/s) | v fit mean (um/s) | dissolved "
              "rate / q | nodes | steps | wall (s) |" % act_rows[0]["T"])
        print("|" + "---|" * 12)
        for q_ in act_rows:
            print("| %s | %g | %d | %g | %.2f | %.2f | %.4f | %.4f | %.4f | "
                  "%d | %d | %.1f |" % (
                      q_["case"], q_["delta_um"], q_["m"], q_["width_um"],
                      q_["depth_end_um"], q_["vt_um"], q_["v_max_um_s"],
                      q_["v_mean_um_s"], q_["q_ratio"], q_["nodes"],
                      q_["steps"], q_["wall_s"]))
        groups = {}
        for q_ in act_rows:
            groups.setdefault(q_["delta_um"], []).append(q_)
        for delta, rows in sorted(groups.items()):
            if len(rows) >= 2:
                inv = [q_["delta_um"] / q_["width_um"] for q_ in rows]
                c, r0 = np.polyfit(inv, [q_["q_ratio"] for q_ in rows], 1)
                print("delta = %g um: dissolved rate / q = %.4f %+.3f delta / W "
                      "(widths %s um)" % (delta, r0, c, ", ".join(
                          "%g" % q_["width_um"] for q_ in rows)))
    if shape_rows:
        print("\n(c) pit shape (opening in a passive film), diffusion "
              "control\n")
        print("| case | dim | interface | delta (um) | m | t (s) | depth "
              "(um) | width (um) | nodes | steps | ranks x threads | wall "
              "(s) |")
        print("|" + "---|" * 12)
        for q_ in shape_rows:
            print("| %s | %d | %s | %g | %d | %g | %.2f | %.2f | %d | %d | "
                  "%d x %d | %.1f |" % (
                      q_["case"], q_["dim"], q_["model"], q_["delta_um"],
                      q_["m"], q_["T"], q_["depth_um"], q_["width_um"],
                      q_["nodes"], q_["steps"], q_["ranks"], q_["threads"],
                      q_["wall_s"]))
        for r in shapes:
            ts, depth, width, _ = r["shape"]
            print("%s: t (s) %s; depth (um) %s; width (um) %s" % (
                r["name"], " ".join("%g" % t for t in ts),
                " ".join("%.1f" % (d * 1e6) for d in depth),
                " ".join("%.1f" % (w * 1e6) for w in width)))
    for base, other, na, nb, worst in mpi:
        print("\nprocesses: %s (1 process) against %s: %d and %d history "
              "rows; largest relative difference per column: %s" % (
                  base, other, na, nb, ", ".join(
                      "%s %.1e" % (k, v) for k, v in worst.items())))
    print("\nwrote %s/pit_growth.csv, stefan_reference.csv and the PNGs"
          % out)


if __name__ == "__main__":
    main()
