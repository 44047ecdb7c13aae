#!/usr/bin/env python3
"""Render doc/results.md from the study's HDF5 files (written by `fsym-study`).

Usage: report_results.py [OUT_DIR [RESULTS_MD]]   (defaults: out, doc/results.md)

Reads OUT_DIR/results.h5 (per-method coefficients at eps = P/1000 .. P/10000), the
force-point scenes OUT_DIR/back*.h5 and the scans OUT_DIR/scanm2.h5, scangfr5.h5 and
acoef.h5. Every number in the report comes from those files; the report is written to a
temporary name and renamed into place.
"""
import os
import sys

import h5py

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fsym_report import study_scenes, text, write_atomic  # noqa: E402
import numpy as np

FACTOR = 1.5  # "about k times" (a number read off a figure): k/FACTOR <= ratio <= k*FACTOR
PAPER_METHODS = ["FR", "A", "A'", "C", "M1", "M1(-0.2)", "M1(-0.1)", "M1(-1/24)", "M2(-0.1)",
                 "M2(-0.5)", "M2(-1)", "M2(-2)", "GFR5(0.3)", "GFR5(0.5)", "GFR5(1)", "A5",
                 "BM", "A6", "A6'"]  # the methods in the paper's figures
CONVERGED = 0.05  # eps vs eps/2 relative difference below which a coefficient is converged
PAPER = ("S. A. Chin, *Forward and non-forward symplectic integrators in solving classical "
         "dynamics problems*, Int. J. Comput. Math. 84(6), 729-747 (2007), "
         "doi:10.1080/00207160701458476, arXiv:0704.3273")


REFERENCES = [
    PAPER + " (the study repeated here; A, A', C, AN, M1, M2, GFR5).",
    "S. A. Chin, *Symplectic integrators from composite operator factorizations*, Phys. "
    "Lett. A 226, 344-348 (1997) (algorithms A and C).",
    "E. Forest and R. D. Ruth, *Fourth-order symplectic integration*, Physica D 43, 105-117 "
    "(1990) (FR).",
    "M. Creutz and A. Gocksch, *Higher-order hybrid Monte Carlo algorithms*, Phys. Rev. "
    "Lett. 63, 9-12 (1989) (FR; GFR5(1)).",
    "M. Suzuki, *Fractal decomposition of exponential operators with applications to "
    "many-body theories and Monte Carlo simulations*, Phys. Lett. A 146, 319-323 (1990) "
    "(GFR5(1)).",
    "R. I. McLachlan, *On the numerical integration of ordinary differential equations by "
    "symmetric composition methods*, SIAM J. Sci. Comput. 16, 151-168 (1995) (M1).",
    "S. Blanes and P. C. Moan, *Practical symplectic partitioned Runge-Kutta and "
    "Runge-Kutta-Nystrom methods*, J. Comput. Appl. Math. 142, 313-330 (2002) (BM, BM-mf, "
    "SRKN6b).",
    "I. P. Omelyan, I. M. Mryglod and R. Folk, *Optimized Forest-Ruth- and Suzuki-like "
    "algorithms for integration of motion in many-body systems*, Comput. Phys. Commun. 146, "
    "188-202 (2002), and *Symplectic analytically integrable decomposition algorithms: "
    "classification, derivation, and application to molecular dynamics, quantum and "
    "celestial mechanics simulations*, Comput. Phys. Commun. 151, 272-314 (2003) (the "
    "extrapolated gradient of A', C', AN').",
]


def g7(x):
    return f"{x:.7g}"


# ---- the rules ------------------------------------------------------------------------
# Each claim of the paper is decided by one of the rules below; each returns a verdict:
# HOLDS, FAILS or TIE (a difference the claim asserts but the data cannot tell from no
# difference). The tolerances follow from two numbers only: the page's convergence criterion
# CONVERGED (a coefficient is known to that relative accuracy, so a ratio of two coefficients
# to TIE = (1 + CONVERGED)^2) and FACTOR, the reading of "about k times" (a number read off
# a figure by eye). test/report/test_report_rules.py plants a counter-example for every
# claim row and checks that it is reported as not holding.
HOLDS, FAILS, TIE_VERDICT = "holds", "does not hold", "tie"
TIE = (1 + CONVERGED) ** 2       # two coefficients each known to CONVERGED
CLOSE = 2 * CONVERGED            # curves that "closely match": differ as two converged ones
LIKE = 1 - 1 / FACTOR            # "like": differ no more than a factor-F rescaling would


