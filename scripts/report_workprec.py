#!/usr/bin/env python3
"""Render the work-precision report and figures from the HDF5 file of fsym-workprec.

Usage: report_workprec.py [H5 [MD [FIGDIR]]]
       (defaults: out/work-precision.h5, doc/work-precision.md, doc/figures)

The time each method needs to reach each target error is interpolated log-log between the
two runs of its sweep that bracket the target (fsym-workprec extends every sweep until they
exist); times are the minimum over interleaved repetitions, their spread the median over the
same repetitions and the difference between the odd and the even rounds (two independent
repetitions of the study). Of the two clocks recorded (wall, thread CPU) the one with the
smaller median spread over all runs is used. A time verdict is called only when the ratio
exceeds the measured spread of both contenders and both halves of the rounds agree;
otherwise it is a tie. Evaluations are counted as forces and gradients separately, and as
effective evaluations F + c G with the measured gradient cost c and its range. Figures
(PNG and PDF): error against run time, one
figure per orbit, methods split into panels of at most eight curves, each with its own
colour and marker; the precession on the e = 0.9 orbit; error against evaluations.
"""
import os
import sys

import h5py

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fsym_report import text, write_atomic  # noqa: E402
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

PANELS = [
    ("forward, analytic gradient", ["T2", "A", "C", "A3", "A4", "A5", "A6"]),
    ("forward, extrapolated gradient", ["A'", "C'", "A3'", "A4'", "A5'", "A6'", "C"]),
    ("non-forward, 3-4 forces", ["FR", "M1", "M1(-1/24)", "M2(-0.1)", "M2(-0.5)", "M2(-1)",
                                "M2(-2)", "C"]),
    ("non-forward, 5-6 forces; RKN", ["GFR5(0.3)", "GFR5(0.5)", "GFR5(1)", "BM", "BM-mf",
                                      "SRKN6b", "RKN", "C"]),
]
COLOURS = ["tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple", "tab:brown",
           "tab:pink", "black"]
MARKERS = ["o", "s", "^", "v", "D", "P", "X", "*"]


def load(path):
    data = {"orbits": []}
    with h5py.File(path, "r") as f:
        p = f["parameters"].attrs
        data["par"] = {k: (text(v) if isinstance(v, bytes) else v) for k, v in p.items()}
        data["methods"] = [text(m).strip() for m in p["methods"]]
        for key in ("e0.9", "e0.6", "e0.6_3d"):
            g = f[key]
            o = dict(key=key, description=text(g.attrs["description"]),
                     d=int(g.attrs["dimension"]), periods=int(g.attrs["periods"]), runs={})
            for m in g.values():
                lab = text(m.attrs["label"])
                o["runs"][lab] = {k: m[k][()] for k in m.keys()}
                # samples: (steps, rounds) as h5py shows the Fortran (rounds, steps) array
                o["runs"][lab]["forward"] = int(m.attrs["forward"])
                o["runs"][lab]["order"] = int(m.attrs["order"])
            data["orbits"].append(o)
    return data


CLOCKS = {"cpu": ("cpu_samples", "thread CPU time"), "wall": ("time_samples", "wall clock")}


def spread_of(samples):
    """Relative spread of one run's samples: the larger of (median - minimum)/minimum and the
    relative difference between the minima of the odd and the even rounds."""
    lo = samples.min()
    halves = abs(samples[0::2].min() / samples[1::2].min() - 1) if len(samples) > 1 else 0
    return max(np.median(samples) / lo - 1, halves)


def choose_clock(data):
    """The clock whose median spread over every run of every orbit is smaller, and both
    medians (or 'wall' for files without CPU samples)."""
    med = {}
    for clock, (key, _) in CLOCKS.items():
        sp = [np.median(r[key], axis=1) / r[key].min(axis=1) - 1 for o in data["orbits"]
              for r in o["runs"].values() if key in r]
        med[clock] = float(np.median(np.concatenate(sp))) if sp else np.inf
    return min(med, key=med.get), med


def loglog(a, b, f):
    """Log-log interpolation between a and b at fraction f (0 when either is 0)."""
    if a <= 0 or b <= 0:
        return 0.0
    return float(np.exp(np.log(a) + f * (np.log(b) - np.log(a))))


