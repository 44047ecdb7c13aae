#!/usr/bin/env python3
"""The claim rules of scripts/report_results.py can fail.

A synthetic study (every number chosen by hand, no file read) on which every claim row of
doc/results.md holds; then, for every row, a planted counter-example (one number changed)
that must be reported as "does not hold", and a few planted ties that must be reported as
ties. A rule loosened until it cannot fail, a row added without a counter-example here, or a
tie reported as a difference makes this test fail. Exit 0 on success, 1 on failure, 77
(skipped) when numpy or h5py is missing.
"""
import copy
import os
import sys

try:
    import numpy as np
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                    "scripts"))
    import report_results as rr
except ImportError as exc:  # the report's own imports: numpy, h5py
    print(f"skipped: {exc}")
    sys.exit(77)

LADDER = [1000, 2000, 5000, 10000]
PERIOD = 75.8664
T = np.linspace(0.0, 1.0, 5000)
SPIKE = np.exp(-((T - 0.5) / 0.01) ** 2)   # an energy-curve shape: one pericentre spike
RAMP = np.minimum(1.0, np.maximum(0.0, (T - 0.48) / 0.04))  # a precession-curve shape

# method: forward, forces, gradients, E (max energy coeff.), P (precession coeff. at P)
METHODS = {
    "T2": (1, 1, 0, 12000.0, 8000.0), "FR": (0, 3, 0, 21.2, 10.86),
    "A": (1, 2, 1, 1.89, 1.0), "A'": (1, 3, 0, 1.95, 0.8), "C": (1, 3, 1, 0.27, 0.00356),
    "C'": (1, 4, 0, 0.29, 0.0038), "M1": (0, 4, 0, 13.5, 2.33),
    "M1(-1/24)": (0, 4, 0, 4.37, 0.66), "M2(-0.1)": (0, 4, 0, 7.49, 0.52),
    "M2(-0.5)": (0, 4, 0, 3.31, 0.30), "M2(-1)": (0, 4, 0, 2.73, 0.20),
    "M2(-2)": (0, 4, 0, 2.2, 0.15), "M2(t1*)": (0, 4, 0, 2.65, 1e-8),
    "GFR5(0)": (0, 3, 0, 21.2, 10.86), "GFR5(0.3)": (0, 5, 0, 1.56, 0.65),
    "GFR5(0.5)": (0, 5, 0, 1.08, 0.27), "GFR5(1)": (0, 5, 0, 0.9, 0.153),
    "A5": (1, 4, 1, 0.22, 0.000768), "BM": (0, 6, 0, 0.386, 0.0686),
    "BM-mf": (0, 6, 0, 0.88, 0.155), "A6": (1, 5, 1, 0.13, 0.00062),
    "A6'": (1, 6, 0, 0.125, 0.0134), "RKN": (0, 3, 0, 7.96, 3.34),
}
DISTANCES = {"back3f": {"FR": 0.04, "A": 0.005, "RKN": 0.01},
             "back4f": {"M1": 0.08, "M1(-1/24)": 0.02, "C": 0.005},
             "back4f2": {"M2(-0.1)": 0.05, "M2(-0.5)": 0.02, "C": 0.005},
             "back5f": {"GFR5(0.3)": 0.06, "GFR5(1)": 0.03, "A5": 0.004},
             "back6f": {"BM": 0.02, "A6": 0.004}}


class FakeSummary(rr.Summary):
    """The interface of rr.Summary on numbers set by hand."""

    def __init__(self):  # no file read: every attribute is set here
        self.ladder = LADDER
        self.t1zero = -1.1545
        self.period = PERIOD
        self.labels = list(METHODS)
        self.d, self.curves = {}, {}
        for m, (fw, nf, ng, e, p) in METHODS.items():
            self.d[m] = dict(forward=fw, symplectic=int(m != "RKN"), nf=nf, ng=ng,
                             emax=np.full(4, e), eP=np.full(4, 0.1 * e), pP=np.full(4, -p),
                             e2P=np.full(4, 0.1 * e), p2P=np.full(4, -2 * p))
            self.curves[m] = dict(energy=e * SPIKE, precession=-p * RAMP)
        rkn = self.d["RKN"]
        rkn["eP"] = np.array([8.0, 4.0, 1.6, 0.8])      # keeps falling with the step
        rkn["e2P"] = 2 * rkn["eP"]                       # one irreversible step a period


class FakeScenes:
    """The interface of rr.SceneData on numbers set by hand."""

    def __init__(self):
        self.d = copy.deepcopy(DISTANCES)
        self.alpha_a = np.linspace(0.0, 2.0, 201)
        self.a0 = -(0.5 + (self.alpha_a - 1.0) ** 2)
        self.alpha = np.linspace(0.0, 2.0, 81)
        self.em = 1.0 + (self.alpha - 0.55) ** 2
        self.pm = -(0.1 + (self.alpha - 1.0) ** 2)

    def distances(self, scene):
        return self.d[scene]

    def point_scenes(self):
        return list(self.d)

    def acoef(self):
        return self.alpha_a, self.a0

    def scan_gfr5(self):
        return self.alpha, self.em, self.pm


