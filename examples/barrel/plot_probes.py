#!/usr/bin/env python3
"""Plots every probe column of a run's probes.csv against time, one small panel each, as an SVG
(standard library only: no matplotlib needed).

Usage: python3 examples/barrel/plot_probes.py RUN/probes.csv [OUT.svg]   (default RUN/probes.svg)
"""
import csv
import os
import sys

SKIP = {"time", "step", "dt", "newton_iterations"}
PANEL_W, PANEL_H, MARGIN = 360, 200, 60
UNITS = {"tip": "m", "force": "N", "volume": "m^3"}


def unit(name):
    if "." in name:
        return "Pa"
    for key, u in UNITS.items():
        if key in name:
            return u
    return ""


def panel(name, t, y, x0, y0):
    lo, hi = min(y), max(y)
    if hi == lo:
        lo, hi = lo - 1.0, hi + 1.0
    t0, t1 = min(t), max(t)
    t1 = t1 if t1 > t0 else t0 + 1.0

    def px(a, b):
        return (x0 + MARGIN + (a - t0) / (t1 - t0) * (PANEL_W - MARGIN - 10),
                y0 + PANEL_H - 30 - (b - lo) / (hi - lo) * (PANEL_H - 50))

    points = " ".join("%.1f,%.1f" % px(a, b) for a, b in zip(t, y))
    (ax, ay), (bx, by) = px(t0, lo), px(t1, hi)
    return "\n".join([
        '<rect x="%.1f" y="%.1f" width="%.1f" height="%.1f" fill="none" stroke="#999"/>'
        % (ax, by, bx - ax, ay - by),
        '<polyline points="%s" fill="none" stroke="#c33" stroke-width="1.5"/>' % points,
        '<text x="%.1f" y="%.1f" font-size="13">%s [%s]</text>' % (ax, by - 6, name, unit(name)),
        '<text x="%.1f" y="%.1f" font-size="10" text-anchor="end">%.4g</text>' % (ax - 4, by + 8, hi),
        '<text x="%.1f" y="%.1f" font-size="10" text-anchor="end">%.4g</text>' % (ax - 4, ay, lo),
        '<text x="%.1f" y="%.1f" font-size="10">t = %.4g s</text>' % (ax, ay + 14, t0),
        '<text x="%.1f" y="%.1f" font-size="10" text-anchor="end">%.4g s</text>' % (bx, ay + 14, t1),
    ])


def main():
    if len(sys.argv) < 2:
        raise SystemExit(__doc__)
    src = sys.argv[1]
    dst = sys.argv[2] if len(sys.argv) > 2 else os.path.join(os.path.dirname(src), "probes.svg")
    with open(src) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise SystemExit("%s: no rows (no converged step)" % src)
    names = [c for c in rows[0].keys() if c not in SKIP]
    t = [float(r["time"]) for r in rows]
    cols = 2
    nrows = (len(names) + cols - 1) // cols or 1
    parts = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" '
             'font-family="sans-serif">' % (cols * PANEL_W, nrows * PANEL_H),
             '<rect width="100%" height="100%" fill="white"/>']
    for i, name in enumerate(names):
        parts.append(panel(name, t, [float(r[name]) for r in rows], (i % cols) * PANEL_W,
                           (i // cols) * PANEL_H))
    parts.append("</svg>")
    with open(dst, "w") as f:
        f.write("\n".join(parts) + "\n")
    print("plot_probes: %s" % dst)


if __name__ == "__main__":
    main()