def roundoff(s, labels, n=5000):
    """Relative size of round-off in a coefficient: unit round-off u grows at most linearly
    over the n steps of a period and is divided by eps^4 (eps = P/n) and by the smallest
    coefficient compared."""
    eps = s.period / n
    least = min(min(s.E(m, n), s.P(m, n)) for m in labels)
    return float(np.finfo(float).eps) * n / (eps ** 4 * least)


def rule_about(ratio, k):
    """'about k times', 'comparable' (k = 1): the ratio lies within a factor FACTOR of k."""
    return HOLDS if k / FACTOR <= ratio <= k * FACTOR else FAILS


def rule_near(ratio, k, tol):
    """'twice', 'converges': the ratio lies within a factor (1 + tol) of k."""
    return HOLDS if k / (1 + tol) <= ratio <= k * (1 + tol) else FAILS


def rule_more(ratio, k=1.0, band=TIE):
    """'larger', 'smaller', 'improves' (k = 1), 'much larger', 'far' (k = FACTOR), 'more
    than k times': the ratio, oriented as the statement, exceeds k by more than the band; a
    ratio within the band of k is a tie; below it the statement does not hold."""
    if ratio > k * band:
        return HOLDS
    return TIE_VERDICT if ratio >= k / band else FAILS


def rule_at_most(value, limit):
    """A difference that must not exceed a limit (convergence, closeness of two curves)."""
    return HOLDS if value <= limit else FAILS


def rule_least_at(x0, xmin, value0, least, others, tol=CONVERGED):
    """'lowest at x0' on a scan: the scan's minimiser xmin is nearer to x0 than to every
    other value the paper shows (others), and the value at x0 is within tol of the least."""
    nearest = all(abs(xmin - x0) < abs(xmin - o) for o in others)
    return HOLDS if nearest and value0 <= least * (1 + tol) else FAILS


def rule_all(verdicts):
    """A general statement ('in all cases'): holds when every case holds."""
    if all(v == HOLDS for v in verdicts):
        return HOLDS
    return FAILS if any(v == FAILS for v in verdicts) else TIE_VERDICT


def curve_difference(x, ref):
    """Relative L2 difference of coefficient curve x from the reference curve ref."""
    x, ref = np.asarray(x), np.asarray(ref)
    return float(np.linalg.norm(x - ref) / np.linalg.norm(ref))


class Summary:
    """Coefficients of every method from results.h5, indexed by label."""

    def __init__(self, path):
        with h5py.File(path, "r") as f:
            par = f["parameters"].attrs
            self.ladder = [int(n) for n in par["steps_per_period"]]
            self.t1zero = float(par["m2_t1_zero"])
            self.period = float(par["period"])
            self.q0, self.v0 = par["q0"], par["v0"]
            self.commit = text(par["git_commit"])
            self.compiler = text(par["compiler"])
            self.labels = [text(m).strip() for m in par["methods"]]
            self.d = {}
            self.curves = {}
            for g in f["summary"].values():
                lab = text(g.attrs["label"])
                self.d[lab] = dict(
                    forward=int(g.attrs["forward"]), symplectic=int(g.attrs["symplectic"]),
                    nf=int(g.attrs["forces_per_step"]), ng=int(g.attrs["gradients_per_step"]),
                    emax=g["energy_max"][()], eP=g["energy_at_P"][()],
                    pP=g["precession_at_P"][()], e2P=g["energy_at_2P"][()],
                    p2P=g["precession_at_2P"][()])
                if "energy_curve" in g:
                    self.curves[lab] = dict(energy=g["energy_curve"][()],
                                            precession=g["precession_curve"][()])

    def at(self, label, key, n=5000):
        return float(self.d[label][key][self.ladder.index(n)])

    def E(self, label, n=5000):
        return abs(self.at(label, "emax", n))

    def P(self, label, n=5000):
        return abs(self.at(label, "pP", n))

    def curve(self, label, kind):
        """The coefficient curve ('energy' or 'precession') over the first period, P/5000."""
        return self.curves[label][kind]


