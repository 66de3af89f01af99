#!/usr/bin/env python3
"""Chapter-3 set-ups of Lu (2010) in 3D: the barrel scenes against the material-point driver.

    /usr/bin/python3 validation/chapter3_3d/run_study.py [--exe PATH] [--out DIR] [--quick]

Runs the scenes of examples/barrel/chapter3 (thesis §3.5, SPEC §2 set-ups 1-4: passive and
activated elongation, isometric, isometric then concentric) with `isomuscle run`, the same
protocols with `isomuscle material uniaxial` (one homogeneous material point), and the parameter
study of §3.6 (D, sigma0 in passive elongation; k_c, k_e, d in activated elongation) on a coarse
barrel, and writes CSVs, PNG figures and report.md (the numbers and the differences between the
3D body and the material point) into --out (default validation/output/chapter3_3d, git-ignored).
See README.md in this folder.
"""

import argparse
import csv
import json
import math
import re
import subprocess
import sys
import time
import tomllib
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[1]
sys.path.insert(0, str(REPO / "validation" / "chapter3"))
from uniaxial_runs import run_uniaxial  # noqa: E402

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SCENE_DIR = REPO / "examples" / "barrel" / "chapter3"
MODEL = "lu2010"
KPA = 1e-3

# The barrel (examples/geometry/barrel.igs, geometry/shapes.cpp): length 5 cm, radius
# r(z) = r_end + (r_mid - r_end) 4 t (1 - t), t = z / L, end diameters 0.9 cm, middle 1.75 cm.
L0 = 0.05
R_END, R_MID = 0.0045, 0.00875
A_END, A_MID = math.pi * R_END**2, math.pi * R_MID**2
GAUGE = 0.01  # m, axis_z60 - axis_z40: the gauge over which the strain at the centre is measured

# Set-ups: scene file, the driver protocol it is compared with, start of the moving stage (s).
SETUPS = {
    "setup1": ("setup1_passive.toml", "passive", 0.0),
    "setup2": ("setup2_activated.toml", "activated", 0.5),
    "setup3": ("setup3_isometric.toml", "isometric", None),
    "setup4": ("setup4_concentric.toml", "concentric", 0.4),
}
STRAINS = [0.05, 0.10, 0.15, 0.20, 0.25, 0.30]
PARTS = ["see", "pe", "matrix", "vol", "total"]
MP_PART = {"see": "sigma_see_Pa", "pe": "sigma_pe_Pa", "matrix": "sigma_matrix_Pa",
           "vol": "sigma_vol_Pa", "total": "sigma33_Pa"}
PART_LABEL = {"see": "σ_CE (= SEE part)", "pe": "σ_PE", "matrix": "σ_I (matrix)",
              "vol": "σ_VOL", "total": "σ33"}
PART_STYLE = {"see": "C0", "pe": "C3", "matrix": "C2", "vol": "C1", "total": "k"}

# §3.6 as in validation/chapter3/run_figures.py: one parameter varied, the others Table 3.10;
# D and sigma0 in passive elongation, k_c, k_e and d in activated elongation, compared at 20 %.
SENSITIVITY = [
    ("D", "setup1", [1e-9, 1e-8, 1e-7, 1e-6], "m²/N"),
    ("sigma0", "setup1", [1.6e5, 4.0e5, 7.0e5, 1.0e6], "Pa"),
    ("k_c", "setup2", [4.0, 5.0, 5.88], ""),
    ("k_e", "setup2", [3.14, 5.0, 7.56], ""),
    ("d", "setup2", [1.1, 1.5, 1.8], ""),
]
DEFAULTS = {"D": 1e-9, "sigma0": 7.0e5, "k_c": 5.0, "k_e": 5.0, "d": 1.5}
SENS_STRAIN = 0.20
# The sensitivity runs stop at 20 % strain: passive 2.0 s, activated 0.5 s + 2.0 s.
SENS_END = {"setup1": 2.0, "setup2": 2.5}
FINE_REFINE = "[0, 4, 1]"    # the committed scenes: 5 spans along z
COARSE_REFINE = "[0, 2, 1]"  # --quick and the sensitivity study: 3 spans along z (24 elements)


def force_length(r):
    """Thesis 3.28 on r = lambda_f / lambda_opt."""
    r = np.asarray(r, dtype=float)
    return np.select([r < 0.4, r < 0.6, r < 1.4, r < 1.6],
                     [0.0 * r, 9 * (r - 0.4) ** 2, 1 - 4 * (1 - r) ** 2, 9 * (r - 1.6) ** 2], 0.0)


# ---------------------------------------------------------------- scenes and runs


def replace_line(text, key, line, name):
    """Replaces the first line that starts with `key = ` (a failure when there is none)."""
    new, n = re.subn(rf"(?m)^{re.escape(key)} = .*$", line, text, count=1)
    if n != 1:
        raise SystemExit(f"run_study: no line '{key} = ...' in {name}")
    return new


