#!/usr/bin/env python3
"""Tables and figures of bench/diffusion/run_pit_growth_1d.sh.

    /usr/bin/python3 bench/diffusion/plot_pit_growth_1d.py DIR

DIR holds runs.csv and runs/<case>/history.csv. Writes DIR/pit_growth_1d.csv
(one row per case), DIR/stefan_reference.csv, DIR/error_vs_delta.png,
DIR/error_vs_wall.png, DIR/depth_vs_time.png, DIR/activation.png (when
there are such cases), and prints the tables (markdown).

The references (exact Stefan solution with s0 = 10 um by the Landau
transformation, the quasi-steady s^2 = s0^2 + 2 K St t and the issue's
d^2 = 2 K (C_sat/C_solid) t) come from plot_pit_growth.py in this folder.
In 1D the depth from the mouth is s = s0 + pit_volume_with_damage (the
converted length plus the dissolved fraction of the metal nodes: the front
by mass); pit_depth (far edge of the deepest converted node, steps of h) is
reported as s max.
Diffusion control: error s / s_exact(T) - 1 at the end time T; for each
interface model, the observed order from three successive horizons
p = log2((s_2d - s_d) / (s_d - s_d/2)) and the first-order Richardson
extrapolation of the two finest, s_R = 2 s_d/2 - s_d.
Activation control: the dissolved amount per unit cross-section
metal_amount(0) - metal_amount(t) - C_sat pit_volume against i/(nF) t, and
pit_volume_with_damage against v t, v = i/(nF)/(C_solid - C_sat); rates
fitted over the last three quarters of the run.
Processes: a case <name>_npN is compared with <name>, row by row.
Time step: cases with a safety factor other than 0.9 are left out of the
order and the extrapolation; for each interface and delta with two steps or
more, the error is extrapolated to dt -> 0 linearly in dt through the two
smallest steps.
"""
import csv
import math
import os
import sys

import numpy as np

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_pit_growth import (  # noqa: E402
    _TYPES, C_SAT, C_SOLID, FARADAY, VALENCE, _decode, issue_formula,
    quasi_steady, read_history, read_series, stefan)
import xml.etree.ElementTree as ET  # noqa: E402

S0 = 10e-6
STEFAN_40 = 48.637  # um, the exact value at 40 s quoted in the test input


def read_pvtu_1d(path):
    """Nodes (cell centres) and point fields (one value per node) of a 1D
    PVTU file: deal.II writes each node as a line cell with 2 vertices."""
    root = ET.parse(path).getroot()
    points, fields = [], {}
    for piece in root.find("PUnstructuredGrid").findall("Piece"):
        vtu = ET.parse(os.path.join(os.path.dirname(path),
                                    piece.get("Source"))).getroot()
        p = vtu.find("UnstructuredGrid/Piece")
        a = p.find("Points/DataArray")
        points.append(_decode(a.text, _TYPES[a.get("type")]).reshape(-1, 3))
        for a in p.find("PointData"):
            fields.setdefault(a.get("Name"), []).append(
                _decode(a.text, _TYPES[a.get("type")]))
    x = np.concatenate(points).reshape(-1, 2, 3).mean(axis=1)[:, 0]
    return x, {k: np.concatenate(v).reshape(-1, 2)[:, 0]
               for k, v in fields.items()}


def max_electrolyte_concentration(run_dir):
    """Largest C / C_sat of the electrolyte nodes over the VTU snapshots
    (a sample of the run, not its true maximum)."""
    worst = float("nan")
    for _, path in read_series(run_dir):
        _, f = read_pvtu_1d(path)
        e = f["phase"] == 0
        if e.any():
            c = float(f["concentration"][e].max()) / C_SAT
            worst = c if math.isnan(worst) else max(worst, c)
    return worst


