#!/usr/bin/env python3
"""Turn the study's HDF5 scenes (written by `fsym-study`) into the paper's figures.

Usage: plot_figures.py [OUT_DIR [FIG_DIR]]   (defaults: out, doc/figures)

Every figure is written as PNG (for the markdown pages) and as vector PDF. Coefficient
scenes (engNf) give engNf (energy error coefficient against t/P) and angNf (precession error
coefficient against t/P), each with a zoom on the first pericentre passage. Force-point
scenes (backX) give backX: the force-evaluation points over the dashed exact orbit; forward
methods as circles (hollow, except A5 in back5f, solid as in the paper), non-forward methods
as squares (first solid, then hollow), RKN as plus signs, gradient evaluations as crosses, the
step ends as black dots. back4f, back4f2 and back5f show one step, from position 2 to the
pericentre 3, as the paper's do, with the force points of the two non-forward methods
numbered in the order they are evaluated (F1, F2, ... for the first, f1, f2, ... for the
second), the names the paper's text uses; a force the step reuses from the end of the
previous one (first same as last) is drawn and numbered as the step's first. acoef, scanm2 and
scangfr5 give the GFR5 coefficients and the two parameter scans. Groups are found through
their `label` attribute (the group names are safe forms of the labels).
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import h5py  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.ticker import MaxNLocator  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fsym_report import study_scenes  # noqa: E402

ONE_STEP = {"back4f", "back4f2", "back5f"}  # the paper shows one step 2 -> 3 (and numbers it)
SOLID_FORWARD = {"back5f": {"A5"}}          # "forward algorithm A5 (solid circles)"


def text(x):
    return x.decode() if isinstance(x, bytes) else str(x)


def methods(f):
    """The method labels of a scene, in the order the scene ran them."""
    return [text(m) for m in f["parameters"].attrs["methods"]]


def group(f, where, label):
    """The group under `where` whose `label` attribute is `label`."""
    for g in f[where].values():
        if text(g.attrs.get("label", g.attrs.get("method", ""))) == label:
            return g
    raise KeyError(f"no {where} group labelled {label}")


def save(fig, figdir, name):
    fig.savefig(os.path.join(figdir, name + ".png"), dpi=110)
    fig.savefig(os.path.join(figdir, name + ".pdf"), metadata={"CreationDate": None})
    plt.close(fig)


def coefficient_figures(f, scene, figdir):
    """engNf.png and angNf.png from one coefficient scene."""
    for kind, prefix, ylabel in [
        ("energy_coefficient", "eng", r"$(E(t)-E_0)/(E_0\,\epsilon^4)$"),
        ("precession_coefficient", "ang", r"LRL rotation angle (rad) $/\,\epsilon^4$"),
    ]:
        fig, axs = plt.subplots(1, 2, figsize=(11, 4.6), gridspec_kw=dict(width_ratios=[3, 2]))
        par = f["parameters"].attrs
        period = float(par["period"])
        lo, hi = 0.0, 0.0
        for m in methods(f):
            obs = group(f, "observables", m)[kind]
            t = obs["time"][()] / period
            y = obs["value"][()]
            for ax in axs:
                ax.plot(t, y, lw=1.2, label=m)
            w = (t >= 0.49) & (t <= 0.51)
            lo, hi = min(lo, y[w].min()), max(hi, y[w].max())
        for ax in axs:
            ax.axhline(0.0, color="0.6", lw=0.6)
            ax.set_xlabel("t / P")
            ax.set_ylabel(ylabel)
        axs[1].set_xlim(0.49, 0.51)
        pad = 0.06 * (hi - lo) + 1e-12
        axs[1].set_ylim(lo - pad, hi + pad)
        axs[1].xaxis.set_major_locator(MaxNLocator(4))
        axs[1].yaxis.set_major_locator(MaxNLocator(6))
        axs[1].set_title("zoom: first pericentre passage")
        n = round(period / float(par["eps"]))
        what = "energy error" if prefix == "eng" else "precession error"
        axs[0].set_title(f"{what}, e = 0.9 Kepler orbit, " + r"$\epsilon$" + f" = P/{n}")
        axs[0].legend(frameon=False)
        fig.tight_layout()
        save(fig, figdir, prefix + scene[3:])


def last_step(g, p):
    """The force points of the last step of group g, with those of the previous step that
    sit at the position the last step starts from (a first-same-as-last force it reuses; the
    step's own force at its end is then the next step's first and left out); p: the
    step-end positions. Returns positions and kinds."""
    q = g["position"][()][:, 0, :]
    kind, step = g["kind"][()], g["step"][()]
    last = step == step.max()
    at = [np.hypot(*(q - x).T) <= 1e-12 * np.hypot(*x) for x in (p[-2], p[-1])]
    reuse = (step == step.max() - 1) & at[0]
    keep = reuse | last
    if np.any(reuse):  # then the force at the end is the next step's first: not this one's
        keep &= ~(last & at[1])
    return q[keep], kind[keep]


def point_figure(f, scene, figdir):
    """backX.png: force-evaluation points over the exact orbit."""
    fig, ax = plt.subplots(figsize=(6.4, 6.4))
    qe = f["exact/position/value"][()][:, 0, :]
    ax.plot(qe[:, 0], qe[:, 1], "k--", lw=1.0, label="exact orbit")
    nonfwd = 0
    pts = [qe[np.argmin(np.hypot(qe[:, 0], qe[:, 1]))][None, :]]
    colours = ["tab:red", "tab:blue", "tab:green", "tab:purple"]
    one = scene in ONE_STEP
    for i, m in enumerate(methods(f)):
        g = group(f, "force_evaluations", m)
        par = group(f, "parameters", m).attrs
        p = group(f, "particles", m)["position/value"][()][:, 0, :]
        if one:
            q, kind = last_step(g, p)
            p = p[-2:]
        else:
            q = g["position"][()][:, 0, :]
            kind = g["kind"][()]
        col = colours[i % len(colours)]
        prefix = None
        if text(par["method"]) == "RKN":
            style = dict(marker="+", s=120, color=col, linewidths=1.6)
        elif int(par["forward"]) == 1:
            face = col if m in SOLID_FORWARD.get(scene, ()) else "none"
            style = dict(marker="o", s=70, facecolors=face, edgecolors=col, linewidths=1.4)
        else:
            face = col if nonfwd == 0 else "none"
            style = dict(marker="s", s=60, facecolors=face, edgecolors=col, linewidths=1.4)
            prefix = "F" if nonfwd == 0 else "f"
            nonfwd += 1
        sel = kind != 2  # gradients sit where a force was evaluated: mark them separately
        ax.scatter(q[sel, 0], q[sel, 1], label=f"{m} force points"
                   + (f" ({prefix}1, {prefix}2, ...)" if one and prefix else ""), zorder=3,
                   **style)
        if one and prefix:
            for k, qk in enumerate(q[sel]):
                ax.annotate(f"{prefix}{k + 1}", qk, textcoords="offset points",
                            xytext=(7, 5 if prefix == "F" else -12), color=col, fontsize=9)
        if np.any(kind == 2):
            ax.scatter(q[kind == 2, 0], q[kind == 2, 1], marker="x", s=25, color=col, zorder=4,
                       label=f"{m} gradient points")
        pts += [q, p]
        ax.plot(p[:, 0], p[:, 1], ":", color=col, lw=0.8)
        ends = ("start 2 and end 3 of the step" if one else
                "step ends (positions after 0, 1, 2 steps)")
        ax.scatter(p[:, 0], p[:, 1], marker="o", s=22, color="k", zorder=5,
                   label=ends if i == 0 else None)
        if one and i == 0:
            for lab, pk in zip(["2", "3"], p):
                ax.annotate(lab, pk, textcoords="offset points", xytext=(-12, 6), fontsize=10)
    if scene == "backfr" and "substeps" in f:
        sub = f["substeps/FR/position/value"][()][:, 0, :]
        fq = group(f, "force_evaluations", "FR")["position"][()][:, 0, :]
        path = []
        for k in range(len(fq)):
            path += [sub[k], fq[k]]
        path.append(sub[-1])
        path = np.array(path)
        ax.plot(path[:, 0], path[:, 1], "-", color="tab:red", lw=0.8,
                label="FR's three T2 substeps (triangles)")
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
    ax.set_xlabel("x (L)")
    ax.set_ylabel("y (L)")
    ax.xaxis.set_major_locator(MaxNLocator(5))
    ax.yaxis.set_major_locator(MaxNLocator(5))
    par = f["parameters"].attrs
    n = round(float(par["period"]) / float(par["eps"]))
    steps = "one step (2 -> 3) to" if one else "two steps to"
    ax.set_title(f"force-evaluation points, {steps} the pericentre, "
                 + r"$\epsilon$" + f" = P/{n}", fontsize=10)
    ax.legend(frameon=True, framealpha=0.85, fontsize=8, loc="best")
    fig.tight_layout()
    save(fig, figdir, scene)


def acoef_figure(f, figdir):
    fig, ax = plt.subplots(figsize=(6.4, 4.5))
    al = f["gfr5/alpha"][()]
    for name in ["a0", "a1", "a2"]:
        ax.plot(al, f["gfr5"][name][()], label=name)
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.axvline(float(f["gfr5"].attrs["alpha_least_negative_a0"]), color="0.6", ls=":", lw=0.8,
               label=r"$a_0$ least negative")
    ax.set_xlabel(r"$\alpha$")
    ax.set_ylabel("GFR5 substep fraction")
    ax.set_title(r"GFR5 substep fractions $a_0, a_1, a_2$ against $\alpha$")
    ax.legend(frameon=False)
    fig.tight_layout()
    save(fig, figdir, "acoef")


def scan_figure(f, scene, figdir):
    s = f["scan"]
    x = s["t1"][()] if "t1" in s else s["alpha"][()]
    xl = r"$t_1$" if "t1" in s else r"$\alpha$"
    fig, axs = plt.subplots(1, 2, figsize=(10, 4))
    axs[0].plot(x, s["energy_max"][()], "o-", ms=3, label="measured")
    axs[0].set_ylabel("max |energy coefficient| over one period")
    axs[1].plot(x, s["precession_at_P"][()], "o-", ms=3, label="measured")
    axs[1].axhline(0.0, color="0.6", lw=0.6)
    axs[1].set_ylabel("precession coefficient at t = P")
    if "t1_zero" in s.attrs and int(s.attrs["zero_found"]) == 1:
        axs[1].axvline(float(s.attrs["t1_zero"]), color="tab:red", ls=":",
                       label=f"zero at t1 = {float(s.attrs['t1_zero']):.4f}")
        axs[1].legend(frameon=False)
    if "alpha_least_energy" in s.attrs:
        a = float(s.attrs["alpha_least_energy"])
        axs[0].axvline(a, color="tab:red", ls=":", label=f"least at alpha = {a:.3f}")
        a = float(s.attrs["alpha_least_precession"])
        axs[1].axvline(a, color="tab:red", ls=":", label=f"least |precession| at alpha = {a:.3f}")
    for ax in axs:
        ax.set_xlabel(xl)
        ax.legend(frameon=False, fontsize=8)
    n = round(float(f["parameters"].attrs["period"]) / float(f["parameters"].attrs["eps"]))
    fig.suptitle(("M2 against its free parameter " + r"$t_1$" if "t1" in s else
                  "GFR5 against its free parameter " + r"$\alpha$")
                 + ", e = 0.9 Kepler orbit, " + r"$\epsilon$" + f" = P/{n}")
    fig.tight_layout()
    save(fig, figdir, scene)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "out"
    figdir = sys.argv[2] if len(sys.argv) > 2 else os.path.join("doc", "figures")
    os.makedirs(figdir, exist_ok=True)
    done = 0
    # the scene names and kinds come from fsym-study (OUT/scenes.txt); drawn kind by kind
    draw = {"coefficients": lambda f, scene: coefficient_figures(f, scene, figdir),
            "points": lambda f, scene: point_figure(f, scene, figdir),
            "acoef": lambda f, scene: acoef_figure(f, figdir),
            "scan": lambda f, scene: scan_figure(f, scene, figdir)}
    scenes = study_scenes(out)
    for scene in [name for kind in draw for name, k in scenes if k == kind]:
        path = os.path.join(out, scene + ".h5")
        if not os.path.exists(path):
            continue
        with h5py.File(path, "r") as f:
            draw[dict(scenes)[scene]](f, scene)
        done += 1
        print(f"[plot] {scene}: figure(s) in {figdir}", flush=True)
    if done == 0:
        sys.exit(f"plot_figures.py: no scene files in {out}")


if __name__ == "__main__":
    main()