class SceneData:
    """The scenes beside results.h5 that the claims read: force points, the GFR5 scans."""

    def __init__(self, out):
        self.out = out

    def distances(self, scene):
        return distances(os.path.join(self.out, scene + ".h5"))

    def point_scenes(self):
        """The force-point scenes, named by fsym-study (OUT/scenes.txt)."""
        return [name for name, kind in study_scenes(self.out) if kind == "points"]

    def acoef(self):
        with h5py.File(os.path.join(self.out, "acoef.h5"), "r") as f:
            return f["gfr5/alpha"][()], f["gfr5/a0"][()]

    def scan_gfr5(self):
        with h5py.File(os.path.join(self.out, "scangfr5.h5"), "r") as f:
            return (f["scan/alpha"][()], f["scan/energy_max"][()],
                    f["scan/precession_at_P"][()])


def reldiff(a, b):
    s = max(abs(a), abs(b))
    return 0.0 if s == 0 else abs(a - b) / s


def distances(path):
    """Max distance of each method's force-evaluation points from the exact orbit."""
    out = {}
    with h5py.File(path, "r") as f:
        qe = f["exact/position/value"][()][:, 0, :]
        # dense polyline: distance to the nearest segment
        a, b = qe[:-1], qe[1:]
        for g in f["force_evaluations"].values():
            q = g["position"][()][:, 0, :]
            best = []
            for p in q:
                ab = b - a
                t = np.clip(np.einsum("ij,ij->i", p - a, ab) / np.einsum("ij,ij->i", ab, ab),
                            0, 1)
                best.append(np.min(np.hypot(*(a + t[:, None] * ab - p).T)))
            out[text(g.attrs["label"])] = max(best)
    return out


class Claims:
    def __init__(self):
        self.rows = []

    def add(self, key, section, claim, measured, verdict, rule):
        assert verdict in (HOLDS, FAILS, TIE_VERDICT)
        assert key not in [r[0] for r in self.rows], key
        self.rows.append((key, section, claim, measured, verdict, rule))

    def about(self, key, section, claim, ratio, k, what):
        """'about k times': within FACTOR of k."""
        self.add(key, section, claim, f"{what} = {g7(ratio)}", rule_about(ratio, k),
                 f"within x{FACTOR:g} of {k:g}")

    def more(self, key, section, claim, ratio, k, what, note=""):
        """'larger' (k = 1), 'much larger' (k = FACTOR), 'more than k times'."""
        self.add(key, section, claim, f"{what} = {g7(ratio)}{note}", rule_more(ratio, k),
                 f"> {g7(k * TIE)} ({k:g} x TIE); tie within [{g7(k / TIE)}, {g7(k * TIE)}]")

    def close(self, key, section, claim, s, a, b):
        """'closely matches', 'nearly indistinguishable': the energy curves of a and b."""
        dd = curve_difference(s.curve(a, "energy"), s.curve(b, "energy"))
        self.add(key, section, claim, f"relative L2 difference of the energy curves over the "
                 f"first period = {dd:.3g} (max heights {a}/{b} = {g7(s.E(a) / s.E(b))})",
                 rule_at_most(dd, CLOSE), f"<= {CLOSE:g} (2 x the convergence criterion)")


# The families whose backward step shrinks from left to right (the paper's section 3 and 4:
# t1 of M1 from McLachlan's -0.299 to -1/24; "the more negative the parameter t1 the smaller
# the negative time step" of M2; |a0| of GFR5 decreasing from alpha = 0 (FR) to 1).
SHRINKING = [["M1", "M1(-1/24)"], ["M2(-0.1)", "M2(-0.5)", "M2(-1)", "M2(-2)"],
             ["FR", "GFR5(0.3)", "GFR5(0.5)", "GFR5(1)"]]
# Non-forward against forward at equal evaluations per step, as the paper's figures pair
# them (eng3f: FR with A, A'; eng4f: M1 with C; eng4f2: M2 with C; eng5f: GFR5 with A5;
# eng6f: BM with A6, A6').
EVAL_PAIRS = [("FR", "A"), ("FR", "A'"), ("M1", "C"), ("M1(-1/24)", "C"), ("M2(-0.1)", "C"),
              ("M2(-0.5)", "C"), ("M2(-1)", "C"), ("M2(-2)", "C"), ("GFR5(0.3)", "A5"),
              ("GFR5(0.5)", "A5"), ("GFR5(1)", "A5"), ("BM", "A6"), ("BM", "A6'")]