def scene_copy(setup, out_dir, refine, dt_factor=1.0, end=None, times=None, fields=None,
               params=None, tag=""):
    """A copy of a committed scene in out_dir/scenes: the IGES path absolute, the refinement
    replaced, optionally dt scaled, end time, output times and fields replaced and material
    parameters added. Returns (path, parsed scene)."""
    name = SETUPS[setup][0]
    text = (SCENE_DIR / name).read_text(encoding="utf-8")
    rel = '"../../geometry/'
    if rel not in text:
        raise SystemExit(f"run_study: {name} does not name ../../geometry/")
    text = text.replace(rel, '"' + str(REPO / "examples" / "geometry") + "/")
    text = replace_line(text, "knot_insertion", f"knot_insertion = {refine}", name)
    if refine == COARSE_REFINE:
        # near_end sits on the Gauss point v = 0.1 of 5 spans; on 3 spans the nearest one is 1/6
        # (see the note on probe positions in the scene and in README.md).
        text = text.replace("xi = [0.125, 0.1, ", "xi = [0.125, 0.166666666666667, ")
    parsed = tomllib.loads(text)
    if dt_factor != 1.0:
        t = parsed["time"]
        text = replace_line(text, "dt", f"dt = {t['dt'] * dt_factor!r}", name)
        if "dt_max" in t:
            text = replace_line(text, "dt_max", f"dt_max = {t['dt_max'] * dt_factor!r}", name)
    if end is not None:
        text = replace_line(text, "end", f"end = {end!r}", name)
    if times is not None:
        text = replace_line(text, "times", "times = [" + ", ".join(repr(x) for x in times) + "]",
                            name)
    if fields is not None:
        text = replace_line(text, "fields", "fields = [" + ", ".join(f'"{f}"' for f in fields)
                            + "]", name)
    if params:
        lines = "".join(f"{k} = {v!r}\n" for k, v in params.items())
        if "[material.parameters]\n" in text:
            text = text.replace("[material.parameters]\n", "[material.parameters]\n" + lines, 1)
        else:
            text, n = re.subn(r'(?m)^(model = "lu2010".*)$',
                              lambda m: m.group(1) + "\n[material.parameters]\n" + lines.rstrip(),
                              text, count=1)
            if n != 1:
                raise SystemExit(f"run_study: no model line in {name}")
    path = out_dir / "scenes" / f"{setup}{tag}.toml"
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    return path, tomllib.loads(text)


class Run3D:
    """One `isomuscle run`: probes.csv as columns, summary.json, and the derived quantities."""

    def __init__(self, setup, scene, run_dir, wall_s):
        self.setup = setup
        self.scene = scene
        self.wall_s = wall_s
        self.summary = json.loads((run_dir / "summary.json").read_text(encoding="utf-8"))
        with open(run_dir / "probes.csv", newline="", encoding="utf-8") as f:
            rows = list(csv.reader(f))
        header, body = rows[0], np.array([[float(x) for x in r] for r in rows[1:]], dtype=float)
        self.col = {h: body[:, i] for i, h in enumerate(header)}
        # t = 0: the reference state (no row in probes.csv; every probe is 0 there, volume V0).
        self.v0 = self.summary["volume_initial_m3"]
        for h in header:
            self.col[h] = np.concatenate([[self.v0 if h == "volume" else 0.0], self.col[h]])
        self.t = self.col["time"]
        moving = [b for b in scene["boundary"] if b.get("face") == "v1" and
                  b.get("type") == "displacement"]
        if moving:
            b = moving[0]
            start, stop = b.get("start", 0.0), b.get("stop", math.inf)
            self.u_end = b["velocity"][2] * np.clip(self.t, start, stop) - b["velocity"][2] * start
        else:
            self.u_end = 0.0 * self.t
        self.strain = self.u_end / L0            # nominal (engineering) strain of the barrel
        self.force = self.col["pull_force_z"]    # N, > 0 tension
        self.p_mean = self.force * L0 / self.v0  # force per mean undeformed area V0 / L0
        self.p_mid = self.force / A_MID          # force per undeformed mid-section area
        self.local = (self.col["axis_z60"] - self.col["axis_z40"]) / GAUGE  # strain at the centre
        self.dv = self.col["volume"] / self.v0 - 1.0
        D = scene["material"].get("parameters", {}).get("D", 1e-9)
        # Virial theorem: int tr(sigma) dv = int x . t da; with the clamps' axial forces only,
        # int p dv = F l / 3 (l = L0 + u_end), and U_J = (J - 1)^2 / D (3.21) gives
        # p = 2 (J - 1) / D, so dV / V = D F l / (6 V). The clamps' lateral tractions are left out.
        self.dv_virial = D * self.force * (L0 + self.u_end) / (6.0 * self.v0)

    def part(self, probe, part):
        return self.col[f"{probe}.{part}"]

    def at_time(self, values, t):
        return float(np.interp(t, self.t, values))

    def at_strain(self, values, strain, after=0.0):
        keep = self.t >= after - 1e-12
        x, y = self.strain[keep], values[keep]
        order = np.argsort(x, kind="stable")
        return float(np.interp(strain, x[order], y[order]))

    def stats(self):
        s = self.summary
        return {"status": s["status"], "elements": s["elements"], "dofs": s["dofs"],
                "steps": s["steps"], "newton": s["newton_iterations"],
                "cuts": len(s.get("step_cuts", [])), "wall": s["wall_seconds"]["total"],
                "reached": s["time"]["reached"], "end": s["time"]["end"]}


