#!/usr/bin/env python3
"""Turn the study's HDF5 scenes (written by `fsym-study`) into the paper's figures.

Usage: plot_figures.py [OUT_DIR [FIG_DIR]]   (defaults: out, doc/figures)

Coefficient scenes (engNf) give two PNGs: engNf.png (energy error coefficient against t/P)
and angNf.png (precession error coefficient against t/P). Force-point scenes (backX) give
backX.png: the force-evaluation points over the dashed exact orbit; forward methods as
circles, non-forward methods as squares (first solid, then hollow), RKN as plus signs.
acoef, scanm2 and scangfr5 give the GFR5 coefficients and the two parameter scans.
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import h5py  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

COEF_SCENES = ["eng3f", "eng4f", "eng4f2", "eng5f", "eng6f"]
POINT_SCENES = ["backfr", "back3f", "back4f", "back4f2", "back5f", "back6f"]


def text(x):
    return x.decode() if isinstance(x, bytes) else str(x)


def methods(f):
    return text(f.attrs["methods"]).split(",")


def coefficient_figures(f, scene, figdir):
    """engNf.png and angNf.png from one coefficient scene."""
    for kind, prefix, ylabel in [
        ("energy_coefficient", "eng", r"$(E(t)-E_0)/(E_0\,\epsilon^4)$"),
        ("precession_coefficient", "ang", r"LRL rotation angle $/\,\epsilon^4$"),
    ]:
        fig, axs = plt.subplots(1, 2, figsize=(11, 4.6), gridspec_kw=dict(width_ratios=[3, 2]))
        period = float(f.attrs["period"])
        for m in methods(f):
            obs = f["observables"][m][kind]
            t = obs["time"][()] / period
            for ax in axs:
                ax.plot(t, obs["value"][()], lw=1.2, label=m)
        for ax in axs:
            ax.axhline(0.0, color="0.6", lw=0.6)
            ax.set_xlabel("t / P")
        axs[1].set_xlim(0.49, 0.51)
        axs[1].set_title("zoom: first pericentre passage")
        axs[0].set_ylabel(ylabel)
        n = round(period / float(f.attrs["eps"]))
        axs[0].set_title(f"{prefix}{scene[3:]}: e = 0.9 Kepler orbit, " + r"$\epsilon$" + f" = P/{n}")
        axs[0].legend(frameon=False)
        fig.tight_layout()
        fig.savefig(os.path.join(figdir, prefix + scene[3:] + ".png"), dpi=110)
        plt.close(fig)


def point_figure(f, scene, figdir):
    """backX.png: force-evaluation points over the exact orbit."""
    fig, ax = plt.subplots(figsize=(6.4, 6.4))
    qe = f["exact/position/value"][()][:, 0, :]
    ax.plot(qe[:, 0], qe[:, 1], "k--", lw=1.0, label="exact orbit")
    nonfwd = 0
    pts = [qe[np.argmin(np.hypot(qe[:, 0], qe[:, 1]))][None, :]]
    colours = ["tab:red", "tab:blue", "tab:green", "tab:purple"]
    for i, m in enumerate(methods(f)):
        g = f["force_evaluations"][m]
        q = g["position"][()][:, 0, :]
        kind = g["kind"][()]
        col = colours[i % len(colours)]
        if text(g.attrs["method"]) == "RKN":
            style = dict(marker="+", s=120, color=col, linewidths=1.6)
        elif int(g.attrs["forward"]) == 1:
            style = dict(marker="o", s=70, facecolors="none", edgecolors=col, linewidths=1.4)
        else:
            face = col if nonfwd == 0 else "none"
            style = dict(marker="s", s=60, facecolors=face, edgecolors=col, linewidths=1.4)
            nonfwd += 1
        sel = kind != 2  # gradients sit where a force was evaluated: mark them separately
        ax.scatter(q[sel, 0], q[sel, 1], label=f"{m} force points", zorder=3, **style)
        if np.any(kind == 2):
            ax.scatter(q[kind == 2, 0], q[kind == 2, 1], marker="x", s=25, color=col, zorder=4,
                       label=f"{m} gradient points")
        p = f["particles"][m]["position/value"][()][:, 0, :]
        pts += [q, p]
        ax.plot(p[:, 0], p[:, 1], ":", color=col, lw=0.8)
        ax.scatter(p[:, 0], p[:, 1], marker="o", s=22, color="k", zorder=5)
    if scene == "backfr" and "substeps" in f:
        sub = f["substeps/FR/position/value"][()][:, 0, :]
        fq = f["force_evaluations/FR/position"][()][:, 0, :]
        path = []
        for k in range(len(fq)):
            path += [sub[k], fq[k]]
        path.append(sub[-1])
        path = np.array(path)
        ax.plot(path[:, 0], path[:, 1], "-", color="tab:red", lw=0.8)
        labels = ["1", "1a", "1b", "2", "2a", "2b", "3"]
        for k, lab in enumerate(labels[: len(sub)]):
            ax.annotate(lab, sub[k], textcoords="offset points", xytext=(6, 4))
        for k in range(min(3, len(fq))):
            ax.annotate(f"F{k + 1}", fq[k], textcoords="offset points", xytext=(6, -10),
                        color="tab:red", fontsize=8)
        pts.append(sub)
    pts = np.vstack(pts)
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    half = 0.6 * max(hi - lo) + 0.02
    mid = 0.5 * (lo + hi)
    ax.set_xlim(mid[0] - half, mid[0] + half)
    ax.set_ylim(mid[1] - half, mid[1] + half)
    ax.set_aspect("equal")
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    n = round(float(f.attrs["period"]) / float(f.attrs["eps"]))
    ax.set_title(f"{scene}: two steps to the pericentre, " + r"$\epsilon$" + f" = P/{n}")
    ax.legend(frameon=False, fontsize=8, loc="best")
    fig.tight_layout()
    fig.savefig(os.path.join(figdir, scene + ".png"), dpi=110)
    plt.close(fig)


def acoef_figure(f, figdir):
    fig, ax = plt.subplots(figsize=(6.4, 4.5))
    al = f["gfr5/alpha"][()]
    for name in ["a0", "a1", "a2"]:
        ax.plot(al, f["gfr5"][name][()], label=name)
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.axvline(float(f["gfr5"].attrs["alpha_least_negative_a0"]), color="0.6", ls=":", lw=0.8)
    ax.set_xlabel(r"$\alpha$")
    ax.set_ylabel("GFR5 substep fraction")
    ax.set_title("acoef: coefficients of GFR5 against alpha")
    ax.legend(frameon=False)
    fig.tight_layout()
    fig.savefig(os.path.join(figdir, "acoef.png"), dpi=110)
    plt.close(fig)


def scan_figure(f, scene, figdir):
    s = f["scan"]
    x = s["t1"][()] if "t1" in s else s["alpha"][()]
    xl = r"$t_1$" if "t1" in s else r"$\alpha$"
    fig, axs = plt.subplots(1, 2, figsize=(10, 4))
    axs[0].plot(x, s["energy_max"][()], "o-", ms=3)
    axs[0].set_ylabel("max |energy coefficient| over one period")
    axs[1].plot(x, s["precession_at_P"][()], "o-", ms=3)
    axs[1].axhline(0.0, color="0.6", lw=0.6)
    axs[1].set_ylabel("precession coefficient at t = P")
    if "t1_zero" in s.attrs and int(s.attrs["zero_found"]) == 1:
        axs[1].axvline(float(s.attrs["t1_zero"]), color="tab:red", ls=":",
                       label=f"zero at t1 = {float(s.attrs['t1_zero']):.4f}")
        axs[1].legend(frameon=False)
    if "alpha_least_energy" in s.attrs:
        axs[0].axvline(float(s.attrs["alpha_least_energy"]), color="tab:red", ls=":")
        axs[1].axvline(float(s.attrs["alpha_least_precession"]), color="tab:red", ls=":")
    for ax in axs:
        ax.set_xlabel(xl)
    fig.suptitle(f"{scene}: " + ("M2(t1)" if "t1" in s else "GFR5(alpha)") + ", eps = P/5000")
    fig.tight_layout()
    fig.savefig(os.path.join(figdir, scene + ".png"), dpi=110)
    plt.close(fig)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "out"
    figdir = sys.argv[2] if len(sys.argv) > 2 else os.path.join("doc", "figures")
    os.makedirs(figdir, exist_ok=True)
    done = 0
    for scene in COEF_SCENES + POINT_SCENES + ["acoef", "scanm2", "scangfr5"]:
        path = os.path.join(out, scene + ".h5")
        if not os.path.exists(path):
            continue
        with h5py.File(path, "r") as f:
            if scene in COEF_SCENES:
                coefficient_figures(f, scene, figdir)
            elif scene in POINT_SCENES:
                point_figure(f, scene, figdir)
            elif scene == "acoef":
                acoef_figure(f, figdir)
            else:
                scan_figure(f, scene, figdir)
        done += 1
        print(f"[plot] {scene}: figure(s) in {figdir}", flush=True)
    if done == 0:
        sys.exit(f"plot_figures.py: no scene files in {out}")


if __name__ == "__main__":
    main()