def build_claims(s, sc):
    """Every claim row from the summary `s` (a Summary) and the scenes `sc` (a SceneData)."""
    c = Claims()
    sec = "2. Three force evaluations"
    worst = max((reldiff(s.at(m, "emax", 1000), s.at(m, "emax", 2000)), m)
                for m in PAPER_METHODS if m in s.d and s.d[m]["symplectic"])
    c.add("converged_P1000", sec, "symplectic methods: the energy coefficient has converged "
          "at eps = P/1000 (the same at P/2000)",
          f"largest relative difference of the max energy coefficient, P/1000 vs P/2000, over "
          f"the paper's symplectic methods ({worst[1]}) = {worst[0]:.3g}",
          rule_at_most(worst[0], CONVERGED), f"<= {CONVERGED:g} (this page's convergence "
          "criterion)")
    r = s.at("RKN", "eP", 5000) / s.at("RKN", "eP", 10000)
    c.more("rkn_energy_falls", sec, "RKN: the energy error after mid-period keeps lowering "
           "with the step (no convergence)", r, 1,
           "energy coeff. at t = P, eps = P/5000 over P/10000")
    r = s.at("RKN", "e2P") / s.at("RKN", "eP")
    c.add("rkn_energy_steps", sec, "RKN (non-symplectic): the energy error grows by an "
          "irreversible step each period (linearly: twice after two periods)",
          f"energy coeff. at 2P over that at P = {g7(r)}", rule_near(r, 2, TIE - 1),
          f"within x{g7(TIE)} of 2")
    c.about("fr_a_energy", sec, "FR's energy spike ~10x that of A", s.E("FR") / s.E("A"), 10,
            "ratio")
    c.close("a1_a_energy_curve", sec, "A' energy error closely matches A's", s, "A'", "A")
    r = s.at("RKN", "pP", 5000) / s.at("RKN", "pP", 10000)
    c.add("rkn_prec_converges", sec, "RKN's precession coefficient converges like the "
          "symplectic ones", f"precession coeff. P/5000 over P/10000 = {g7(r)}",
          rule_near(r, 1, CONVERGED), f"within x{1 + CONVERGED:g} of 1 (the convergence "
          "criterion)")
    c.about("fr_rkn_prec", sec, "FR's precession error ~3x that of RKN",
            s.P("FR") / s.P("RKN"), 3, "ratio")
    c.about("fr_a_prec", sec, "FR's precession error ~10x that of A", s.P("FR") / s.P("A"),
            10, "ratio")
    c.about("fr_a1_prec", sec, "FR's precession error ~10x that of A'",
            s.P("FR") / s.P("A'"), 10, "ratio")
    c.more("a1_smaller_a_prec", sec, "A' precession error smaller than A's",
           s.P("A") / s.P("A'"), 1, "ratio A/A'")
    d = sc.distances("back3f")
    c.more("back3f", sec, "FR evaluates the force far off the trajectory, A close to it "
           "(Fig. back3f)", d["FR"] / d["A"], FACTOR, "max distance of the force points from "
           f"the exact orbit, FR/A ({g7(d['FR'])} / {g7(d['A'])})")

    sec = "3. Four force evaluations"
    for key, name in (("E", "energy"), ("P", "precession")):
        f = getattr(s, key)
        c.more(f"m1_t1_{name}", sec, f"M1: reducing the backward step t1 from McLachlan's "
               f"-0.299 to -1/24 improves the {name} error", f("M1") / f("M1(-1/24)"), 1,
               "ratio M1/M1(-1/24)")
    for name in ("energy", "precession"):
        dd = curve_difference(s.curve("C'", name), s.curve("C", name))
        h = getattr(s, name[0].upper())("C'") / getattr(s, name[0].upper())("C")
        note = ""
        if rule_at_most(dd, LIKE) != HOLDS:
            what = "coefficient" if name == "precession" else "height"
            note = (f"; the paper is wrong here: it omits C' as similar to C, but the {name} "
                    f"{what} of C' is {g7(h)} times C's")
        c.add(f"c1_like_c_{name}", sec, f"C' (extrapolated gradient): results similar to C's "
              f"({name})", f"relative L2 difference of the {name} curves over the first "
              f"period = {dd:.3g} (heights C'/C = {g7(h)}){note}", rule_at_most(dd, LIKE),
              f"<= {g7(LIKE)} (what a factor-{FACTOR:g} rescaling gives)")
    d = sc.distances("back4f")
    c.more("back4f", sec, "M1: t1 = -1/24 brings the back-tracking force points closer "
           "(Fig. back4f)", d["M1"] / d["M1(-1/24)"], 1,
           "max distance from the orbit, M1/M1(-1/24)")
    m1 = ["M1", "M1(-1/24)"]
    m2 = ["M2(-0.1)", "M2(-0.5)", "M2(-1)", "M2(-2)"]
    for key, name in (("E", "energy"), ("P", "precession")):
        f = getattr(s, key)
        b1, b2 = min(m1, key=f), min(m2, key=f)
        c.more(f"m2_over_m1_{name}", sec, f"M2 (momentum first) much improved over M1 "
               f"({name})", f(b1) / f(b2), FACTOR, f"best M1 ({b1}) over best M2 ({b2})")
    for key, name in (("E", "energy"), ("P", "precession")):
        f = getattr(s, key)
        c.more(f"m2_05_{name}", sec, f"M2: t1 = -0.5 improves on t1 = -0.1 ({name})",
               f("M2(-0.1)") / f("M2(-0.5)"), 1, "ratio M2(-0.1)/M2(-0.5)")
    d = sc.distances("back4f2")
    c.more("back4f2", sec, "M2: t1 = -0.5 reduces the back-tracking points (Fig. back4f2)",
           d["M2(-0.1)"] / d["M2(-0.5)"], 1, "max distance from the orbit, M2(-0.1)/M2(-0.5)")
    fam = min(abs(s.at(m, "p2P")) for m in m2)
    r = fam / max(abs(s.at("M2(t1*)", "p2P")), 1e-300)
    c.more("m2_zero", sec, "M2: t1 can be fine-tuned so that the precession error is zero "
           f"after each period (t1* = {s.t1zero:.7f}, the zero at t = P; checked at t = 2P)",
           r, 1 / CONVERGED, "precession at 2P: least |coefficient| of M2(-0.1 .. -2) over "
           "|M2(t1*)|")

    sec = "4. Five and six force evaluations"
    al, a0 = sc.acoef()
    amin = al[np.argmin(abs(a0))]
    step = float(np.max(np.diff(al)))
    c.add("gfr5_a0", sec, "GFR5: the backward step a0 is least negative at alpha = 1",
          f"alpha of the least |a0| on [0, 2] = {amin:.3f} (grid step {step:.3f})",
          rule_at_most(abs(amin - 1), step), "within one grid step of 1")
    al, em, pm = sc.scan_gfr5()
    shown = [0.0, 0.3, 0.5, 1.0]  # FR and the alphas of the paper's figures
    for name, x0, y in (("energy", 0.5, em), ("precession", 1.0, abs(pm))):
        j = int(np.argmin(y))
        v0 = y[np.argmin(abs(al - x0))]
        what = ("the energy error height is lowest" if name == "energy" else
                "the precession error is smallest")
        c.add(f"gfr5_least_{name}", sec, f"GFR5: {what} at alpha = {x0:g}",
              f"least on the scan at alpha = {al[j]:.3f}; value at {x0:g} over the least = "
              f"{g7(v0 / y[j])}",
              rule_least_at(x0, al[j], v0, y[j], [o for o in shown if o != x0]),
              f"least nearer to {x0:g} than to the other alphas shown "
              f"({', '.join(f'{o:g}' for o in shown if o != x0)}), value within "
              f"x{1 + CONVERGED:g} of the least")
    r = max(reldiff(s.at("GFR5(0)", k), s.at("FR", k)) for k in ("emax", "pP"))
    ro = roundoff(s, ["FR", "GFR5(0)"])
    c.add("gfr5_0_fr", sec, "GFR5 at alpha = 0 reproduces FR", "largest relative difference "
          f"of the coefficients, GFR5(0) vs FR = {r:.3g}", rule_at_most(r, ro),
          f"<= {ro:.2g} (round-off: u x steps / (eps^4 x the smaller coefficient))")
    c.more("a5_c_prec", sec, "A5's precession error more than 4 times smaller than C's",
           s.P("C") / s.P("A5"), 4, "ratio C/A5")
    c.about("a5_gfr5_prec", sec, "A5's precession error 200 times smaller than "
            "GFR5(alpha = 1)'s", s.P("GFR5(1)") / s.P("A5"), 200, "ratio GFR5(1)/A5")
    d = sc.distances("back5f")
    c.more("back5f", sec, "GFR5: alpha 0.3 -> 1 shrinks the off-trajectory triangle "
           "(Fig. back5f)", d["GFR5(0.3)"] / d["GFR5(1)"], 1,
           "max distance from the orbit, GFR5(0.3)/GFR5(1)")
    c.about("bm_c_energy", sec, "BM's energy error comparable to C's", s.E("BM") / s.E("C"),
            1, "ratio of the max heights BM/C")
    c.about("bm_a6_energy", sec, "BM's maximum energy error height ~4x that of A6",
            s.E("BM") / s.E("A6"), 4, "ratio BM/A6")
    c.about("bm_a6_prec", sec, "BM's precession error two orders of magnitude larger than "
            "A6's", s.P("BM") / s.P("A6"), 100, "ratio BM/A6")
    c.about("bm_c_prec", sec, "BM's precession error ~20x that of C", s.P("BM") / s.P("C"),
            20, "ratio BM/C")
    c.close("a61_a6_energy_curve", sec, "A6' energy error nearly indistinguishable from A6's",
            s, "A6'", "A6")
    c.more("a61_a6_prec", sec, "A6' precession error much larger than A6's",
           s.P("A6'") / s.P("A6"), FACTOR, "ratio A6'/A6")
    c.more("a61_bm_prec", sec, "A6' precession error still smaller than BM's",
           s.P("BM") / s.P("A6'"), 1, "ratio BM/A6'")
    nonfwd = ["FR", "M1", "M1(-1/24)"] + m2 + ["GFR5(0.3)", "GFR5(0.5)", "GFR5(1)"]
    for key, name in (("E", "energy"), ("P", "precession")):
        f = getattr(s, key)
        best = min(nonfwd, key=f)
        r = f(best) / f("BM")
        note = ""
        if rule_more(r) != HOLDS:
            better = [m for m in nonfwd if f(m) < f("BM")]
            note = (f"; the paper is wrong here: {', '.join(better)} "
                    f"{'has' if len(better) == 1 else 'have'} a smaller {name} error than BM")
        c.more(f"bm_superior_{name}", sec, f"BM is superior among the paper's non-forward "
               f"methods ({name})", r, 1, f"best other non-forward ({best}) over BM", note)
    for key, name in (("E", "energy"), ("P", "precession")):
        f = getattr(s, key)
        c.more(f"bm_mf_{name}", sec, f"BM's momentum-first form has much larger errors "
               f"({name})", f("BM-mf") / f("BM"), FACTOR, "ratio BM-mf/BM")

    sec = "1, 5. Introduction and conclusions"
    for key, name in (("E", "energy"), ("P", "precession")):
        f = getattr(s, key)
        c.more(f"order4_{name}", sec, f"fourth-order forward algorithms are far more accurate "
               f"than second-order ones ({name}, A against T2 at the same step)",
               f("T2") / f("A"), FACTOR,
               "ratio T2/A of the errors (coefficient ratio, both scaled by eps^4)")
    for key, name in (("E", "energy"), ("P", "precession")):
        f = getattr(s, key)
        c.more(f"rkn_{name}", sec, f"forward algorithms are superior to Runge-Kutta-Nystrom "
               f"on the Kepler problem ({name}, A against RKN, three evaluations each)",
               f("RKN") / f("A"), 1, "ratio RKN/A")
    cases = []
    for fam in SHRINKING:
        for a, b in zip(fam[:-1], fam[1:]):
            re_, rp = s.E(a) / s.E(b), s.P(a) / s.P(b)
            v = rule_all([rule_more(re_), rule_more(rp)])
            cases.append((a, b, v))
            c.add(f"shrink:{a}->{b}", sec, f"non-forward {a} -> {b} (smaller backward step) "
                  "improves both errors", f"ratios {a}/{b}: energy {g7(re_)}, precession "
                  f"{g7(rp)}", v, f"both > {g7(TIE)} (TIE)")
    bad = [f"{a} -> {b}" for a, b, v in cases if v != HOLDS]
    c.add("shrink_all", sec, "in all cases studied, non-forward integrators improve when "
          "their negative time steps shrink (every step along M1, M2 and FR -> GFR5(alpha) "
          "of the paper)", f"{len(cases) - len(bad)} of {len(cases)} cases improve both "
          "errors" + (f"; not: {', '.join(bad)}" if bad else ""),
          rule_all([v for a, b, v in cases]), "every case above holds")
    mins = []
    for scene in sc.point_scenes():   # the figures with forward and non-forward methods
        d = sc.distances(scene)
        fw = [m for m in d if m in s.d and s.d[m]["forward"]]
        nf = [m for m in d if m in s.d and not s.d[m]["forward"] and m != "RKN"]
        if fw and nf:
            mins.append((min(d[m] for m in nf) / max(d[m] for m in fw), scene))
    w = min(mins)
    c.more("closer", sec, "forward integrators evaluate the force closer to the trajectory "
           "than non-forward ones (every force-point figure)", w[0], 1,
           f"least over the figures of (nearest non-forward max distance)/(farthest forward "
           f"max distance) ({w[1]})")
    band = TIE ** 0.25
    for nf, fw in EVAL_PAIRS:
        n_nf = s.d[nf]["nf"] + s.d[nf]["ng"]
        n_fw = s.d[fw]["nf"] + s.d[fw]["ng"]
        r = (s.P(nf) / s.P(fw)) ** 0.25 * n_nf / n_fw
        c.add(f"evals:{nf}/{fw}", sec, f"to reach the same precession error, non-forward {nf} "
              f"needs more evaluations than forward {fw} (loss of efficiency)",
              f"evaluation ratio (|prec| ratio)^(1/4) x evaluations per step ({n_nf}/{n_fw}) "
              f"= {g7(r)}", rule_more(r, 1, band),
              f"> {g7(band)} (TIE^(1/4)); tie within [{g7(1 / band)}, {g7(band)}]")
    return c


