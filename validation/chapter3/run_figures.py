#!/usr/bin/env python3
"""Chapter-3 figures of Lu (2010) from the material-point driver: thesis Figures 3.18-3.26.

    python3 validation/chapter3/run_figures.py [--exe PATH] [--out DIR] [--dt S]

Runs `isomuscle material uniaxial` for the lu2010 law (Table 3.10 defaults) in the four set-ups of
§3.5 (passive and activated elongation, isometric, isometric then concentric) and the parameter
study of §3.6 (D, sigma0, k_c, k_e, d), and writes CSVs, PNGs and report.md into the output folder
(default validation/output/chapter3, git-ignored). See README.md in this folder.
"""

import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from uniaxial_runs import REPO, find_executable, model_parameters, run_uniaxial  # noqa: E402

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

MODEL = "lu2010"
KPA = 1e-3
PULL_START = {"passive": 0.0, "activated": 0.5}  # s, start of the pull stage

# §3.6: one parameter varied, the other 13 from Table 3.10. D and sigma0 in passive elongation
# (Figure 3.25), k_c, k_e and d in activated elongation (Figure 3.26; the thesis omits k_e).
SENSITIVITY = [
    ("D", "passive", [1e-9, 1e-8, 1e-7, 1e-6], "m²/N"),
    ("sigma0", "passive", [1.6e5, 4.0e5, 7.0e5, 1.0e6], "Pa"),
    ("k_c", "activated", [4.0, 5.0, 5.88], ""),
    ("k_e", "activated", [3.14, 5.0, 7.56], ""),
    ("d", "activated", [1.1, 1.5, 1.8], ""),
]
STRAINS = [0.05, 0.10, 0.15, 0.20, 0.30]


def force_length(r):
    """Thesis 3.28 on r = lambda_f / lambda_opt."""
    r = np.asarray(r, dtype=float)
    return np.select([r < 0.4, r < 0.6, r < 1.4, r < 1.6],
                     [0.0 * r, 9 * (r - 0.4) ** 2, 1 - 4 * (1 - r) ** 2, 9 * (r - 1.6) ** 2], 0.0)


def pull_stage(run, protocol):
    keep = run["time_s"] >= PULL_START[protocol] - 1e-12
    return run["eng_strain"][keep], run["eng_stress_Pa"][keep]


def zoom_to_strain(ax, curves, limit=0.20):
    """Shows strains up to `limit` with the y range of the curves there (the exponential matrix
    makes 20-30 % strain dwarf the rest)."""
    top = max(np.max(y[x <= limit + 1e-12]) for x, y in curves)
    bottom = min(0.0, min(np.min(y[x <= limit + 1e-12]) for x, y in curves))
    margin = 0.04 * (top - bottom)
    ax.set_xlim(-0.5, 100 * limit + 0.5)
    ax.set_ylim((bottom - margin) * KPA, (top + margin) * KPA)


def strain_labels(ax, title):
    ax.set_xlabel("engineering strain (%)")
    ax.set_ylabel("engineering stress (kPa)")
    ax.set_title(title, fontsize=10)
    ax.grid(alpha=0.3)


def figure_elongation(runs, out):
    """Figures 3.18 and 3.19: engineering stress against strain (full range and up to 20 %)."""
    names = []
    for protocol, number, title in [("passive", "18", "passive elongation"),
                                    ("activated", "19", "activated elongation")]:
        fig, axes = plt.subplots(1, 2, figsize=(10, 4))
        curves = [pull_stage(runs[protocol], protocol)]
        if protocol == "activated":
            curves.append(pull_stage(runs["passive"], "passive"))
        for ax, zoom in zip(axes, (False, True)):
            ax.plot(100 * curves[0][0], curves[0][1] * KPA, "k-", label=f"{MODEL}, {title}")
            if protocol == "activated":
                ax.plot(100 * curves[1][0], curves[1][1] * KPA, "k--", lw=1,
                        label=f"{MODEL}, passive (for reference)")
                ax.axvline(15, color="0.6", lw=0.8, ls=":")
            if zoom:
                zoom_to_strain(ax, curves)
            strain_labels(ax, f"Fig. 3.{number}: {title}" + (", up to 20 %" if zoom else ""))
            ax.legend(loc="upper left", fontsize=8)
        name = f"fig3_{number}_{protocol}_elongation.png"
        fig.tight_layout()
        fig.savefig(out / name, dpi=150)
        plt.close(fig)
        names.append(name)
    return names


