#!/usr/bin/env python3
"""Figure of the imaginary-time benchmark (issue 26): relative <H> error against FFTs per
method for each problem (top row, from the `# sweep` lines of fsym_itp_bench, as
scripts/itp.sh saves them), the same for the norm-decay energy (bottom row, `# sweep-norm`
lines; for Gross-Pitaevskii against the chemical potential), and the Gross-Pitaevskii
ground-state density (from fsym_itp_run's HDF5 file).

usage: plot_itp.py BENCH.txt GP.h5 OUT.png
"""
import re
import sys

import h5py
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

SWEEP = r"# %s problem=(\S+) method=(\S+) tau=\s*(\S+) rel_err=\s*(\S+) ffts=(\d+)"


def read_sweeps(path, kind="sweep"):
    """{problem: {method: [(tau, rel_err, ffts), ...]}} from the `# <kind>` lines."""
    pattern = re.compile(SWEEP % kind)
    data = {}
    with open(path, encoding="utf-8") as f:
        for line in f:
            m = pattern.match(line)
            if m:
                prob, meth, tau, err, nfft = m.groups()
                data.setdefault(prob, {}).setdefault(meth, []).append(
                    (float(tau), float(err), int(nfft)))
    return data


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    bench, gp, out = sys.argv[1:]
    rows = [(read_sweeps(bench), "relative error of <H>"),
            (read_sweeps(bench, "sweep-norm"), "relative error of the norm-decay energy")]
    probs = [p for p in ("ho3d", "pt1d", "gp3d") if p in rows[0][0]]
    if not rows[1][0]:
        rows = rows[:1]  # output of an older benchmark: no norm sweeps
    fig, grid = plt.subplots(len(rows), len(probs) + 1,
                             figsize=(4.2 * (len(probs) + 1), 3.8 * len(rows)), squeeze=False)
    titles = {"ho3d": "3-D oscillator (32$^3$)", "pt1d": "Pöschl–Teller $\\lambda=3$ (256)",
              "gp3d": "3-D anisotropic GP (36$^3$)"}
    colours = plt.get_cmap("tab20").colors
    for axes, (data, ylabel) in zip(grid, rows):
        for ax, prob in zip(axes, probs):
            methods = list(rows[0][0][prob])  # the same colour for a method in both rows
            for meth, pts in data.get(prob, {}).items():
                i = methods.index(meth) if meth in methods else len(methods)
                pts = sorted(pts, key=lambda p: p[2])
                err = np.array([p[1] for p in pts])
                nfft = np.array([p[2] for p in pts])
                style = "s--" if meth in ("CN", "Strang", "TVT") else "o-"
                ax.loglog(nfft, np.maximum(err, 1e-16), style, ms=3, lw=1,
                          color=colours[(2 * i) % 20 + (i // 10) % 2], label=meth)
            for tol in (1e-8, 1e-10, 1e-12):
                ax.axhline(tol, color="k", lw=0.5, ls=":")
            ax.set_xlabel("FFTs (total, t = 16)")
            ax.set_ylabel(ylabel, fontsize=9)
            ax.set_title(titles.get(prob, prob), fontsize=10)
        axes[0].legend(fontsize=6, ncol=2)
    for ax in grid[1:, -1]:
        ax.axis("off")
    axes = grid[0]
    with h5py.File(gp, "r") as f:
        rho = f["fields/density/value"][()]
        x = f["grid/x1"][()]
        n = len(x)
        rho = rho.reshape(n, n, n)  # h5py: (n3, n2, n1)
        ax = axes[-1]
        im = ax.imshow(rho[n // 2, :, :], origin="lower", extent=[x[0], x[-1], x[0], x[-1]])
        ax.set_xlabel("x (L)")
        ax.set_ylabel("y (L)")
        ax.set_title("GP ground-state density, z = 0 (method %s)" % f["parameters"].attrs["method"].decode()
                     if isinstance(f["parameters"].attrs["method"], bytes)
                     else "GP ground-state density, z = 0", fontsize=9)
        fig.colorbar(im, ax=ax, shrink=0.8)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print("wrote", out)


if __name__ == "__main__":
    main()