def run_scene(exe, setup, scene_path, scene, out_dir, log):
    run_dir = out_dir / "runs" / scene_path.stem
    start = time.perf_counter()
    done = subprocess.run([str(exe), "run", str(scene_path), "--out", str(run_dir)],
                          capture_output=True, text=True)
    wall = time.perf_counter() - start
    (out_dir / "runs").mkdir(parents=True, exist_ok=True)
    (out_dir / "runs" / f"{scene_path.stem}.log").write_text(done.stdout + done.stderr,
                                                             encoding="utf-8")
    if not (run_dir / "summary.json").is_file():
        raise SystemExit(f"run_study: {scene_path} failed ({done.returncode}):\n"
                         f"{done.stderr[-2000:]}")
    run = Run3D(setup, scene, run_dir, wall)
    st = run.stats()
    log(f"  {scene_path.stem}: {st['status']} to {st['reached']:g} s, {st['steps']} steps, "
        f"{st['newton']} Newton its, {st['cuts']} cuts, {st['wall']:.1f} s")
    if st["status"] != "converged":
        log(f"  WARNING: {scene_path.stem} stopped at {st['reached']} s: "
            f"{run.summary.get('reason')}")
    return run


def write_run_csv(run, path):
    cols = {"time_s": run.t, "eng_strain": run.strain, "pull_force_N": run.force,
            "force_per_mean_area_Pa": run.p_mean, "force_per_mid_area_Pa": run.p_mid,
            "centre_local_strain": run.local, "mid_surface_radial_m": run.col["mid_surface_x"],
            "volume_change": run.dv,
            "volume_change_virial": run.dv_virial}
    for probe in ("centre", "mid_inner", "mid_outer", "near_end"):
        for p in PARTS:
            cols[f"{probe}_{p}_Pa"] = run.part(probe, p)
    with open(path, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        w.writerow(cols.keys())
        for i in range(len(run.t)):
            w.writerow([f"{c[i]:.10g}" for c in cols.values()])


# ---------------------------------------------------------------- comparisons


def pct(a, b):
    """(a - b) / b in %."""
    return 100.0 * (a - b) / b if b != 0 else float("nan")


def mp_at_strain(mp, column, strain, after=0.0):
    """The driver's column at an engineering strain of its loading stage; NaN outside it (the
    centre of the activated barrel starts the pull shortened)."""
    keep = mp["time_s"] >= after - 1e-12
    x = mp["eng_strain"][keep]
    if not (x.min() - 1e-12 <= strain <= x.max() + 1e-12):
        return float("nan")
    return mp.at_strain(column, strain, after)


def elongation_rows(run, mp, after):
    """Per strain: 3D nominal stresses, centre stress and local strain against the driver."""
    rows = []
    for s in STRAINS:
        if s > run.strain.max() + 1e-9:
            continue
        local = run.at_strain(run.local, s, after)
        rows.append({
            "strain": s,
            "mp_P": mp_at_strain(mp, "eng_stress_Pa", s, after),
            "p_mean": run.at_strain(run.p_mean, s, after),
            "p_mid": run.at_strain(run.p_mid, s, after),
            "force": run.at_strain(run.force, s, after),
            "mp_sigma": mp_at_strain(mp, "sigma33_Pa", s, after),
            "centre": run.at_strain(run.part("centre", "total"), s, after),
            "inner": run.at_strain(run.part("mid_inner", "total"), s, after),
            "outer": run.at_strain(run.part("mid_outer", "total"), s, after),
            "local": local,
            "mp_sigma_local": mp_at_strain(mp, "sigma33_Pa", local, after),
            "mp_P_local": mp_at_strain(mp, "eng_stress_Pa", local, after),
            "dv": run.at_strain(run.dv, s, after),
            "dv_virial": run.at_strain(run.dv_virial, s, after),
        })
    return rows


def time_rows(run, mp, times):
    rows = []
    for t in times:
        r = {"t": t, "force": run.at_time(run.force, t), "p_mean": run.at_time(run.p_mean, t),
             "p_mid": run.at_time(run.p_mid, t), "local": run.at_time(run.local, t),
             "mp_P": float(np.interp(t, mp["time_s"], mp["eng_stress_Pa"])),
             "mp_stretch": float(np.interp(t, mp["time_s"], mp["stretch"])),
             "dv": run.at_time(run.dv, t), "dv_virial": run.at_time(run.dv_virial, t),
             "bulge": run.at_time(run.col["mid_surface_x"], t)}
        for p in PARTS:
            r[p] = run.at_time(run.part("centre", p), t)
            r["mp_" + p] = float(np.interp(t, mp["time_s"], mp[MP_PART[p]]))
        r["inner"] = run.at_time(run.part("mid_inner", "total"), t)
        r["outer"] = run.at_time(run.part("mid_outer", "total"), t)
        r["near_end"] = run.at_time(run.part("near_end", "total"), t)
        rows.append(r)
    return rows


# ---------------------------------------------------------------- figures


def strain_axes(ax, title, ylabel):
    ax.set_xlabel("engineering strain of the barrel, u_end / L0 (%)")
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=9)
    ax.grid(alpha=0.3)