def verdict_text(v):
    return {HOLDS: "yes", FAILS: "**does not hold**", TIE_VERDICT: "**tie**"}[v]


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "out"
    md = sys.argv[2] if len(sys.argv) > 2 else os.path.join("doc", "results.md")
    s = Summary(os.path.join(out, "results.h5"))
    claims = build_claims(s, SceneData(out))
    L = render(s, claims)
    write_atomic(md, L)
    count = {v: sum(1 for r in claims.rows if r[4] == v) for v in (HOLDS, FAILS, TIE_VERDICT)}
    print(f"[report] {md}: {len(s.labels)} methods, {count[HOLDS]}/{len(claims.rows)} claims "
          f"hold, {count[FAILS]} do not, {count[TIE_VERDICT]} ties")
    for key, sec, claim, measured, verdict, rule in claims.rows:
        if verdict != HOLDS:
            print(f"[report]   {verdict}: {claim}: {measured}")


def render(s, claims):
    """The page's lines."""
    L = ["# Results: the paper's study, measured", "",
         f"The study of {PAPER}, repeated by `bash scripts/main.sh`: `fsym-study` writes the "
         "HDF5 files, `scripts/report_results.py` renders this page from them (rendering the "
         "same files again gives the same text; nothing here is edited by hand). Git commit "
         f"that made the numbers: `{s.commit}`; compiler: {s.compiler}.", "",
         f"Orbit: q = ({s.q0[0]:g}, {s.q0[1]:g}), v = ({s.v0[0]:g}, {s.v0[1]:g}) (e = 0.9), "
         f"period P = {g7(s.period)}. Every run uses compensated (Kahan) summation. Energy "
         "coefficient: (E(t) - E0)/(E0 eps^4), the maximum of its absolute value over one "
         "period; precession coefficient: the signed rotation angle of the Laplace-Runge-Lenz "
         "vector at t = P, measured against the start vector (atan2(A0 x A, A0 . A)), divided "
         "by eps^4, counter-clockwise positive. eps is in time units.", "",
         "## Per method, eps = P/5000 (convergence: the same at eps = P/10000)", "",
         f"A coefficient counts as converged when its relative difference between eps and "
         f"eps/2 is at most {CONVERGED:g}. GFR5(0) is Forest-Ruth written as GFR5; M2(t1*) "
         f"is M2 at the zero of its precession at t = P, t1* = {s.t1zero:.9f}.", "",
         "| method | forward | forces/step | gradients/step | max abs energy coeff | "
         "rel. diff eps/2 | precession coeff at P | rel. diff eps/2 | converged |",
         "|---|---|---|---|---|---|---|---|---|"]
    bad = []
    for m in s.labels:
        d = s.d[m]
        re_ = reldiff(s.at(m, "emax", 5000), s.at(m, "emax", 10000))
        rp = reldiff(s.at(m, "pP", 5000), s.at(m, "pP", 10000))
        conv = [w for w, r in (("energy", re_), ("precession", rp)) if r > CONVERGED]
        if conv:
            bad.append(f"{m} ({', '.join(conv)})")
        L.append(f"| {m} | {'yes' if d['forward'] else 'no'} | {d['nf']} | {d['ng']} | "
                 f"{g7(s.at(m, 'emax'))} | {re_:.2e} | {g7(s.at(m, 'pP'))} | {rp:.2e} | "
                 f"{'no: ' + ', '.join(conv) if conv else 'yes'} |")
    count = {v: sum(1 for r in claims.rows if r[4] == v) for v in (HOLDS, FAILS, TIE_VERDICT)}
    L += ["", "Not converged at eps = P/5000: " + ("; ".join(bad) if bad else "none") + ". "
          "T2 is second order (its coefficients scale as eps^-2); RKN's energy is not "
          "symplectic and keeps falling with the step (see the claims); SRKN6b's precession "
          "coefficient is small and still moving at this step; M2(t1*)'s precession is zero "
          "by construction at P/5000 (t1* is tuned there), so its relative difference means "
          "nothing.", "",
          "## The paper's claims", "",
          "Every comparative statement of the paper, section by section, each tested on the "
          "comparison the paper itself makes (the methods of the figure the statement is "
          "about), with the measured numbers (eps = P/5000 unless stated). Energy heights are "
          "the max abs energy coefficient over one period, precession the abs coefficient at "
          "t = P; curves are the coefficients after every step of the first period. "
          "Force-point distances are measured in the force-point scenes (eps = P/400, both "
          "steps of each scene; the figures back4f, back4f2 and back5f show the second step, "
          "as the paper's do), from each point to the exact orbit. The tolerances follow from the wording and from two "
          "numbers:", "",
          f"- the convergence criterion above, C = {CONVERGED:g}: a coefficient is known to a "
          f"factor 1 + C, a ratio of two to TIE = (1 + C)^2 = {g7(TIE)};",
          f"- F = {FACTOR:g}, the reading of a number stated off a figure ('about k times').",
          "",
          "The rules: 'about k times', 'comparable' hold when the ratio lies in [k/F, k F]; "
          "'larger', 'smaller', 'improves', 'closer' when the ratio, oriented as the "
          "statement, exceeds TIE; 'much larger', 'far' when it exceeds F TIE; 'more than "
          "k times' when it exceeds k TIE; a ratio within a factor TIE of the threshold is "
          "a **tie** (the data cannot tell), below it the claim does not hold. Curves "
          f"'closely match' or are 'nearly indistinguishable' when their relative L2 "
          f"difference is at most 2 C = {CLOSE:g} (two converged curves), 'similar' when at "
          f"most 1 - 1/F = {g7(LIKE)} (what rescaling one curve by F gives). 'Converged' is "
          "the criterion C itself; 'lowest at x' on a scan needs the scan's minimiser nearer "
          "to x than to the other values the paper shows and the value at x within 1 + C of "
          "the least; 'reproduces' means equal to round-off. Evaluations count a force "
          "gradient as one evaluation (the paper's count: AN uses N - 1 forces and one force "
          "gradient, 'or N force evaluations using extrapolation'); to the same error a "
          "fourth-order method needs (error ratio)^(1/4) times the steps, so that ratio is "
          "known to TIE^(1/4). A general statement ('in all cases') holds when every case "
          "the paper shows holds, counter-cases included.", "",
          "| section | claim (paper) | measured | rule | holds |", "|---|---|---|---|---|"]
    for key, sec, claim, measured, verdict, rule in claims.rows:
        L.append(f"| {sec} | {claim} | {measured} | {rule} | {verdict_text(verdict)} |")
    L += ["", f"{count[HOLDS]} of {len(claims.rows)} statements hold by these rules; "
          f"{count[FAILS]} do not (marked **does not hold**) and {count[TIE_VERDICT]} are "
          "ties (marked **tie**: the measured difference is within what the convergence "
          "criterion can tell).", "", "## References", ""]
    L += [f"- {r}" for r in REFERENCES]
    return L


if __name__ == "__main__":
    main()