def time_to(run, errkey, target, clock):
    """The run's cost of reaching the target: a dict with the time (minimum over all rounds,
    over the odd and over the even rounds), its spread, the steps per period N* and the
    force and gradient evaluations, each interpolated log-log between the two runs that
    bracket the target; or None and a reason."""
    err = np.abs(run[errkey])
    smp = run[CLOCKS[clock][0]]
    t = smp.min(axis=1)
    n = run["steps_per_period"]
    ok = np.isfinite(err) & (t > 0)
    for k in range(len(err)):
        if not ok[k] or not err[k] <= target:
            continue
        if k == 0:
            return None, "already below the target at the coarsest step P/%d" % round(n[0])
        if not ok[k - 1]:
            return None, "the run before the crossing failed"
        f = np.log(target / err[k - 1]) / np.log(err[k] / err[k - 1])
        res = dict(time=loglog(t[k - 1], t[k], f),
                   odd=loglog(smp[k - 1, 0::2].min(), smp[k, 0::2].min(), f),
                   even=loglog(smp[k - 1, 1::2].min(), smp[k, 1::2].min(), f),
                   spread=max(spread_of(smp[k - 1]), spread_of(smp[k])),
                   n=loglog(n[k - 1], n[k], f),
                   F=loglog(run["force_evals"][k - 1], run["force_evals"][k], f),
                   G=loglog(run["grad_evals"][k - 1], run["grad_evals"][k], f))
        return res, None
    return None, "not reached at the finest step P/%d" % round(n[-1])


def time_verdict(bf, bn):
    """Forward (bf) against non-forward (bn), each a time_to result: the verdict and the
    band. Decided only when the ratio of the minima exceeds the product of the two measured
    spreads and the odd and the even rounds on their own give the same side."""
    ratio = bn["time"] / bf["time"]
    band = (1 + bf["spread"]) * (1 + bn["spread"])
    odd, even = bn["odd"] / bf["odd"], bn["even"] / bf["even"]
    if ratio > band and odd > 1 and even > 1:
        return "forward wins", ratio, band, odd, even
    if ratio < 1 / band and odd < 1 and even < 1:
        return "non-forward wins", ratio, band, odd, even
    return "a tie within the measured spread", ratio, band, odd, even


def eval_verdict(f4, n4, cmin, cmax):
    """Fewest effective evaluations F + c G of each kind, for the gradient cost c at both
    ends of its measured range: the verdict holds only when it is the same at both."""
    out = []
    for c in (cmin, cmax):
        ef = min(r[2]["F"] + c * r[2]["G"] for r in f4)
        en = min(r[2]["F"] + c * r[2]["G"] for r in n4)
        out.append((ef, en, en / ef))
    sides = {("forward" if r > 1 else "non-forward" if r < 1 else "tie") for _, _, r in out}
    return (sides.pop() + " needs fewer" if len(sides) == 1 else
            "depends on the gradient cost within its measured range"), out


def targets(data):
    par = data["par"]
    out = []
    for o in data["orbits"]:
        for e in par["energy_targets"]:
            out.append((o, "max_rel_energy_error", float(e),
                        f"max abs(dE/E) <= {float(e):g}, {o['description']}"))
        if o["key"] == "e0.9":
            p = float(par["precession_target"])
            out.append((o, "precession_rad", p,
                        f"abs(precession) <= {p:g} rad after {o['periods']} periods, "
                        f"{o['description']}"))
    return out


def kind(label, run):
    if label == "RKN":
        return "RKN"
    return "forward" if run["forward"] else "non-forward"