def zoom(ax, curves, limit=0.20):
    top = max(np.max(y[x <= limit + 1e-12]) for x, y in curves if np.any(x <= limit + 1e-12))
    bot = min(0.0, min(np.min(y[x <= limit + 1e-12]) for x, y in curves
                       if np.any(x <= limit + 1e-12)))
    m = 0.04 * (top - bot)
    ax.set_xlim(-0.5, 100 * limit + 0.5)
    ax.set_ylim((bot - m) * KPA, (top + m) * KPA)


def figure_elongation(run, mp, after, number, title, out):
    """Left: nominal stress (force per area) against nominal strain; right: the fibre Cauchy
    stress at the centre against the nominal strain and against the strain measured at the
    centre, with the driver's sigma33. Bottom row: up to 20 %."""
    keep = run.t >= after - 1e-12
    mkeep = mp["time_s"] >= after - 1e-12
    x3, xl = run.strain[keep], run.local[keep]
    xm = mp["eng_strain"][mkeep]
    nominal = [(xm, mp["eng_stress_Pa"][mkeep], "k-", "material point P33"),
               (x3, run.p_mean[keep], "C0-", "barrel F L0 / V0 (mean area)"),
               (x3, run.p_mid[keep], "C0--", "barrel F / A_mid (mid-section)")]
    centre = [(xm, mp["sigma33_Pa"][mkeep], "k-", "material point σ33"),
              (x3, run.part("centre", "total")[keep], "C1-", "barrel centre σ_ff, at nominal strain"),
              (xl, run.part("centre", "total")[keep], "C1--",
               "barrel centre σ_ff, at the strain of the centre"),
              (x3, run.part("mid_outer", "total")[keep], "C2:", "barrel σ_ff at r = 8.3 mm")]
    fig, axes = plt.subplots(2, 2, figsize=(11, 8))
    for row in range(2):
        for colm, (curves, ylabel, what) in enumerate(
                [(nominal, "engineering stress (kPa)", "force per area"),
                 (centre, "fibre Cauchy stress (kPa)", "stress at the centre")]):
            ax = axes[row][colm]
            for x, y, style, label in curves:
                ax.plot(100 * x, y * KPA, style, label=label)
            if row == 1:
                zoom(ax, [(c[0], c[1]) for c in curves])
            strain_axes(ax, f"set-up {number}, {title}: {what}" + (", up to 20 %" if row else ""),
                        ylabel)
            ax.legend(fontsize=7, loc="upper left")
    fig.tight_layout()
    name = f"fig_setup{number}_{title.replace(' ', '_')}.png"
    fig.savefig(out / name, dpi=140)
    plt.close(fig)
    return name


def figure_parts(run, mp, number, title, marks, out):
    """Left: sigma33 at the centre and its parts (3.44), barrel (solid) and material point
    (dashed); right: force per mean area and per mid-section area against the driver's P33."""
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 4.6))
    for p in PARTS:
        ax1.plot(run.t, run.part("centre", p) * KPA, "-", color=PART_STYLE[p],
                 lw=2 if p == "total" else 1.2, label=f"barrel {PART_LABEL[p]}")
        ax1.plot(mp["time_s"], mp[MP_PART[p]] * KPA, "--", color=PART_STYLE[p], lw=0.9,
                 label=f"point {PART_LABEL[p]}")
    ax1.set_xlabel("time (s)")
    ax1.set_ylabel("fibre Cauchy stress at the centre (kPa)")
    ax1.set_title(f"set-up {number}, {title}: σ33 and its parts (3.44)", fontsize=9)
    ax1.legend(fontsize=6.5, ncol=2)
    ax2.plot(mp["time_s"], mp["eng_stress_Pa"] * KPA, "k-", label="material point P33")
    ax2.plot(run.t, run.p_mean * KPA, "C0-", label="barrel F L0 / V0 (mean area)")
    ax2.plot(run.t, run.p_mid * KPA, "C0--", label="barrel F / A_mid")
    ax2.plot(run.t, run.part("centre", "total") * KPA, "C1-", label="barrel σ_ff at the centre")
    ax2.plot(run.t, run.part("near_end", "total") * KPA, "C4:",
             label="barrel σ_ff on the axis 5 mm from the clamp")
    ax2.set_xlabel("time (s)")
    ax2.set_ylabel("stress (kPa)")
    ax2.set_title(f"set-up {number}: force per area and local stresses", fontsize=9)
    ax2.legend(fontsize=7)
    for ax in (ax1, ax2):
        ax.grid(alpha=0.3)
        for m in marks:
            ax.axvline(m, color="0.6", lw=0.8, ls=":")
    fig.tight_layout()
    name = f"fig_setup{number}_{title.replace(' ', '_')}.png"
    fig.savefig(out / name, dpi=140)
    plt.close(fig)
    return name