def plot_parts(ax, run):
    t = run["time_s"]
    ax.plot(t, run["sigma33_Pa"] * KPA, "k-", lw=2, label="σ33")
    ax.plot(t, run["sigma_see_Pa"] * KPA, "C0-", label="σ_CE33 (= σ_SEE part)")
    ax.plot(t, run["sigma_vol_Pa"] * KPA, "C1--", label="σ_VOL33")
    ax.plot(t, run["sigma_matrix_Pa"] * KPA, "C2-.", label="σ_I33 (matrix)")
    ax.plot(t, run["sigma_pe_Pa"] * KPA, "C3:", label="σ_PE33")
    ax.set_xlabel("time (s)")
    ax.set_ylabel("Cauchy stress, zz (kPa)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)


def figure_isometric(runs, out):
    """Figures 3.20 (activation) and 3.21 (the parts of 3.44 against time)."""
    run = runs["isometric"]
    fig, ax = plt.subplots(figsize=(5.5, 3.6))
    ax.plot(run["time_s"], run["activation"], "k-")
    ax.set_xlabel("time (s)")
    ax.set_ylabel("activation f_t")
    ax.set_title("Fig. 3.20: activation (n1 = 0, n2 = 1, t0 = 0.1 s, t1 = 0.4 s)", fontsize=10)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(out / "fig3_20_activation.png", dpi=150)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(6, 4.4))
    plot_parts(ax, run)
    ax.set_title("Fig. 3.21: isometric contraction (3.44)", fontsize=10)
    fig.tight_layout()
    fig.savefig(out / "fig3_21_isometric_parts.png", dpi=150)
    plt.close(fig)
    return ["fig3_20_activation.png", "fig3_21_isometric_parts.png"]


def figure_concentric(runs, params, out):
    """Figures 3.22 (parts against time) and 3.23/3.24 (input f_lambda, output CE stress)."""
    run = runs["concentric"]
    fig, ax = plt.subplots(figsize=(6, 4.4))
    plot_parts(ax, run)
    ax.axvline(0.4, color="0.6", lw=0.8, ls=":")
    ax.set_title("Fig. 3.22: isometric (0-0.4 s) then concentric at 5 mm/s", fontsize=10)
    fig.tight_layout()
    fig.savefig(out / "fig3_22_concentric_parts.png", dpi=150)
    plt.close(fig)

    # The CE stress from the SEE stretch, sigma_CE = sigma_SEE = beta[exp(alpha(lambda_s-1)) - 1]
    # (3.23-3.24), normalised by sigma0, against the fibre stretch in the concentric stage.
    lam_opt, alpha, beta, sigma0 = (params[k] for k in ("lambda_opt", "alpha", "beta", "sigma0"))
    keep = run["time_s"] >= 0.5  # after the 0.1 s velocity transient at the stage switch
    lam = run["stretch"][keep]
    ce = beta * (np.exp(alpha * (run["lambda_s"][keep] - 1.0)) - 1.0) / sigma0
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
    grid = np.linspace(0.3, 1.8, 600)
    ax1.plot(grid, force_length(grid / lam_opt), "k-")
    ax1.set_xlabel("fibre stretch λ̄f")
    ax1.set_ylabel("f_λ")
    ax1.set_title(f"Fig. 3.23: input force-stretch curve (3.28), λopt = {lam_opt:g}", fontsize=10)
    ax1.grid(alpha=0.3)
    ax2.plot(lam, ce, "k-", label="σ_CE/σ0 from the run")
    fv = ce[0] / force_length(lam[0] / lam_opt)
    ax2.plot(lam, fv * force_length(lam / lam_opt), "C1--",
             label=f"f_λ(λ) × {fv:.3f} (f_t f_v at t = 0.5 s)")
    ax2.set_xlabel("axial stretch λ (= λ̄f to 1e-4)")
    ax2.set_ylabel("normalised CE stress σ_CE/σ0")
    ax2.set_title("Fig. 3.24: CE stress in the concentric stage", fontsize=10)
    ax2.grid(alpha=0.3)
    ax2.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / "fig3_23_24_force_stretch.png", dpi=150)
    plt.close(fig)
    return ["fig3_22_concentric_parts.png", "fig3_23_24_force_stretch.png"]


def figure_sensitivity(sens, out):
    """Figures 3.25 (D, sigma0; passive) and 3.26 (k_c, k_e, d; activated); bottom row up to 20 %."""
    names = []
    groups = [("fig3_25_sensitivity_D_sigma0.png", ["D", "sigma0"], "Fig. 3.25, passive"),
              ("fig3_26_sensitivity_kc_ke_d.png", ["k_c", "k_e", "d"], "Fig. 3.26, activated")]
    for name, params, title in groups:
        fig, axes = plt.subplots(2, len(params), figsize=(5 * len(params), 7.5))
        for col, p in enumerate(params):
            protocol, unit, runs = sens[p]
            curves = [pull_stage(run, protocol) for _, run in runs]
            for row in range(2):
                ax = axes[row][col]
                for (value, _), (x, y) in zip(runs, curves):
                    ax.plot(100 * x, y * KPA, label=f"{p} = {value:g} {unit}".strip())
                if row == 1:
                    zoom_to_strain(ax, curves)
                strain_labels(ax, f"{title}: {p}" + (", up to 20 %" if row else ""))
                ax.legend(fontsize=8, loc="upper left")
        fig.tight_layout()
        fig.savefig(out / name, dpi=150)
        plt.close(fig)
        names.append(name)
    return names


