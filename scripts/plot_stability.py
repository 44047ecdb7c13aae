#!/usr/bin/env python3
"""Plots of the stability study (doc/stability.md) from the HDF5 file of fsym-stability.

usage: plot_stability.py [FILE.h5] [OUTDIR]   (defaults out/stability.h5, doc/figures)
"""
import sys
import os

import h5py
import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SHOW = ["T2", "FR", "A", "C", "BM", "RKN"]
MARKERS = ["o", "s", "^", "v", "D", "P", "X", "*"]  # one per method shown, with its colour


def names_of(attr):
    if isinstance(attr, bytes):
        attr = attr.decode()
    return [s.strip() for s in str(attr).split(",")]


def finish(fig, ax, out, name, xlabel, ylabel, title):
    """Label, add the legend, save as OUT/NAME and close."""
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, name), dpi=120)
    fig.savefig(os.path.join(out, os.path.splitext(name)[0] + ".pdf"),
                metadata={"CreationDate": None})
    plt.close(fig)


def main():
    src = sys.argv[1] if len(sys.argv) > 1 else "out/stability.h5"
    out = sys.argv[2] if len(sys.argv) > 2 else "doc/figures"
    os.makedirs(out, exist_ok=True)
    with h5py.File(src, "r") as f:
        methods = names_of(f.attrs["methods"])
        idx = {m: i for i, m in enumerate(methods)}

        # 1. oscillator traces (Fortran (401, nm) arrives as (nm, 401))
        x = f["oscillator/x"][()]
        tr = f["oscillator/trace"][()]
        xs = f["oscillator/xstar"][()]
        fig, ax = plt.subplots(figsize=(7, 4.5))
        for m in SHOW:
            line, = ax.plot(x, tr[idx[m]], label=f"{m} (x* = {xs[idx[m]]:.3f})")
            ax.axvline(xs[idx[m]], color=line.get_color(), ls=":", lw=0.8)
        ax.axhline(2, color="k", lw=0.8)
        ax.axhline(-2, color="k", lw=0.8)
        ax.set_ylim(-4, 4)
        finish(fig, ax, out, "stability_trace.png", "x = h omega",
               "trace of the oscillator step map",
               "Stable while |trace| < 2 (dotted: x*)")

        # 2. chain spectral radius
        h = f["chain/h"][()]
        rho = f["chain/rho"][()]
        wmax = f["chain/omega"][()][-1]
        cnames = names_of(f["chain"].attrs["methods"])
        fig, ax = plt.subplots(figsize=(7, 4.5))
        for i, m in enumerate(cnames):
            line, = ax.semilogy(h * wmax, np.maximum(rho[i] - 1.0, 1e-16), label=m)
            ax.axvline(xs[idx[m]], color=line.get_color(), ls=":", lw=0.8)
        finish(fig, ax, out, "stability_chain.png", "h omega_max",
               "spectral radius - 1 (dgeev; floor 1e-16)",
               "Stiff chain: instability sets in at h = x*/omega_max (dotted)")

        # 3. FPU energy exchange at f = 0.5 (samples (nm, nsamp, 2 + m))
        smp = f["fpu/samples_half"][()]
        ns = f["fpu/nsamples_half"][()]
        pick = ["T2", "A", "C", "RKN"]
        fig, axes = plt.subplots(2, 2, figsize=(9, 6), sharex=True)
        for ax, m in zip(axes.flat, pick):
            s = smp[idx[m], : ns[idx[m]], :]
            for j in range(2, s.shape[1]):
                ax.plot(s[:, 0], s[:, j], lw=0.9, label=f"I_{j - 1}")
            ax.plot(s[:, 0], s[:, 2:].sum(axis=1), "k", lw=0.9, label="I")
            ax.set_title(f"{m}, h = 0.5 x*/omega", fontsize=9)
            ax.legend(fontsize=7)
            ax.set_ylabel("oscillatory energy (I_j / I_1(0))")
        for ax in axes[1]:
            ax.set_xlabel("t")
        fig.suptitle("FPU (omega = 50): oscillatory energies of the stiff springs")
        fig.tight_layout()
        fig.savefig(os.path.join(out, "stability_fpu_exchange.png"), dpi=120)
        fig.savefig(os.path.join(out, "stability_fpu_exchange.pdf"),
                    metadata={"CreationDate": None})
        plt.close(fig)

        # 4. FPU scan
        sx = f["fpu/scan_x"][()]
        sdh = f["fpu/scan_dh"][()]
        fig, ax = plt.subplots(figsize=(7, 4.5))
        for m in SHOW:
            y = sdh[idx[m]]
            ok = y >= 0
            ax.semilogy(sx[ok], np.minimum(y[ok], 1e3), label=m)
        for k in (1,):
            ax.axvline(k * np.pi, color="k", ls=":", lw=0.8)
        finish(fig, ax, out, "stability_fpu_scan.png", "h omega",
               "max |H - H0| over T = 50",
               "FPU energy error against the step (dotted: h omega = pi)")

        # 5. eccentric orbits: steps per period needed
        ecc = f["kepler/e"][()]
        need = f["kepler/needed"][()]
        nmax = int(f["kepler"].attrs["nmax"])
        fig, ax = plt.subplots(figsize=(7, 4.5))
        for m in SHOW:
            n = need[idx[m]].astype(float)
            n[n <= 0] = np.nan
            k = SHOW.index(m) if m in SHOW else 0
            ax.loglog(1.0 - ecc, n, "-", marker=MARKERS[k % len(MARKERS)],
                      ms=9 - k, label=m)
        ax.axhline(nmax, color="k", ls=":", lw=0.8)
        ax.invert_xaxis()
        finish(fig, ax, out, "stability_eccentric.png", "1 - e (pericentre distance)",
               "steps per period for max |dE/E| < 1e-6",
               f"Extreme eccentricity (dotted: search limit {nmax})")

        # 6. long run
        de = f["long/de"][()]
        done = f["long/periods_done"][()]
        lnames = names_of(f["long"].attrs["methods"])
        fig, ax = plt.subplots(figsize=(7, 4.5))
        for i, m in enumerate(lnames):
            n = int(done[i])
            p = np.arange(1, n + 1)
            ax.loglog(p, np.maximum(np.abs(de[i, :n]), 1e-17), lw=0.8, label=m)
        finish(fig, ax, out, "stability_long.png", "period",
               "|dE/E| at the end of the period",
               "e = 0.9 at P/1000: bounded (splitting) vs drifting (RKN)")


if __name__ == "__main__":
    main()