def figure_sensitivity(sens, out):
    names = []
    for name, params in [("fig_sensitivity_D_sigma0.png", ["D", "sigma0"]),
                         ("fig_sensitivity_kc_ke_d.png", ["k_c", "k_e", "d"])]:
        fig, axes = plt.subplots(1, len(params), figsize=(5.2 * len(params), 4.3))
        for ax, p in zip(axes, params):
            setup, unit, runs = sens[p]
            after = SETUPS[setup][2]
            for i, (v, run, mp) in enumerate(runs):
                keep = run.t >= after - 1e-12
                mk = mp["time_s"] >= after - 1e-12
                lim = SENS_STRAIN + 1e-9
                mx = mp["eng_strain"][mk]
                ax.plot(100 * run.strain[keep], run.p_mean[keep] * KPA, "-", color=f"C{i}",
                        label=f"{p} = {v:g}{' ' + unit if unit else ''}: barrel F L0/V0")
                ax.plot(100 * mx[mx <= lim], mp["eng_stress_Pa"][mk][mx <= lim] * KPA, "--",
                        color=f"C{i}", lw=0.9, label="  material point P33")
            strain_axes(ax, f"§3.6 in 3D: {p} ({'passive' if setup == 'setup1' else 'activated'}"
                        " elongation)", "engineering stress (kPa)")
            ax.legend(fontsize=6.5, loc="upper left")
        fig.tight_layout()
        fig.savefig(out / name, dpi=140)
        plt.close(fig)
        names.append(name)
    return names


# ---------------------------------------------------------------- report


def kpa(x):
    return "–" if not math.isfinite(x) else f"{x * KPA:.2f}"


def signed_pct(a, b, digits=1):
    d = pct(a, b)
    return "–" if not math.isfinite(d) else f"{d:+.{digits}f} %"


def stats_table(runs):
    lines = ["| run | elements | DOFs | steps | Newton its | step cuts | wall (s) | reached |",
             "|---|---|---|---|---|---|---|---|"]
    for name, run in runs:
        s = run.stats()
        lines.append(f"| {name} | {s['elements']} | {s['dofs']} | {s['steps']} | {s['newton']} | "
                     f"{s['cuts']} | {s['wall']:.1f} | {s['reached']:g} / {s['end']:g} s |")
    return lines


def elongation_table(rows):
    lines = ["| strain | point P33 | barrel F L0/V0 (Δ) | barrel F/A_mid (Δ) | point σ33 | "
             "centre σ_ff (Δ) | strain at the centre | point σ33 there | centre against it | "
             "σ_ff at r = 3.9 / 8.3 mm | ΔV/V (virial) |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(
            f"| {100 * r['strain']:.0f} % | {kpa(r['mp_P'])} | {kpa(r['p_mean'])} "
            f"({pct(r['p_mean'], r['mp_P']):+.0f} %) | {kpa(r['p_mid'])} "
            f"({pct(r['p_mid'], r['mp_P']):+.0f} %) | {kpa(r['mp_sigma'])} | {kpa(r['centre'])} "
            f"({pct(r['centre'], r['mp_sigma']):+.0f} %) | {100 * r['local']:.2f} % | "
            f"{kpa(r['mp_sigma_local'])} | {signed_pct(r['centre'], r['mp_sigma_local'])} | "
            f"{kpa(r['inner'])} / {kpa(r['outer'])} | {r['dv']:.3g} ({r['dv_virial']:.3g}) |")
    return lines


def time_table(rows):
    lines = ["| t (s) | point σ33 | centre σ33 (Δ) | centre CE / VOL / I / PE | point CE / VOL / I / "
             "PE | barrel F L0/V0 (point P33) | F/A_mid | strain at the centre | σ_ff near the "
             "clamp |", "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(
            f"| {r['t']:g} | {kpa(r['mp_total'])} | {kpa(r['total'])} "
            f"({pct(r['total'], r['mp_total']):+.1f} %) | {kpa(r['see'])} / {kpa(r['vol'])} / "
            f"{kpa(r['matrix'])} / {kpa(r['pe'])} | {kpa(r['mp_see'])} / {kpa(r['mp_vol'])} / "
            f"{kpa(r['mp_matrix'])} / {kpa(r['mp_pe'])} | {kpa(r['p_mean'])} ({kpa(r['mp_P'])}) | "
            f"{kpa(r['p_mid'])} | {100 * r['local']:.2f} % | {kpa(r['near_end'])} |")
    return lines