def time_gap(coarse, fine):
    """max |sigma33(dt) - sigma33(dt/10)| over the coarse times, relative to the fine peak, and the
    time where it occurs."""
    tc, tf = coarse["time_s"], fine["time_s"]
    ff = np.interp(tc, tf, fine["sigma33_Pa"])
    gap = np.abs(coarse["sigma33_Pa"] - ff)
    i = int(np.argmax(gap))
    return gap[i] / np.max(np.abs(fine["sigma33_Pa"])), tc[i]


def write_report(out, dt, runs, fine, sens, figures, exe):
    p, a, iso, con = (runs[k] for k in ("passive", "activated", "isometric", "concentric"))
    lines = [
        "# Chapter 3 (Lu 2010, §3.5–3.6): material-point reproduction",
        "",
        f"Law `{MODEL}` with the Table 3.10 defaults; one material point, fibres along the load "
        "axis, lateral faces traction-free (F = diag(a, b, λ), S11 = S22 = 0 solved each step); "
        f"specimen 5 cm, 5 mm/s; dt = {dt:g} s. Executable: `{exe}`.",
        "",
        "## Figures",
        "",
    ]
    lines += [f"* `{f}`" for f in figures]
    lines += ["", "## Key numbers", "", "Engineering stress (first Piola P33), kPa:", "",
              "| strain | passive | activated |", "|---|---|---|"]
    for s in STRAINS:
        lines.append(f"| {100 * s:.0f} % | {p.at_strain('eng_stress_Pa', s) * KPA:.2f} | "
                     f"{a.at_strain('eng_stress_Pa', s, 0.5) * KPA:.2f} |")
    lines.append(f"| 0 % (end of 0.5 s isometric activation) | – | "
                 f"{a.at_time('eng_stress_Pa', 0.5) * KPA:.2f} |")
    i_peak = int(np.argmax(iso["sigma33_Pa"]))
    lines += [
        "",
        "Isometric contraction (Figure 3.21):",
        "",
        f"* peak σ33 = {iso['sigma33_Pa'][i_peak] * KPA:.2f} kPa at t = {iso['time_s'][i_peak]:.3f} s "
        f"(σ0 f_λ(1/λopt) = {7e5 * force_length(1 / 1.05) * KPA:.2f} kPa);",
        f"* at the peak: σ_CE33 = {iso['sigma_see_Pa'][i_peak] * KPA:.2f} kPa, σ_VOL33 = "
        f"{iso['sigma_vol_Pa'][i_peak] * KPA:.2f} kPa, σ_I33 = {iso['sigma_matrix_Pa'][i_peak]:.3f} Pa, "
        f"σ_PE33 = {iso['sigma_pe_Pa'][i_peak]:.3g} Pa;",
        f"* max |σ_I33| = {np.max(np.abs(iso['sigma_matrix_Pa'])):.3f} Pa, max σ_PE33 = "
        f"{np.max(iso['sigma_pe_Pa']):.3g} Pa; σ33 at 1 s = {iso.at_time('sigma33_Pa', 1.0):.3g} Pa.",
        "",
        "Isometric then concentric (Figure 3.22):",
        "",
    ]
    for t in (0.4, 0.5, 1.4, 2.4):
        lines.append(f"* t = {t} s: σ33 = {con.at_time('sigma33_Pa', t) * KPA:.2f} kPa, σ_CE33 = "
                     f"{con.at_time('sigma_see_Pa', t) * KPA:.2f} kPa, σ_I33 = "
                     f"{con.at_time('sigma_matrix_Pa', t) * KPA:.3f} kPa, stretch "
                     f"{con.at_time('stretch', t):.3f}")
    lines += ["", "Time-step convergence (σ33, dt against dt/10, relative to the peak):", ""]
    for k in ("isometric", "concentric"):
        g, t = time_gap(runs[k], fine[k])
        lines.append(f"* {k}: {100 * g:.3f} % at t = {t:.3f} s (the activation front; first order "
                     "in dt, see tests/materials/test_uniaxial_driver.cpp)")
    lines += ["", "Run time per protocol (solve as reported by the executable, and wall time of "
              "the call):", ""]
    for k, r in runs.items():
        lines.append(f"* {k}: {len(r['time_s']) - 1} steps, solve {r.solve_s * 1e3:.1f} ms, "
                     f"wall {r.wall_s * 1e3:.0f} ms")
    lines += ["", "## Sensitivity (§3.6): engineering stress at 20 % strain, kPa", ""]
    for name, (protocol, unit, rs) in sens.items():
        start = PULL_START[protocol]
        vals = [(v, r.at_strain("eng_stress_Pa", 0.2, start) * KPA) for v, r in rs]
        cells = ", ".join(f"{v:g}: {s:.2f}" for v, s in vals)
        lo, hi = vals[0][1], vals[-1][1]
        lines.append(f"* {name} ({protocol}; {unit or 'dimensionless'}): {cells}; "
                     f"(last - first)/last = {100 * (hi - lo) / hi:+.1f} %")
    lines += thesis_comparison(sens)
    (out / "report.md").write_text("\n".join(lines) + "\n", encoding="utf-8")


