"""Running `isomuscle material uniaxial` and reading its CSV (thesis §3.5 set-ups, SPEC §2).

Only the standard library and numpy: the figures live in run_figures.py.
"""

import os
import re
import shutil
import subprocess
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[2]

CSV_COLUMNS = [
    "time_s", "stretch", "eng_strain", "eng_stress_Pa", "sigma33_Pa", "sigma_see_Pa",
    "sigma_pe_Pa", "sigma_matrix_Pa", "sigma_vol_Pa", "activation", "lambda_s", "lambda_m",
]


def has_material_command(exe):
    """True when exe is an isomuscle built with the `material` subcommand."""
    try:
        done = subprocess.run([str(exe), "material", "list", "--model", "lu2010"],
                              capture_output=True, text=True, timeout=60)
    except (OSError, subprocess.TimeoutExpired):
        return False
    return done.returncode == 0 and "sigma0" in done.stdout


def find_executable(given=None):
    """The isomuscle executable: --exe, $ISOMUSCLE_EXE, build/release/app/isomuscle, then any
    build/*/app/isomuscle (newest first); the first one that has the `material` command."""
    if given:
        exe = Path(given)
        if not (exe.is_file() and os.access(exe, os.X_OK)):
            raise SystemExit(f"run_figures: --exe {given} is not an executable file")
        if not has_material_command(exe):
            raise SystemExit(f"run_figures: {given} has no working `material` command")
        return exe
    candidates = []
    if os.environ.get("ISOMUSCLE_EXE"):
        candidates.append(Path(os.environ["ISOMUSCLE_EXE"]))
    candidates.append(REPO / "build" / "release" / "app" / "isomuscle")
    candidates += sorted((REPO / "build").glob("*/app/isomuscle"), key=lambda p: p.stat().st_mtime,
                         reverse=True)
    on_path = shutil.which("isomuscle")
    if on_path:
        candidates.append(Path(on_path))
    skipped = []
    for c in candidates:
        if c.is_file() and os.access(c, os.X_OK):
            if has_material_command(c):
                return c
            skipped.append(str(c))
    note = f" (skipped, no `material` command: {', '.join(skipped)})" if skipped else ""
    raise SystemExit("run_figures: no isomuscle executable with the `material` command found"
                     f"{note}; build it (scripts/build.sh release isomuscle) or pass --exe PATH")


class UniaxialRun:
    """One CSV of `isomuscle material uniaxial`: columns as numpy arrays (empty fields -> NaN),
    plus the wall time of the call and the solve time the executable reported."""

    def __init__(self, path, wall_s, solve_s):
        self.path = Path(path)
        self.wall_s = wall_s
        self.solve_s = solve_s
        data = np.genfromtxt(self.path, delimiter=",", names=True)
        if list(data.dtype.names) != CSV_COLUMNS:
            raise SystemExit(f"run_figures: {self.path} has columns {data.dtype.names}, "
                             f"expected {CSV_COLUMNS}")
        self.columns = {name: np.asarray(data[name], dtype=float) for name in CSV_COLUMNS}
        finite = [n for n in CSV_COLUMNS if n not in ("lambda_s", "lambda_m")]
        for n in finite:
            if not np.all(np.isfinite(self.columns[n])):
                raise SystemExit(f"run_figures: {self.path}: column {n} has empty or NaN fields")

    def __getitem__(self, name):
        return self.columns[name]

    def at_time(self, name, t):
        """Value of a column at the row nearest to time t (s)."""
        i = int(np.argmin(np.abs(self["time_s"] - t)))
        return float(self[name][i])

    def at_strain(self, name, strain, after_time=0.0):
        """Linear interpolation of a column at an engineering strain, on the rows at or after
        after_time (the pull stage of the activated protocol starts at 0.5 s)."""
        keep = self["time_s"] >= after_time - 1e-12
        x, y = self["eng_strain"][keep], self[name][keep]
        order = np.argsort(x)
        return float(np.interp(strain, x[order], y[order]))


def run_uniaxial(exe, model, protocol, out_csv, dt=1e-3, params=None):
    """Runs one protocol; params is a dict NAME -> value passed as --param NAME=VALUE."""
    cmd = [str(exe), "material", "uniaxial", "--model", model, "--protocol", protocol,
           "--dt", repr(dt), "--out", str(out_csv)]
    for name, value in (params or {}).items():
        cmd += ["--param", f"{name}={value!r}"]
    start = time.perf_counter()
    done = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.perf_counter() - start
    if done.returncode != 0:
        raise SystemExit(f"run_figures: {' '.join(cmd)} failed ({done.returncode}):\n"
                         f"{done.stderr}{done.stdout}")
    match = re.search(r" in ([0-9.eE+-]+) s;", done.stdout)
    solve = float(match.group(1)) if match else float("nan")
    return UniaxialRun(out_csv, wall, solve)


def model_parameters(exe, model):
    """Defaults of a model from `isomuscle material list --model MODEL`: name -> value."""
    done = subprocess.run([str(exe), "material", "list", "--model", model], capture_output=True,
                          text=True)
    if done.returncode != 0:
        raise SystemExit(f"run_figures: material list failed:\n{done.stderr}")
    values = {}
    for line in done.stdout.splitlines():
        m = re.match(r"^\s+(\S+)\s+default\s+(\S+)", line)
        if m:
            values[m.group(1)] = float(m.group(2))
    return values