def write_report(out, args, exe, runs3d, mps, results, sens, figures, elapsed):
    refine = COARSE_REFINE if args.quick else FINE_REFINE
    L = [
        "# Chapter 3 (Lu 2010, §3.5–3.6) in 3D: the barrel against one material point",
        "",
        f"Scenes `examples/barrel/chapter3/setup*.toml` (law `{MODEL}`, Table 3.10 defaults, "
        f"fibres along z, both ends clamped), knot insertion {refine}"
        f"{' and dt × 2 (--quick)' if args.quick else ''}; material point: `isomuscle material "
        f"uniaxial --model {MODEL} --protocol …`, dt = 1e-3 s. Executable `{exe}`. "
        f"Whole study {elapsed:.0f} s.",
        "",
        "Stresses in kPa. *Barrel F L0/V0*: pull force over the mean undeformed cross-section "
        f"V0/L0 = {1e4 * runs3d['setup1'].v0 / L0:.4f} cm² (the engineering stress of a bar of "
        f"the same length and volume); *F/A_mid*: over the mid-section {1e4 * A_MID:.4f} cm² "
        f"(the ends have {1e4 * A_END:.4f} cm²). *Centre σ_ff*: fibre Cauchy stress a·σ·a "
        "(thesis 5.30, 5.41) at the Gauss point next to the axis on the mid-plane (r = 0.49 mm); "
        "its parts are those of 3.44 with σ_VOL = p~ (the mixed formulation's pressure). "
        "*Strain at the centre*: (u_z(z = 3 cm) − u_z(z = 2 cm)) / 1 cm on the axis. Δ: relative "
        "to the material point.",
        "",
        "## Runs",
        "",
    ]
    L += stats_table([(k, runs3d[k]) for k in SETUPS])
    L += ["", "## Figures", ""] + [f"* `{f}`" for f in figures]

    for key, number, title in [("setup1", 1, "passive elongation"),
                               ("setup2", 2, "activated elongation")]:
        rows = results[key]
        L += ["", f"## Set-up {number}: {title}", ""]
        if key == "setup2":
            r0 = results["setup2_t05"]
            L += [f"End of the 0.5 s isometric activation: point P33 = {kpa(r0['mp_P'])}, barrel "
                  f"F L0/V0 = {kpa(r0['p_mean'])} ({pct(r0['p_mean'], r0['mp_P']):+.1f} %), "
                  f"centre σ_ff = {kpa(r0['total'])} ({pct(r0['total'], r0['mp_total']):+.1f} %), "
                  f"strain at the centre {100 * r0['local']:+.2f} %.", ""]
        L += elongation_table(rows)
    for key, number, title in [("setup3", 3, "isometric contraction"),
                               ("setup4", 4, "isometric then concentric")]:
        L += ["", f"## Set-up {number}: {title}", ""]
        L += results[key + "_notes"]
        L += [""] + time_table(results[key])

    if sens:
        L += sensitivity_section(sens)
    (out / "report.md").write_text("\n".join(L) + "\n", encoding="utf-8")