def scale(s, m, key, f, n=None):
    """Multiply a coefficient of method m (all of the ladder, or step n) by f."""
    k = {"E": "emax", "P": "pP"}.get(key, key)
    if n is None:
        s.d[m][k] = s.d[m][k] * f
        if k in ("emax", "pP"):
            s.curves[m]["energy" if k == "emax" else "precession"] *= f
    else:
        s.d[m][k][LADDER.index(n)] *= f


def set_ratio(s, key, a, b, r):
    """Make |coefficient(a)| / |coefficient(b)| = r by scaling a."""
    f = getattr(s, key)
    scale(s, a, key, r * f(b) / f(a))


def curve(s, m, kind, ref, f):
    s.curves[m][kind] = s.curves[ref][kind] * f


def shift_scan(sc, what, x):
    if what == "a0":
        sc.a0 = -(0.5 + (sc.alpha_a - x) ** 2)
    elif what == "em":
        sc.em = 1.0 + 0.5 * (sc.alpha - x) ** 2
    else:
        sc.pm = -(0.1 + (sc.alpha - x) ** 2)


def dist(sc, scene, m, ref, r):
    sc.d[scene][m] = r * sc.d[scene][ref]


# For every claim row: a change of one number that makes the claim false.
COUNTER = {
    "converged_P1000": lambda s, c: scale(s, "A5", "emax", 1.06, 1000),
    "rkn_energy_falls": lambda s, c: scale(s, "RKN", "eP", 0.3, 5000),
    "rkn_energy_steps": lambda s, c: scale(s, "RKN", "e2P", 1.5),
    "fr_a_energy": lambda s, c: set_ratio(s, "E", "FR", "A", 20),
    "a1_a_energy_curve": lambda s, c: curve(s, "A'", "energy", "A", 1.15),
    "rkn_prec_converges": lambda s, c: scale(s, "RKN", "pP", 1.1, 5000),
    "fr_rkn_prec": lambda s, c: set_ratio(s, "P", "FR", "RKN", 5),
    "fr_a_prec": lambda s, c: set_ratio(s, "P", "A", "FR", 1 / 20),
    "fr_a1_prec": lambda s, c: set_ratio(s, "P", "A'", "FR", 1 / 20),
    "a1_smaller_a_prec": lambda s, c: set_ratio(s, "P", "A'", "A", 1.2),
    "back3f": lambda s, c: dist(c, "back3f", "FR", "A", 1.2),
    "m1_t1_energy": lambda s, c: set_ratio(s, "E", "M1(-1/24)", "M1", 1.2),
    "m1_t1_precession": lambda s, c: set_ratio(s, "P", "M1(-1/24)", "M1", 1.2),
    "c1_like_c_energy": lambda s, c: curve(s, "C'", "energy", "C", 1.6),
    "c1_like_c_precession": lambda s, c: curve(s, "C'", "precession", "C", 0.5),
    "back4f": lambda s, c: dist(c, "back4f", "M1", "M1(-1/24)", 0.8),
    "m2_over_m1_energy": lambda s, c: set_ratio(s, "E", "M1(-1/24)", "M2(-2)", 1.3),
    "m2_over_m1_precession": lambda s, c: set_ratio(s, "P", "M1(-1/24)", "M2(-2)", 1.3),
    "m2_05_energy": lambda s, c: set_ratio(s, "E", "M2(-0.5)", "M2(-0.1)", 1.2),
    "m2_05_precession": lambda s, c: set_ratio(s, "P", "M2(-0.5)", "M2(-0.1)", 1.2),
    "back4f2": lambda s, c: dist(c, "back4f2", "M2(-0.1)", "M2(-0.5)", 0.8),
    "m2_zero": lambda s, c: scale(s, "M2(t1*)", "p2P", 0.3 * 0.15 / 1e-8),
    "gfr5_a0": lambda s, c: shift_scan(c, "a0", 0.9),
    "gfr5_least_energy": lambda s, c: shift_scan(c, "em", 0.8),
    "gfr5_least_precession": lambda s, c: shift_scan(c, "pm", 0.7),
    "gfr5_0_fr": lambda s, c: scale(s, "GFR5(0)", "E", 1 + 1e-4),
    "a5_c_prec": lambda s, c: set_ratio(s, "P", "C", "A5", 3),
    "a5_gfr5_prec": lambda s, c: set_ratio(s, "P", "A5", "GFR5(1)", 1 / 400),
    "back5f": lambda s, c: dist(c, "back5f", "GFR5(0.3)", "GFR5(1)", 0.9),
    "bm_c_energy": lambda s, c: set_ratio(s, "E", "BM", "C", 2),
    "bm_a6_energy": lambda s, c: set_ratio(s, "E", "A6", "BM", 1 / 10),
    "bm_a6_prec": lambda s, c: set_ratio(s, "P", "A6", "BM", 1 / 1000),
    "bm_c_prec": lambda s, c: set_ratio(s, "P", "C", "BM", 1 / 100),
    "a61_a6_energy_curve": lambda s, c: curve(s, "A6'", "energy", "A6", 1.15),
    "a61_a6_prec": lambda s, c: set_ratio(s, "P", "A6'", "A6", 1.2),
    "a61_bm_prec": lambda s, c: set_ratio(s, "P", "A6'", "BM", 1.2),
    "bm_superior_energy": lambda s, c: set_ratio(s, "E", "GFR5(1)", "BM", 0.5),
    "bm_superior_precession": lambda s, c: set_ratio(s, "P", "M2(-2)", "BM", 0.5),
    "bm_mf_energy": lambda s, c: set_ratio(s, "E", "BM-mf", "BM", 1.2),
    "bm_mf_precession": lambda s, c: set_ratio(s, "P", "BM-mf", "BM", 1.2),
    "order4_energy": lambda s, c: set_ratio(s, "E", "T2", "A", 1.2),
    "order4_precession": lambda s, c: set_ratio(s, "P", "T2", "A", 1.2),
    "rkn_energy": lambda s, c: set_ratio(s, "E", "RKN", "A", 0.8),
    "rkn_precession": lambda s, c: set_ratio(s, "P", "RKN", "A", 0.8),
    "shrink_all": lambda s, c: set_ratio(s, "P", "M2(-2)", "M2(-1)", 3.3),
    "closer": lambda s, c: dist(c, "back6f", "BM", "A6", 0.8),
}
for fam in rr.SHRINKING:
    for a, b in zip(fam[:-1], fam[1:]):
        COUNTER[f"shrink:{a}->{b}"] = (lambda a, b: lambda s, c:
                                        set_ratio(s, "E", b, a, 1.29))(a, b)