def thesis_comparison(sens):
    """The §3.6 statements of the thesis checked on these runs (at 20 % strain)."""
    at20 = {name: [r.at_strain("eng_stress_Pa", 0.2, PULL_START[protocol]) for _, r in rs]
            for name, (protocol, _, rs) in sens.items()}
    spread = {name: (max(v) - min(v)) / max(v) for name, v in at20.items()}

    def trend(name):
        v = at20[name]
        return "increases" if v[-1] > v[0] else "decreases"

    s0 = at20["sigma0"]
    yes = {True: "yes", False: "**no**"}
    return [
        "", "## Against the statements of §3.6", "",
        "| thesis | here | agrees |", "|---|---|---|",
        f"| stress increases with σ0, k_c, d and decreases with D | σ0 {trend('sigma0')}, "
        f"k_c {trend('k_c')}, d {trend('d')}, D {trend('D')} | "
        f"{yes[(trend('sigma0'), trend('k_c'), trend('d'), trend('D')) == ('increases',) * 3 + ('decreases',)]} |",
        f"| σ0 0.16 → 1.0 MPa: relative difference up to 60.7 % at strain 0.2 | "
        f"{100 * (s0[-1] - s0[0]) / s0[-1]:.1f} % of the largest ({100 * (s0[-1] - s0[0]) / s0[0]:.0f} % "
        "of the smallest) | same order |",
        f"| k_c has little influence | spread {100 * spread['k_c']:.1f} % | "
        f"{yes[spread['k_c'] < 0.05]} |",
        f"| k_e acts like k_c | spread {100 * spread['k_e']:.1f} % | {yes[spread['k_e'] < 0.05]} |",
        f"| d has a bigger influence than k_c and k_e | spread {100 * spread['d']:.1f} % | "
        f"{yes[spread['d'] > max(spread['k_c'], spread['k_e'])]} |",
        f"| D has a considerable influence | spread {100 * spread['D']:.1f} % over 1e-9…1e-6 "
        f"({100 * (at20['D'][0] - at20['D'][2]) / at20['D'][0]:.1f} % over 1e-9…1e-7) | weaker: a "
        "homogeneous point has no constraint that turns compressibility into stress (README.md) |",
    ]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--exe", help="isomuscle executable (default: search build/)")
    parser.add_argument("--out", default=str(REPO / "validation" / "output" / "chapter3"),
                        help="output folder (default validation/output/chapter3)")
    parser.add_argument("--dt", type=float, default=1e-3, help="time step, s (default 1e-3)")
    args = parser.parse_args()
    exe = find_executable(args.exe)
    out = Path(args.out)
    (out / "csv").mkdir(parents=True, exist_ok=True)
    params = model_parameters(exe, MODEL)

    runs = {k: run_uniaxial(exe, MODEL, k, out / "csv" / f"{MODEL}_{k}.csv", args.dt)
            for k in ("passive", "activated", "isometric", "concentric")}
    fine = {k: run_uniaxial(exe, MODEL, k, out / "csv" / f"{MODEL}_{k}_fine.csv", args.dt / 10)
            for k in ("isometric", "concentric")}
    sens = {}
    for name, protocol, values, unit in SENSITIVITY:
        rs = [(v, run_uniaxial(exe, MODEL, protocol, out / "csv" / f"{MODEL}_{protocol}_{name}={v:g}.csv",
                               args.dt, {name: v})) for v in values]
        sens[name] = (protocol, unit, rs)

    figures = figure_elongation(runs, out)
    figures += figure_isometric(runs, out)
    figures += figure_concentric(runs, params, out)
    figures += figure_sensitivity(sens, out)
    write_report(out, args.dt, runs, fine, sens, figures, exe)
    print(f"run_figures: wrote {len(figures)} figures, CSVs and report.md to {out}")


if __name__ == "__main__":
    main()