def sensitivity_section(sens):
    L = ["", "## Sensitivity (§3.6) in 3D", "",
          f"Coarse barrel (knot insertion {COARSE_REFINE}, 24 elements), runs to 20 % strain; "
          "barrel F L0/V0 and the material point's P33 at 20 % strain (kPa), spread = "
          "(max − min) / max.", "",
          "| parameter (set-up) | values | barrel F L0/V0 at 20 % | spread | point P33 at 20 % | "
          "spread | barrel ΔV/V at 20 % |", "|---|---|---|---|---|---|---|"]
    spreads = {}
    for p, (setup, unit, runs) in sens.items():
        after = SETUPS[setup][2]
        b = [r.at_strain(r.p_mean, SENS_STRAIN, after) for _, r, _ in runs]
        m = [mp.at_strain("eng_stress_Pa", SENS_STRAIN, after) for _, _, mp in runs]
        dv = [r.at_strain(r.dv, SENS_STRAIN, after) for _, r, _ in runs]
        spreads[p] = ((max(b) - min(b)) / max(b), (max(m) - min(m)) / max(m), b, m)
        L.append(f"| {p} ({'passive' if setup == 'setup1' else 'activated'}) | "
                 f"{', '.join(f'{v:g}' for v, _, _ in runs)} {unit} | "
                 f"{', '.join(kpa(x) for x in b)} | {100 * spreads[p][0]:.1f} % | "
                 f"{', '.join(kpa(x) for x in m)} | {100 * spreads[p][1]:.1f} % | "
                 f"{', '.join(f'{x:.2g}' for x in dv)} |")
    L += ["", "Sensitivity run statistics:", ""]
    seen, srows = set(), []
    for p, (setup, unit, runs) in sens.items():
        for v, r, _ in runs:
            if id(r) not in seen:
                seen.add(id(r))
                srows.append((f"{setup} {p} = {v:g}", r))
    L += stats_table(srows)

    def trend(p):
        b = spreads[p][2]
        return "increases" if b[-1] > b[0] else "decreases"

    s0 = spreads["sigma0"][2]
    D = spreads["D"][2]
    yes = {True: "yes", False: "**no**"}
    L += ["", "Against the statements of §3.6 (barrel, 20 % strain):", "",
          "| thesis | barrel | material point | agrees (barrel) |", "|---|---|---|---|",
          f"| stress increases with σ0, k_c, d and decreases with D | σ0 {trend('sigma0')}, "
          f"k_c {trend('k_c')}, d {trend('d')}, D {trend('D')} | see the table | "
          f"{yes[(trend('sigma0'), trend('k_c'), trend('d'), trend('D')) == ('increases',) * 3 + ('decreases',)]} |",
          f"| σ0 0.16 → 1.0 MPa: relative difference up to 60.7 % | "
          f"{100 * (s0[-1] - s0[0]) / s0[-1]:.1f} % of the largest | "
          f"{100 * spreads['sigma0'][1]:.1f} % | same order |",
          f"| k_c has little influence | spread {100 * spreads['k_c'][0]:.1f} % | "
          f"{100 * spreads['k_c'][1]:.1f} % | {yes[spreads['k_c'][0] < 0.05]} |",
          f"| k_e acts like k_c | spread {100 * spreads['k_e'][0]:.1f} % | "
          f"{100 * spreads['k_e'][1]:.1f} % | {yes[spreads['k_e'][0] < 0.05]} |",
          f"| d has a bigger influence than k_c and k_e | spread {100 * spreads['d'][0]:.1f} % | "
          f"{100 * spreads['d'][1]:.1f} % | "
          f"{yes[spreads['d'][0] > max(spreads['k_c'][0], spreads['k_e'][0])]} |",
          f"| D has a considerable influence | spread {100 * spreads['D'][0]:.1f} % over "
          f"1e-9…1e-6 ({100 * (D[0] - D[2]) / D[0]:.1f} % over 1e-9…1e-7) | "
          f"{100 * spreads['D'][1]:.1f} % | {yes[spreads['D'][0] > 0.10]} (spread > 10 %) |"]
    return L