for nf, fw in rr.EVAL_PAIRS:
    COUNTER[f"evals:{nf}/{fw}"] = (lambda nf, fw: lambda s, c:
                                   set_ratio(s, "P", nf, fw, 0.5))(nf, fw)

# Differences within what the data can tell: must be ties, not "holds".
TIES = {
    "evals:M2(-0.5)/C": lambda s, c: set_ratio(s, "P", "M2(-0.5)", "C", 1.017 ** 4),
    "a1_smaller_a_prec": lambda s, c: set_ratio(s, "P", "A", "A'", 1.05),
    "rkn_energy": lambda s, c: set_ratio(s, "E", "RKN", "A", 1.05),
    "shrink:M2(-1)->M2(-2)": lambda s, c: set_ratio(s, "E", "M2(-1)", "M2(-2)", 1.017),
}


def verdicts(change=None):
    s, sc = FakeSummary(), FakeScenes()
    if change:
        change(s, sc)
    return {r[0]: r for r in rr.build_claims(s, sc).rows}


def main():
    fails = []
    base = verdicts()
    for key, row in base.items():
        if row[4] != rr.HOLDS:
            fails.append(f"baseline: {key} is '{row[4]}' ({row[3]}), the synthetic study was "
                         "built for every claim to hold")
    missing = sorted(set(base) - set(COUNTER))
    fails += [f"no planted counter-example for claim row {k}" for k in missing]
    fails += [f"counter-example for a row that no longer exists: {k}"
              for k in sorted(set(COUNTER) - set(base))]
    checked = 0
    for key, change in sorted(COUNTER.items()):
        if key not in base:
            continue
        row = verdicts(change)[key]
        checked += 1
        if row[4] != rr.FAILS:
            fails.append(f"{key}: planted counter-example reported as '{row[4]}' (must be "
                         f"'{rr.FAILS}'): {row[3]}; rule {row[5]}")
    for key, change in sorted(TIES.items()):
        row = verdicts(change)[key]
        checked += 1
        if row[4] != rr.TIE_VERDICT:
            fails.append(f"{key}: planted tie reported as '{row[4]}': {row[3]}")
        elif rr.verdict_text(row[4]) == rr.verdict_text(rr.HOLDS):
            fails.append(f"{key}: a tie is rendered like a claim that holds")
    for f in fails:
        print("FAIL", f)
    print(f"{len(base)} claim rows, {len(COUNTER)} counter-examples, {len(TIES)} ties planted")
    print(f"report_rules: {checked - len(fails)} passed, {len(fails)} failed")
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