def main():
    if len(sys.argv) != 2:
        print(__doc__)
        sys.exit(2)
    out = sys.argv[1]
    with open(os.path.join(out, "runs.csv")) as f:
        runs = list(csv.DictReader(f))
    for r in runs:
        for k in ("delta_um", "h_um", "end_time", "wall_s", "current_density",
                  "interface_diffusivity", "time_step", "lower_um",
                  "upper_um"):
            r[k] = float(r[k])
        for k in ("m", "nodes", "steps", "ranks", "threads", "flux_exponent"):
            r[k] = int(r[k])
        r["safety"] = float(r.get("safety_factor") or 0.9)
        r["hist"] = read_history(os.path.join(out, "runs", r["case"],
                                              "history.csv"))
        h = r["hist"]
        r["t"] = h["time"]
        r["s"] = S0 + h["pit_volume_with_damage"]
        r["s_max"] = S0 + h["pit_depth"]

    diffusion = [r for r in runs if r["control"] == "diffusion"]
    activation = [r for r in runs if r["control"] == "activation"]
    serial = [r for r in diffusion if r["ranks"] == 1 and r["safety"] == 0.9]
    steps = [r for r in diffusion if r["ranks"] == 1 and r["safety"] != 0.9]

    t_end = max(r["end_time"] for r in diffusion) if diffusion else 40.0
    t_ref, s_ref = stefan(S0, t_end)
    with open(os.path.join(out, "stefan_reference.csv"), "w") as f:
        f.write("time,stefan_s0_10um,quasi_steady_s0_10um,issue_formula_s0_0\n")
        for t, s in zip(t_ref, s_ref):
            f.write("%.6g,%.9e,%.9e,%.9e\n" % (t, s, quasi_steady(S0, t),
                                               issue_formula(t)))

    def stefan_at(t):
        return np.interp(t, t_ref, s_ref)

    # ------------------------------------------------------------ (a), (b)
    rows = []
    for r in diffusion:
        T = r["t"][-1]
        ref = float(stefan_at(T))
        fit = r["t"] >= 0.25 * T
        slope = np.polyfit(r["t"][fit], r["s"][fit] ** 2, 1)[0]
        ref_fit = t_ref >= 0.25 * T
        slope_ref = np.polyfit(t_ref[ref_fit], s_ref[ref_fit] ** 2, 1)[0]
        r["err"] = 100 * (r["s"][-1] / ref - 1)
        rows.append(dict(
            case=r["case"], control="diffusion", interface=r["interface"],
            delta_um=r["delta_um"], h_um=r["h_um"], T=T,
            s_um=r["s"][-1] * 1e6, s_max_um=r["s_max"][-1] * 1e6,
            stefan_um=ref * 1e6, err_pct=r["err"],
            err_max_pct=100 * (r["s_max"][-1] / ref - 1),
            K_fit_over_stefan_fit=slope / slope_ref,
            max_c_over_c_sat=max_electrolyte_concentration(
                os.path.join(out, "runs", r["case"])),
            nodes=r["nodes"], steps=r["steps"], dt=r["time_step"],
            model_limited=r["model_limited"], safety=r["safety"],
            ranks=r["ranks"],
            threads=r["threads"], wall_s=r["wall_s"],
            history_rows=len(r["t"])))
    by_model = {}
    for r in serial:
        by_model.setdefault(r["interface"], []).append(r)
    for lst in by_model.values():
        lst.sort(key=lambda r: -r["delta_um"])
    richardson = {}
    orders = {}
    for model, lst in by_model.items():
        if len(lst) >= 2:
            c, f_ = lst[-2], lst[-1]
            ratio = c["delta_um"] / f_["delta_um"]
            s_r = f_["s"][-1] + (f_["s"][-1] - c["s"][-1]) / (ratio - 1)
            richardson[model] = (c["delta_um"], f_["delta_um"], s_r,
                                 float(stefan_at(f_["t"][-1])))
        orders[model] = []
        for a, b, c in zip(lst, lst[1:], lst[2:]):
            d1 = a["s"][-1] - b["s"][-1]
            d2 = b["s"][-1] - c["s"][-1]
            p = math.log(d1 / d2) / math.log(a["delta_um"] / b["delta_um"]) \
                if d1 * d2 > 0 else float("nan")
            orders[model].append((a["delta_um"], b["delta_um"],
                                  c["delta_um"], p))

    names = {"dr": "dissolution rate, q = 1", "id": "interface diffusivity, q = 2"}
    if diffusion:
        fig, axes = plt.subplots(1, 2, figsize=(13, 5))
        ax = axes[0]
        ax.plot(t_ref, s_ref * 1e6, "k-", lw=2, label="exact Stefan, s0 = 10 um")
        ax.plot(t_ref, quasi_steady(S0, t_ref) * 1e6, "k--",
                label="quasi-steady s^2 = s0^2 + 2K St t")
        ax.plot(t_ref, issue_formula(t_ref) * 1e6, "k:",
                label="d^2 = 2K (C_sat/C_solid) t (s0 = 0)")
        for model, lst in sorted(by_model.items()):
            for r in lst[-2:]:
                line, = ax.plot(r["t"], r["s"] * 1e6, lw=1,
                                label="%s (s0 + pit_volume_with_damage)"
                                % r["case"])
                ax.plot(r["t"], r["s_max"] * 1e6, lw=0.6, ls="--",
                        color=line.get_color())
        ax.set_xlabel("time (s)")
        ax.set_ylabel("pit depth from the mouth s (um)")
        ax.set_title("1D, diffusion control: the two finest horizons of each "
                     "interface model\n(solid: front by mass, dashed: far edge "
                     "of the deepest converted node)", fontsize=9)
        ax.legend(fontsize=7)
        ax.grid(alpha=0.3)
        ax = axes[1]
        for r in serial:
            keep = r["t"] > 0.5
            ax.plot(r["t"][keep],
                    100 * (r["s"][keep] / stefan_at(r["t"][keep]) - 1),
                    ls="-" if r["interface"] == "dr" else "--", lw=1,
                    label=r["case"])
        ax.axhline(0, color="k", lw=0.5)
        ax.set_xlabel("time (s)")
        ax.set_ylabel("s / exact Stefan - 1 (%)")
        ax.set_title("all 1-process diffusion-control runs (solid: dr, "
                     "dashed: id)", fontsize=9)
        ax.legend(fontsize=7, ncol=2)
        ax.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(os.path.join(out, "depth_vs_time.png"), dpi=130)
        plt.close(fig)

        fig, ax = plt.subplots(figsize=(7.5, 5))
        colours = {"dr": "C0", "id": "C3"}
        for model, lst in sorted(by_model.items()):
            d = np.array([r["delta_um"] for r in lst])
            e = np.array([r["err"] for r in lst])
            ax.loglog(d, np.abs(e), "o-", color=colours.get(model, "k"),
                      label="%s: |s / s_exact - 1|" % names.get(model, model))
            if model in richardson:
                s_r = richardson[model][2]
                e_r = np.array([r["s"][-1] / s_r - 1 for r in lst]) * 100
                ax.loglog(d, np.abs(e_r), "s:", mfc="none",
                          color=colours.get(model, "k"),
                          label="%s: |s / s_R - 1|, s_R = %.3f um (%+.3f %% "
                          "from exact)" % (model, s_r * 1e6,
                                           100 * (s_r / richardson[model][3] - 1)))
        for r in steps:
            ax.loglog([r["delta_um"]], [abs(r["err"])], "x", ms=8,
                      color=colours.get(r["interface"], "k"),
                      alpha=1 if r["safety"] < 0.2 else 0.6)
        if steps:
            ax.plot([], [], "kx", label="smaller step (safety 0.3, 0.1)")
        allr = [r for r in serial]
        if allr:
            d = np.array(sorted({r["delta_um"] for r in allr}))
            e0 = max(abs(r["err"]) for r in allr if r["delta_um"] == d[-1])
            ax.loglog(d, e0 * d / d[-1], "k--", lw=0.8, label="slope 1")
        ax.set_xlabel("horizon delta (um), m = 4, h = delta / 4")
        ax.set_ylabel("error of s at %g s (%%)" % t_end)
        ax.set_title("1D pit growth, diffusion control: error against delta\n"
                     "s_R: first-order Richardson extrapolation of the two "
                     "finest", fontsize=9)
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(os.path.join(out, "error_vs_delta.png"), dpi=130)
        plt.close(fig)

        fig, ax = plt.subplots(figsize=(7.5, 5))
        for model, lst in sorted(by_model.items()):
            w = [r["wall_s"] for r in lst]
            e = [abs(r["err"]) for r in lst]
            ax.loglog(w, e, "o-", color=colours.get(model, "k"),
                      label=names.get(model, model))
            for r in lst:
                ax.annotate("%g um" % r["delta_um"], (r["wall_s"], abs(r["err"])),
                            fontsize=7, xytext=(3, 3),
                            textcoords="offset points")
        ax.set_xlabel("wall time (s), 1 process, 1 thread")
        ax.set_ylabel("|s / s_exact - 1| at %g s (%%)" % t_end)
        ax.set_title("1D pit growth, diffusion control: error against wall "
                     "time", fontsize=9)
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(os.path.join(out, "error_vs_wall.png"), dpi=130)
        plt.close(fig)

    # ------------------------------------------------------------ (c)
    act_rows = []
    q = None
    for r in activation:
        hist = r["hist"]
        t = r["t"]
        q = r["current_density"] / (VALENCE * FARADAY)
        v = q / (C_SOLID - C_SAT)
        depth = hist["pit_volume_with_damage"]
        dissolved = (hist["metal_amount"][0] - hist["metal_amount"]
                     - C_SAT * hist["pit_volume"])
        fit = t >= 0.25 * t[-1]
        v_fit = np.polyfit(t[fit], depth[fit], 1)[0]
        v_max = np.polyfit(t[fit], hist["pit_depth"][fit], 1)[0]
        q_fit = np.polyfit(t[fit], dissolved[fit], 1)[0]
        r["act"] = (t, depth, hist["pit_depth"], dissolved)
        act_rows.append(dict(
            case=r["case"], control="activation", interface=r["interface"],
            delta_um=r["delta_um"], h_um=r["h_um"], T=t[-1], v_um_s=v * 1e6,
            vt_um=v * t[-1] * 1e6, depth_um=depth[-1] * 1e6,
            depth_max_um=hist["pit_depth"][-1] * 1e6,
            depth_over_vt=depth[-1] / (v * t[-1]),
            v_fit_um_s=v_fit * 1e6, v_fit_over_v=v_fit / v,
            v_max_fit_um_s=v_max * 1e6, q=q, dissolved=dissolved[-1],
            dissolved_over_qt=dissolved[-1] / (q * t[-1]),
            q_fit_over_q=q_fit / q, nodes=r["nodes"], steps=r["steps"],
            dt=r["time_step"], ranks=r["ranks"], threads=r["threads"],
            wall_s=r["wall_s"], history_rows=len(t)))
    if activation:
        v = q / (C_SOLID - C_SAT)
        fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
        t_line = np.linspace(0, max(r["end_time"] for r in activation), 50)
        axes[0].plot(t_line, v * t_line * 1e6, "k-", lw=2,
                     label="v t, v = i/(nF)/(C_solid - C_sat)")
        axes[1].plot(t_line, q * t_line, "k-", lw=2, label="i/(nF) t")
        for r in activation:
            t, depth, dmax, diss = r["act"]
            line, = axes[0].plot(t, depth * 1e6, lw=1,
                                 label="%s pit_volume_with_damage" % r["case"])
            axes[0].plot(t, dmax * 1e6, lw=0.8, ls="--",
                         color=line.get_color(),
                         label="%s pit_depth" % r["case"])
            axes[1].plot(t, diss, lw=1, ls="--", label=r["case"])
        axes[0].set_ylabel("depth below x = 0 (um)")
        axes[1].set_ylabel("dissolved metal per unit cross-section (mol/m^2)")
        for ax in axes:
            ax.set_xlabel("time (s)")
            ax.grid(alpha=0.3)
            ax.legend(fontsize=7)
        axes[0].set_title("1D activation control, i = 5.1 kA/m^2", fontsize=9)
        fig.tight_layout()
        fig.savefig(os.path.join(out, "activation.png"), dpi=130)
        plt.close(fig)

    # ------------------------------------------------------------ processes
    mpi = []
    by_name = {r["case"]: r for r in runs}
    for r in runs:
        suffix = "_np%d" % r["ranks"]
        if r["ranks"] > 1 and r["case"].endswith(suffix):
            base = by_name.get(r["case"][:-len(suffix)])
            if base is None:
                continue
            a, b = base["hist"], r["hist"]
            n = min(len(a["time"]), len(b["time"]))
            scaled, pointwise = {}, {}
            for k in a:
                if k not in b:
                    continue
                x, y = a[k][:n], b[k][:n]
                scaled[k] = float(np.abs(x - y).max()
                                  / max(np.abs(x).max(), 1e-300))
                nz = np.abs(x) > 0
                pointwise[k] = float((np.abs(x - y)[nz] / np.abs(x[nz])).max()) \
                    if nz.any() else float(np.abs(y).max())
            mpi.append((base, r, len(a["time"]), len(b["time"]), scaled,
                        pointwise))

    # ------------------------------------------------------------ tables
    with open(os.path.join(out, "pit_growth_1d.csv"), "w") as f:
        all_rows = rows + act_rows
        keys = []
        for row in all_rows:
            keys += [k for k in row if k not in keys]
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        for row in all_rows:
            w.writerow(row)

    if rows:
        T = rows[0]["T"]
        print("\n(a, b) 1D diffusion control, s0 = 10 um; s = s0 + "
              "pit_volume_with_damage at t = %g s: exact Stefan %.3f um, "
              "quasi-steady %.2f um, d^2 = 2K(C_sat/C_solid)t %.2f um. "
              "K_fit / K: slope of s^2 against t over the last three quarters "
              "over that of the exact solution. max C / C_sat: the largest "
              "electrolyte concentration in the VTU snapshots (every T / 10)\n" % (
                  T, float(stefan_at(T)) * 1e6,
                  float(quasi_steady(S0, T)) * 1e6,
                  float(issue_formula(T)) * 1e6))
        print("| case | interface | delta (um) | h (um) | s (um) | err | "
              "s max (um) | K_fit / K | max C / C_sat | ranks | nodes | "
              "steps | dt (s) | safety | wall (s) |")
        print("|" + "---|" * 15)
        for q_ in rows:
            print("| %s | %s | %g | %g | %.3f | %+.3f %% | %.2f | %.4f | "
                  "%.3f | %d | %d | %d | %.3g%s | %g | %.2f |" % (
                      q_["case"], q_["interface"], q_["delta_um"],
                      q_["h_um"], q_["s_um"], q_["err_pct"], q_["s_max_um"],
                      q_["K_fit_over_stefan_fit"], q_["max_c_over_c_sat"],
                      q_["ranks"], q_["nodes"], q_["steps"], q_["dt"],
                      " (model)" if q_["model_limited"] == "yes" else "",
                      q_["safety"], q_["wall_s"]))
        print()
        for model in sorted(by_model):
            for a, b, c, p in orders.get(model, []):
                print("%s: observed order from delta = %g, %g, %g um: %.3f"
                      % (model, a, b, c, p))
            if model in richardson:
                dc, df, s_r, ref = richardson[model]
                print("%s: Richardson (first order) from delta = %g, %g um: "
                      "%.3f um, %+.3f %% from the exact %.3f um" % (
                          model, dc, df, s_r * 1e6, 100 * (s_r / ref - 1),
                          ref * 1e6))
    if steps:
        groups = {}
        for r in serial + steps:
            groups.setdefault((r["interface"], r["delta_um"]), []).append(r)
        print("\ntime step (1 process): error at the end against dt; dt -> 0: "
              "linear in dt through the two smallest steps\n")
        print("| interface | delta (um) | safety: dt (s), err | err, dt -> 0 |")
        print("|---|---|---|---|")
        for (model, delta), lst in sorted(groups.items()):
            if len(lst) < 2:
                continue
            lst.sort(key=lambda r: -r["time_step"])
            a, b = lst[-2], lst[-1]
            e0 = b["err"] - (a["err"] - b["err"]) * b["time_step"] / (
                a["time_step"] - b["time_step"])
            print("| %s | %g | %s | %+.2f %% |" % (
                model, delta, "; ".join("%g: %.3g, %+.3f %%" % (
                    r["safety"], r["time_step"], r["err"]) for r in lst), e0))
    if act_rows:
        print("\n(c) 1D activation control, i = 5.1e3 A/m^2: v = %.4f um/s, "
              "q = i/(nF) = %.5f mol/(m^2 s); fits over the last three "
              "quarters\n" % (act_rows[0]["v_um_s"], act_rows[0]["q"]))
        print("| case | delta (um) | h (um) | depth at %g s (um) | v t (um) | "
              "depth / v t | v fit (um/s) | v fit / v | pit_depth (um) | "
              "dissolved / (q t) | dissolved rate / q | nodes | steps | "
              "wall (s) |" % act_rows[0]["T"])
        print("|" + "---|" * 14)
        for q_ in act_rows:
            print("| %s | %g | %g | %.3f | %.3f | %.4f | %.4f | %.4f | %.2f | "
                  "%.4f | %.4f | %d | %d | %.2f |" % (
                      q_["case"], q_["delta_um"], q_["h_um"], q_["depth_um"],
                      q_["vt_um"], q_["depth_over_vt"], q_["v_fit_um_s"],
                      q_["v_fit_over_v"], q_["depth_max_um"],
                      q_["dissolved_over_qt"], q_["q_fit_over_q"],
                      q_["nodes"], q_["steps"], q_["wall_s"]))
    for base, other, na, nb, scaled, pointwise in mpi:
        worst = max(pointwise.values())
        print("\n(d) processes: %s (1 process, %.2f s) against %s (%d x %d, "
              "%.2f s): %d and %d history rows; largest difference per column "
              "relative to the column's largest value: %s; largest pointwise "
              "relative difference over all columns and rows: %.1e" % (
                  base["case"], base["wall_s"], other["case"], other["ranks"],
                  other["threads"], other["wall_s"], na, nb, ", ".join(
                      "%s %.1e" % (k, v) for k, v in scaled.items()), worst))
    print("\nwrote %s/pit_growth_1d.csv, stefan_reference.csv and the PNGs"
          % out)


if __name__ == "__main__":
    main()