# ---------------------------------------------------------------- main


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--exe", default=str(REPO / "build" / "release" / "app" / "isomuscle"),
                        help="isomuscle executable (default build/release/app/isomuscle)")
    parser.add_argument("--out", default=str(REPO / "validation" / "output" / "chapter3_3d"),
                        help="output folder (default validation/output/chapter3_3d)")
    parser.add_argument("--quick", action="store_true",
                        help=f"coarse and fast: knot insertion {COARSE_REFINE} and dt x 2 for "
                             "every run")
    parser.add_argument("--no-sensitivity", action="store_true", help="skip the §3.6 study")
    args = parser.parse_args()
    exe = Path(args.exe).resolve()
    if not exe.is_file():
        raise SystemExit(f"run_study: no executable {exe} (build it or pass --exe)")
    out = Path(args.out)
    (out / "csv").mkdir(parents=True, exist_ok=True)
    started = time.perf_counter()

    def log(msg):
        print(msg, flush=True)

    refine = COARSE_REFINE if args.quick else FINE_REFINE
    dt_factor = 2.0 if args.quick else 1.0

    log("material point runs")
    mps = {}
    for key, (_, protocol, _) in SETUPS.items():
        mps[key] = run_uniaxial(exe, MODEL, protocol, out / "csv" / f"point_{protocol}.csv")

    log(f"barrel runs (knot insertion {refine})")
    runs3d = {}
    for key in SETUPS:
        path, scene = scene_copy(key, out, refine, dt_factor)
        runs3d[key] = run_scene(exe, key, path, scene, out, log)
        write_run_csv(runs3d[key], out / "csv" / f"barrel_{key}.csv")

    results = {}
    for key in ("setup1", "setup2"):
        results[key] = elongation_rows(runs3d[key], mps[key], SETUPS[key][2])
    results["setup2_t05"] = time_rows(runs3d["setup2"], mps["setup2"], [0.5])[0]
    results["setup3"] = time_rows(runs3d["setup3"], mps["setup3"],
                                  [0.11, 0.15, 0.2, 0.3, 0.4, 0.45, 0.5, 0.7, 1.0])
    results["setup4"] = time_rows(runs3d["setup4"], mps["setup4"],
                                  [0.05, 0.2, 0.4, 0.45, 0.5, 1.0, 1.4, 1.9, 2.4])
    lam_opt = 1.05
    for key in ("setup3", "setup4"):
        run, mp = runs3d[key], mps[key]
        tot = run.part("centre", "total")
        i = int(np.argmax(tot))
        j = int(np.argmax(mp["sigma33_Pa"]))
        t_ref = 0.4
        r = [x for x in results[key] if x["t"] == t_ref][0]
        fl = float(force_length((1 + r["local"]) / lam_opt) / force_length(1 / lam_opt))
        notes = [
            f"* peak centre σ33: barrel {kpa(tot[i])} at t = {run.t[i]:.3f} s, material point "
            f"{kpa(mp['sigma33_Pa'][j])} at t = {mp['time_s'][j]:.3f} s "
            f"({pct(tot[i], mp['sigma33_Pa'][j]):+.1f} %);",
            f"* at t = {t_ref} s the centre has shortened by {-100 * r['local']:.2f} % (the thin, "
            f"clamped ends are stretched by the thick middle: σ_ff on the axis 5 mm from the clamp "
            f"{kpa(r['near_end'])} kPa; the mid-section bulges by {1e3 * r['bulge']:.2f} mm in radius); "
            f"f_λ((1 + ε_centre)/λopt) / f_λ(1/λopt) = {fl:.3f}, and the "
            f"centre's σ_CE part is {r['see'] / r['mp_see']:.3f} of the point's;",
            f"* matrix and PE parts at t = {t_ref} s: {kpa(r['matrix'])} and {kpa(r['pe'])} kPa "
            f"({100 * abs(r['matrix']) / r['total']:.2f} % and {100 * abs(r['pe']) / r['total']:.2f} % "
            f"of σ33; point: {r['mp_matrix']:.2f} Pa and {r['mp_pe']:.2f} Pa); σ_VOL / σ33 = "
            f"{r['vol'] / r['total']:.3f} (point {r['mp_vol'] / r['mp_total']:.3f});",
            f"* ΔV/V at t = {t_ref} s: {r['dv']:.3g}, virial estimate D F L0 / (6 V0) = "
            f"{r['dv_virial']:.3g}.",
        ]
        if key == "setup3":
            r5 = [x for x in results[key] if x["t"] == 0.5][0]
            notes.append(f"* decay after t1: σ33(0.5 s) / σ33(0.4 s) = {r5['total'] / r['total']:.4f}"
                         f" (barrel), {r5['mp_total'] / r['mp_total']:.4f} (point; e^(−S 0.1 s) = "
                         f"{math.exp(-5):.4f}).")
        else:
            r45 = [x for x in results[key] if x["t"] == 0.45][0]
            r24 = [x for x in results[key] if x["t"] == 2.4][0]
            notes.append(
                f"* the end starts to move at 0.4 s: in 0.05 s (0.25 mm) the centre σ33 drops by "
                f"{-pct(r45['total'], r['total']):.1f} % (point {-pct(r45['mp_total'], r['mp_total']):.1f} %),"
                f" the force by {-pct(r45['force'], r['force']):.1f} %; at 2.4 s (20 % shortening) "
                f"centre σ33 = {kpa(r24['total'])} kPa with matrix part {kpa(r24['matrix'])} kPa "
                f"(point {kpa(r24['mp_total'])} and {kpa(r24['mp_matrix'])}).")
        results[key + "_notes"] = notes

    figures = [
        figure_elongation(runs3d["setup1"], mps["setup1"], 0.0, 1, "passive elongation", out),
        figure_elongation(runs3d["setup2"], mps["setup2"], 0.5, 2, "activated elongation", out),
        figure_parts(runs3d["setup3"], mps["setup3"], 3, "isometric", [0.1, 0.4], out),
        figure_parts(runs3d["setup4"], mps["setup4"], 4, "concentric", [0.4], out),
    ]

    sens = {}
    if not args.no_sensitivity:
        log(f"sensitivity runs (knot insertion {COARSE_REFINE})")
        cache = {}
        for p, setup, values, unit in SENSITIVITY:
            runs = []
            for v in values:
                params = {} if v == DEFAULTS[p] else {p: v}
                k = (setup, tuple(sorted(params.items())))
                if k not in cache:
                    end = SENS_END[setup]
                    tag = "_sens" + "".join(f"_{a}={b:g}" for a, b in params.items())
                    path, scene = scene_copy(setup, out, COARSE_REFINE, dt_factor, end=end,
                                             times=sorted({SETUPS[setup][2] or end, end}),
                                             fields=["displacement"], params=params, tag=tag)
                    run = run_scene(exe, setup, path, scene, out, log)
                    mp = run_uniaxial(exe, MODEL, SETUPS[setup][1],
                                      out / "csv" / f"point_{SETUPS[setup][1]}{tag}.csv",
                                      params=params)
                    write_run_csv(run, out / "csv" / f"barrel_{setup}{tag}.csv")
                    cache[k] = (run, mp)
                runs.append((v,) + cache[k])
            sens[p] = (setup, unit, runs)
        figures += figure_sensitivity(sens, out)
    write_report(out, args, exe, runs3d, mps, results, sens, figures,
                 time.perf_counter() - started)
    log(f"run_study: wrote {len(figures)} figures, CSVs and report.md to {out} "
        f"in {time.perf_counter() - started:.0f} s")


if __name__ == "__main__":
    main()