def report(data, md, figdir):
    par = data["par"]
    clock, med = choose_clock(data)
    pairs = np.asarray(par.get("gradient_cost_pairs", [par["gradient_cost"]]), dtype=float)
    gc, cmin, cmax = float(par["gradient_cost"]), float(pairs.min()), float(pairs.max())
    gclock = text(par.get("gradient_cost_clock", "wall clock"))
    L = ["# Work-precision: error against run time", "",
         "Generated by `bash scripts/workprec.sh` (program `fsym-workprec` writes "
         "`out/work-precision.h5` and `doc/work-precision.csv`; `scripts/report_workprec.py` "
         "renders this page and the figures from the HDF5 file; rendering the same file "
         "again gives the same text, nothing here is edited by hand). Every number below "
         "comes from that run.", "",
         f"- Hardware: {par['hardware']}",
         f"- Compiler: {par['compiler']}; build flags `{par['build_flags']}`",
         f"- Git commit that made the numbers: `{par['git_commit']}`",
         f"- Total run time of the study: {float(par['total_seconds']):.1f} s",
         f"- Timings: every run {int(par['repetitions'])} times in interleaved rounds (every "
         "run of an orbit once per round, then the next round), each sample at least 4 ms "
         "long (short runs repeated within it), on two clocks: the wall clock and the CPU "
         "time of the thread (`clock_gettime(CLOCK_THREAD_CPUTIME_ID)`), which does not count "
         "the time other jobs on the shared machine take the core. Median spread "
         "(median - minimum)/minimum over all runs: wall clock "
         f"{100 * med['wall']:.1f} %, thread CPU {100 * med['cpu']:.1f} %; this page uses the "
         f"steadier, the {CLOCKS[clock][1]}. A time is the minimum over the rounds; its "
         "spread is the larger of (median - minimum)/minimum and the relative difference "
         "between the minima of the odd and of the even rounds (two independent repetitions), "
         "the larger of the two runs that bracket the target.",
         "- Verdicts: a faster kind is called only when the ratio of the two times exceeds "
         "(1 + spread of one)(1 + spread of the other) and the odd and the even rounds on "
         "their own put the same kind ahead; otherwise the verdict is a tie.", "",
         "## Setup", "",
         "- Methods: the library's catalogue (see doc/results.md for each method's source) "
         "and RKN; the forward/non-forward comparison is that of S. A. Chin, *Forward and "
         "non-forward symplectic integrators in solving classical dynamics problems*, Int. J. "
         "Comput. Math. 84(6), 729-747 (2007), doi:10.1080/00207160701458476, "
         "arXiv:0704.3273. The e = 0.6 orbit is from E. Hairer, C. Lubich and G. Wanner, "
         "*Geometric Numerical Integration*, 2nd ed., Springer (2006).",
         "- Orbits (Kepler, G M = 1): " + "; ".join(
             f"{o['description']}" for o in data["orbits"]) + ". The e = 0.9 orbit is the "
         "paper's q = (10, 0), v = (0, 0.1); the e = 0.6 orbit is q = (0.4, 0), v = (0, 2) "
         "(Hairer, Lubich, Wanner); its d = 3 copy is tilted by 30 degrees about x and 20 "
         "degrees about z.",
         f"- Step sizes: eps = P/N with N geometric from {float(par['base_grid'][0]):g} to "
         f"{float(par['base_grid'][1]):g} ({int(par['base_points'])} values), extended for "
         "each method by the same factor, coarser (down to P/4) or finer (up to P/4e6), "
         "until every target of its orbit is bracketed by two runs.",
         "- Per run: time of the integration alone (`stepper%run`), force and gradient "
         "evaluations (the library's counters), max relative energy error over every step, "
         "LRL precession at the end (signed, in the orbit's plane), phase-space error "
         "against `kepler_exact` (diagnostics in a separate, untimed run).",
         f"- Evaluations: forces F and gradients G are counted separately (the library's "
         f"counters). Effective evaluations F + c G assume the measured cost c of a gradient "
         f"relative to a force (Kepler model, {gclock}, {len(pairs)} interleaved pairs): "
         f"c = {gc:.3f} (ratio of the minima; the pairs range over {cmin:.3f} .. "
         f"{cmax:.3f}); a verdict on effective evaluations is called only when it is the same "
         "at both ends of that range. The evaluation plot uses F + c G.",
         ""]
    for o in data["orbits"]:
        L.append(f"![{o['description']}](figures/work-precision-{o['key']}.png)")
    L += ["", "![precession](figures/work-precision-precession.png)", "",
          "![evaluations](figures/work-precision-evaluations.png)", "",
          "## Time to reach a target error, ranked", "",
          "Time of a whole run (the stated number of periods) interpolated log-log between "
          "the two runs that bracket the target; N* is the interpolated number of steps per "
          "period, F and G the interpolated force and gradient evaluations of the whole run. "
          "Forward: all weights >= 0.", ""]
    bounded = 0
    for o, key, target, title in targets(data):
        rows = []
        for lab in data["methods"]:
            run = o["runs"][lab]
            res, why = time_to(run, key, target, clock)
            rows.append((lab, run, res, why))
        rows.sort(key=lambda r: r[2]["time"] if r[2] else np.inf)
        L += [f"### {title}", "", "| rank | method | kind | order | time to target (ms) | "
              "spread | N* | forces F | gradients G | F + c G |",
              "|---|---|---|---|---|---|---|---|---|---|"]
        for i, (lab, run, res, why) in enumerate(rows):
            if res:
                L.append(f"| {i + 1} | {lab} | {kind(lab, run)} | {run['order']} | "
                         f"{1e3 * res['time']:.3f} | {100 * res['spread']:.1f} % | "
                         f"{res['n']:.0f} | {res['F']:.4g} | {res['G']:.4g} | "
                         f"{res['F'] + gc * res['G']:.4g} |")
            else:
                bounded += 1
                L.append(f"| - | {lab} | {kind(lab, run)} | {run['order']} | - ({why}) "
                         "| | | | | |")
        fw = [r for r in rows if r[2] and r[1]["forward"] and r[0] != "RKN"]
        nf = [r for r in rows if r[2] and not r[1]["forward"] and r[0] != "RKN"]
        L.append("")
        for label, only in (("All splitting methods", 0), ("Fourth-order splitting methods "
                                                           "only (the paper's comparison)", 4)):
            f4 = [r for r in fw if not only or r[1]["order"] == only]
            n4 = [r for r in nf if not only or r[1]["order"] == only]
            if not f4 or not n4:
                L.append(f"- {label}: one of the two kinds never reached the target.")
                continue
            bf, bn = f4[0], n4[0]
            verdict, ratio, band, odd, even = time_verdict(bf[2], bn[2])
            ev, ends = eval_verdict(f4, n4, cmin, cmax)
            L.append(f"- {label}: fastest forward {bf[0]} ({1e3 * bf[2]['time']:.3f} ms, "
                     f"spread {100 * bf[2]['spread']:.1f} %), fastest non-forward {bn[0]} "
                     f"({1e3 * bn[2]['time']:.3f} ms, spread {100 * bn[2]['spread']:.1f} %): "
                     f"{verdict} (ratio non-forward/forward {ratio:.3f} against the band "
                     f"{band:.3f}; odd rounds {odd:.3f}, even rounds {even:.3f}). Fewest "
                     f"effective evaluations F + c G: forward {ends[0][0]:.4g}, non-forward "
                     f"{ends[0][1]:.4g} (ratio {ends[0][2]:.3f}) at c = {cmin:.3f}; forward "
                     f"{ends[1][0]:.4g}, non-forward {ends[1][1]:.4g} (ratio "
                     f"{ends[1][2]:.3f}) at c = {cmax:.3f}: {ev}.")
        top = [r for r in rows if r[2]][:5]
        L += [f"- Forward methods among the five fastest: "
              f"{sum(1 for r in top if r[1]['forward'] and r[0] != 'RKN')}.", ""]
    L += [f"Entries not interpolated (bounded or unreached): {bounded}."]
    write_atomic(md, L)
    return bounded


