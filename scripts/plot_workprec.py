#!/usr/bin/env python3
"""Plot the work-precision table written by fsym-workprec.

Usage: plot_workprec.py doc/work-precision.csv doc/figures/work-precision.png

Four panels: max relative energy error against run time and against effective evaluations
(F + gradient cost x G, the cost read from doc/work-precision.md) on both orbits; a second
figure (suffix -precession) shows the LRL precession after 10 periods of the e = 0.9 orbit
against run time. Forward methods solid, non-forward dashed, RKN dotted.
"""
import csv
import re
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def load(path):
    rows = []
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            rows.append(r)
    return rows


def gradient_cost(md_path):
    try:
        text = Path(md_path).read_text()
    except OSError:
        return 1.0
    m = re.search(r"force evaluation \(Kepler model, one body\): ([0-9.]+)", text)
    return float(m.group(1)) if m else 1.0


def series(rows, orbit, method, xkey, ykey, gcost):
    pts = []
    for r in rows:
        if int(r["orbit"]) != orbit or r["method"] != method:
            continue
        t = float(r["time_s"])
        y = abs(float(r[ykey]))
        if not (t > 0 and y > 0):
            continue
        if xkey == "time":
            x = t
        else:
            x = float(r["force_evals"]) + gcost * float(r["grad_evals"])
        pts.append((x, y))
    return zip(*pts) if pts else ((), ())


def style(method, forward):
    if method == "RKN":
        return ":"
    return "-" if forward else "--"


def main():
    csv_path = sys.argv[1] if len(sys.argv) > 1 else "doc/work-precision.csv"
    png_path = sys.argv[2] if len(sys.argv) > 2 else "doc/figures/work-precision.png"
    rows = load(csv_path)
    gcost = gradient_cost(Path(csv_path).with_suffix(".md"))
    methods = []
    fwd = {}
    for r in rows:
        if r["method"] not in fwd:
            methods.append(r["method"])
            fwd[r["method"]] = r["forward"].strip().upper() == "T"
    cmap = plt.get_cmap("tab20")
    colours = {m: cmap(i % 20) for i, m in enumerate(methods)}
    titles = {1: "e = 0.9, 10 periods", 2: "e = 0.6, 200 periods"}

    fig, axes = plt.subplots(2, 2, figsize=(13, 10))
    for col, orbit in enumerate((1, 2)):
        for row, xkey in enumerate(("time", "evals")):
            ax = axes[row][col]
            for m in methods:
                x, y = series(rows, orbit, m, xkey, "max_rel_energy_error", gcost)
                if x:
                    ax.loglog(x, y, style(m, fwd[m]), marker=".", color=colours[m],
                              label=m, lw=1)
            ax.set_title(titles[orbit])
            ax.set_xlabel("run time (s)" if xkey == "time"
                          else f"effective evaluations F + {gcost:.2f} G")
            ax.set_ylabel("max |dE/E|")
            ax.grid(True, which="both", alpha=0.3)
    axes[0][1].legend(fontsize=7, ncol=2, loc="lower left")
    fig.suptitle("Work-precision (solid: forward, dashed: non-forward, dotted: RKN)")
    fig.tight_layout()
    Path(png_path).parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(png_path, dpi=110)

    fig, ax = plt.subplots(figsize=(8, 6))
    for m in methods:
        x, y = series(rows, 1, m, "time", "precession_rad", gcost)
        if x:
            ax.loglog(x, y, style(m, fwd[m]), marker=".", color=colours[m], label=m, lw=1)
    ax.set_xlabel("run time (s)")
    ax.set_ylabel("|LRL precession| after 10 periods (rad)")
    ax.set_title("e = 0.9 orbit")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(str(png_path).replace(".png", "-precession.png"), dpi=110)


if __name__ == "__main__":
    main()