def save(fig, figdir, name):
    fig.savefig(os.path.join(figdir, name + ".png"), dpi=100)
    fig.savefig(os.path.join(figdir, name + ".pdf"), metadata={"CreationDate": None})
    plt.close(fig)


def panels(data, orbit, xfun, xlabel, ykey, ylabel, title, name, figdir):
    fig, axs = plt.subplots(2, 2, figsize=(13, 10), sharex=True, sharey=True)
    for ax, (ptitle, labels) in zip(axs.ravel(), PANELS):
        for i, lab in enumerate(labels):
            run = orbit["runs"].get(lab)
            if run is None:
                continue
            x, y = xfun(run), np.abs(run[ykey])
            ok = np.isfinite(x) & np.isfinite(y) & (x > 0) & (y > 0)
            ref = lab == "C" and i == len(labels) - 1 and ptitle != PANELS[0][0]
            ax.loglog(x[ok], y[ok], ls="-" if run["forward"] else "--",
                      color="0.55" if ref else COLOURS[i % 8], marker=MARKERS[i % 8], ms=4,
                      lw=1.0, label=lab + (" (reference)" if ref else ""))
        ax.set_title(ptitle, fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8, loc="lower left", ncol=2)
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
        ax.tick_params(labelbottom=True, labelleft=True)
    fig.suptitle(title + " (solid: forward, dashed: non-forward and RKN)")
    fig.tight_layout()
    save(fig, figdir, name)


def figures(data, figdir):
    os.makedirs(figdir, exist_ok=True)
    gcost = float(data["par"]["gradient_cost"])
    clock, _ = choose_clock(data)
    key, name = CLOCKS[clock]
    xlabel = f"run time (s, {name}, minimum of repetitions)"
    for o in data["orbits"]:
        panels(data, o, lambda r: r[key].min(axis=1), xlabel,
               "max_rel_energy_error", "max |dE/E|", f"Energy error against run time, "
               f"{o['description']}", f"work-precision-{o['key']}", figdir)
    o = data["orbits"][0]
    panels(data, o, lambda r: r[key].min(axis=1), xlabel, "precession_rad",
           "|LRL precession| at the end (rad)",
           f"Precession against run time, {o['description']}", "work-precision-precession",
           figdir)
    panels(data, o, lambda r: r["force_evals"] + gcost * r["grad_evals"],
           f"effective evaluations F + c G, c = {gcost:.3f} (measured gradient cost)",
           "max_rel_energy_error", "max |dE/E|",
           f"Energy error against evaluations, {o['description']}",
           "work-precision-evaluations", figdir)


def main():
    h5 = sys.argv[1] if len(sys.argv) > 1 else "out/work-precision.h5"
    md = sys.argv[2] if len(sys.argv) > 2 else "doc/work-precision.md"
    figdir = sys.argv[3] if len(sys.argv) > 3 else "doc/figures"
    data = load(h5)
    figures(data, figdir)
    bounded = report(data, md, figdir)
    print(f"[workprec] wrote {md} ({bounded} entries not interpolated) and figures in {figdir}")


if __name__ == "__main__":
    main()
