#!/usr/bin/env python3
"""The planetary race (issue 22, item 2): REBOUND's planetary integrators against the library's
Kepler-drift methods, interleaved, on two systems; writes a table, a figure and the raw numbers.

Run by `bash scripts/planets.sh` (full mode), which installs REBOUND into the race's own virtual
environment and resolves the library command. Direct use:

    python scripts/planets_race.py [--orbits N] [--reps R] [--samples S] [--systems outer,inner]
                                   [--smoke] [--out-dir out/race] [--doc-dir doc]

Systems (heliocentric start: the Sun at the origin at rest, planets heliocentric):
  outer  Sun + Jupiter, Saturn, Uranus, Neptune, Pluto: ../shared/data/outer_solar_system.txt
         (Hairer, Lubich and Wanner, Geometric Numerical Integration, 2nd ed., Sec. I.2.4).
  inner  Sun + Mercury, Venus, Earth-Moon barycentre, Mars: data/inner_solar_system.txt
         (Standish's J2000 elements, DE405 masses; the full references are in the file).
Each run covers `--orbits` (default 10^4) orbits of the innermost planet: span T = orbits * P_in,
P_in = 2 pi sqrt(a^3 / (G (M_sun + m))) with a from the initial heliocentric two-body energy.
The steps are h = P_in / k (k an integer per method), so a run is exactly N = orbits * k steps.

Measured quantities (the same definitions bind the library side):
  maxdE      max over the S + 1 samples j = 0..S (every N/S steps, the last at the end) of
             |E_j - E_0| / |E_0|, E the total energy (kinetic + pairwise potential, G from the
             data) of the output state, in the barycentric frame. For a corrected method the
             output state is the corrected (synchronized) one; output never changes the
             continuing trajectory (REBOUND: safe_mode = 0, keep_unsynchronized = 1).
  phase_in   at t = T, the angle (radians) between the heliocentric position vector
             r = x_planet - x_sun of the innermost planet and the same vector of the reference
             solution: atan2(|r x r_ref|, r . r_ref).
  phase_out  the same for the outermost body of the file (outer: Pluto; inner: Mars).
  seconds    wall time of the stepping loop including the S samples (synchronization and energy)
             and nothing else (no start-up, no reading, no building); the minimum over the
             repetitions is used, the spread (max / min - 1) is printed.
  time per orbit  = min seconds / orbits;  ns per step = min seconds / N.
The reference solution is IAS15 (REBOUND's default epsilon, exact finish at T). A second IAS15 run
with epsilon = 1e-10 is compared with it; their difference is printed as the reference floor,
below which phase errors are not resolved.

Library side: a contract, not code of this script. For each library method M and step h the
harness runs the command given by the environment variable FSYM_RACE_CMD (default
DEFAULT_LIB_CMD below), a template split like a shell line whose tokens may contain the fields
{state} {system} {method} {h} {nsteps} {samples} {tend} {orbits} (h and tend as repr() of the
double, so they parse exactly). The command must print, among any other lines, exactly one line

    race system=S method=M h=H maxdE=X phase_in=Y phase_out=Z seconds=T orbits=N [evals=E]
         [cpu_seconds=C]

(key=value tokens separated by spaces, in any order after `race`; S and M as given; H, X, Y, Z,
T, N reals in any Fortran or C format; evals optional: force-equivalent evaluations per step with
first-same-as-last reuse, a gradient counted as one; cpu_seconds=C optional: the process CPU
time of the same loop) and exit 0. The quantities are defined as
above; the program integrates nsteps steps of size h from the initial state of the state file and
computes the phases against the reference state of the same file. The library methods are
listed in FSYM_RACE_LIB_METHODS (comma-separated; default DEFAULT_LIB_METHODS below); their steps
are those of FSYM_RACE_LIB_KS (comma-separated k; default LIB_KS below).
FSYM_RACE_MISSING, when set, says why the library side cannot run (scripts/planets.sh sets it
when fpm.toml has no fsym-planets program); the race then runs REBOUND alone.
The first library run of the race is done once untimed (a warm-up, and a check that the command
exists); if it fails, the race reports REBOUND alone and says that the library side is missing.
Nothing is ever invented for a side that did not run.

State file (one per system, written to OUT_DIR/<system>.txt before the library runs), in the
format of data/outer_solar_system.txt that app/solar/fsym_solar_data.f90 reads: `#` comments; G; the
end time T; a comment containing `(initial state`; lines `name mass x y z vx vy vz` (planets by
increasing semi-major axis, then the central body, named Sun), heliocentric start (Sun at the
origin at rest) in the inertial frame of that start; a comment containing `(reference state`;
lines `name x y z vx vy vz` with the IAS15 state at T in the same inertial frame. Reals are
written with 17 significant digits, so both sides start from the same doubles.

Interleaving: each repetition runs every contender (REBOUND's and the library's, alternating)
once, in turn; R repetitions. Progress lines every few seconds on long runs.

Outputs: DOC_DIR/planets-race.csv (raw numbers, every repetition's seconds),
DOC_DIR/planets-race-results.md (tables, reference check, the issue's targets computed from the
numbers), DOC_DIR/figures/planets-race.png and .pdf (energy and phase errors against time per
orbit). The targets: at every target accuracy 1e-6 ... 1e-13 the time per orbit of each side's
best method: per method the least of (a) the time of every run whose error is <= the target and
(b) the log-log interpolation between consecutive runs of its sweep (h decreasing) whose errors
bracket the target; a time of kind (a) is an upper bound of the crossing (marked <=). Targets
below 10x the reference floor are not measurable and are said to be.
"""
import argparse
import csv
import datetime
import math
import os
import platform
import shlex
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

DEFAULT_LIB_CMD = ('bash scripts/apps.sh fsym-planets --profile release '
                   '--flag "-std=f2008 -O2 -ffp-contract=off" -- race state={state} '
                   'system={system} method={method} h={h} nsteps={nsteps} samples={samples}')
DEFAULT_LIB_METHODS = "WH,WH+C17,WHK-M+C17,WHK-L+C17,C,C(T+V)"
LIB_KS = "7,10,14,20,28,40,56,80,112"

# REBOUND contenders: label -> (settings, steps k = P_in / h). Settings as in REBOUND 5.2.2's own
# documentation (the integrator docstrings of the installed package):
#   whfast: corrector (0 = off, 17 = 17th order), kernel ("default", "modifiedkick", "lazy"),
#           coordinates Jacobi (default), safe_mode, keep_unsynchronized;
#   saba:   type "10_6_4" = SABA(10,6,4) (Blanes et al. 2013);
#   leapfrog: order 4 (Yoshida's fourth-order composition);
#   ias15:  the reference.
REBOUND_METHODS = [
    ("WHFast", dict(integrator="whfast", corrector=0, kernel="default"),
     [10, 20, 40, 80, 160, 320]),
    ("WHFast+C17", dict(integrator="whfast", corrector=17, kernel="default"),
     [10, 14, 20, 28, 40, 56, 80, 112]),
    ("WHCKM", dict(integrator="whfast", corrector=17, kernel="modifiedkick"),
     [7, 10, 14, 20, 28, 40, 56, 80]),
    ("WHCKL", dict(integrator="whfast", corrector=17, kernel="lazy"),
     [7, 10, 14, 20, 28, 40, 56, 80]),
    ("SABA(10,6,4)", dict(integrator="saba", type="10_6_4"), [5, 7, 10, 14, 20, 28, 40]),
    ("LF4", dict(integrator="leapfrog", order=4), [50, 100, 200, 400, 800]),
]
# force-equivalent evaluations per step (H. Rein, D. Tamayo and G. Brown, MNRAS 489 (2019)
# 4632): WH 1 kick; WHCKM 1 kick with the gradient term (counted as one more); WHCKL 2 (the
# lazy kernel); SABA(10,6,4) 8 kicks (8 stages in REBOUND's integrator_saba.c); LF4 3 kicks
# (Yoshida's composition of three leapfrogs). The correctors act at output only.
REBOUND_EVALS = {"WHFast": 1, "WHFast+C17": 1, "WHCKM": 2, "WHCKL": 2, "SABA(10,6,4)": 8,
                 "LF4": 3}
TARGETS = [1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13]
TARGET_H_K = 40          # the h = P_Jupiter / 40
HEARTBEAT = 5.0          # seconds between progress lines inside a long run


def say(msg):
    print(f"[race {time.strftime('%H:%M:%S')}] {msg}", flush=True)


# ------------------------------------------------------------------------------------------
# systems
# ------------------------------------------------------------------------------------------
def _data_lines(path):
    with open(path) as f:
        for raw in f:
            line = raw.strip()
            if line:
                yield line


def load_outer(path):
    """G and the initial bodies of data/outer_solar_system.txt (the reference state of the file
    is for t = 500 000 days, not for this race's span, and is not used)."""
    section, g, bodies = 0, None, []
    for line in _data_lines(path):
        if line.startswith("#"):
            if "(initial state" in line:
                section = 3
            elif "(reference state" in line:
                section = 4
            continue
        if section == 0:
            g, section = float(line.split()[0]), 1
        elif section == 1:
            section = 2
        elif section == 3:
            t = line.split()
            bodies.append((t[0], float(t[1]), [float(v) for v in t[2:8]]))
    return g, bodies


def kepler_state(mu, a, e, inc, mean_long, varpi, node):
    """Heliocentric position and velocity of the two-body orbit with these elements (angles in
    degrees): M = L - varpi, omega = varpi - Omega; Kepler's equation by Newton's method."""
    d = math.pi / 180.0
    m_anom = math.remainder((mean_long - varpi) * d, 2.0 * math.pi)
    omega, big_o, i = (varpi - node) * d, node * d, inc * d
    ecc = m_anom if e < 0.8 else math.pi
    for _ in range(50):
        f = ecc - e * math.sin(ecc) - m_anom
        step = f / (1.0 - e * math.cos(ecc))
        ecc -= step
        if abs(step) < 1e-16:
            break
    cos_e, sin_e = math.cos(ecc), math.sin(ecc)
    b = a * math.sqrt(1.0 - e * e)
    xp, yp = a * (cos_e - e), b * sin_e
    edot = math.sqrt(mu / a ** 3) / (1.0 - e * cos_e)
    vxp, vyp = -a * sin_e * edot, b * cos_e * edot
    co, so, cO, sO, ci, si = (math.cos(omega), math.sin(omega), math.cos(big_o),
                              math.sin(big_o), math.cos(i), math.sin(i))
    p = (cO * co - sO * so * ci, sO * co + cO * so * ci, so * si)
    q = (-cO * so - sO * co * ci, -sO * so + cO * co * ci, co * si)
    return [p[j] * xp + q[j] * yp for j in range(3)] + [p[j] * vxp + q[j] * vyp for j in range(3)]


def load_inner(path):
    """G and the initial bodies from the element table of data/inner_solar_system.txt."""
    g, bodies = None, []
    for line in _data_lines(path):
        if line.startswith("#"):
            continue
        t = line.split()
        if g is None:
            g = float(t[0])
            continue
        m = 1.0 / float(t[1])
        a, e, inc, mean_long, varpi, node = (float(v) for v in t[2:8])
        bodies.append((t[0], m, kepler_state(g * (1.0 + m), a, e, inc, mean_long, varpi, node)))
    bodies.append(("Sun", 1.0, [0.0] * 6))
    return g, bodies


class System:
    """A system of the race: planets ordered by semi-major axis, the Sun, span and steps."""

    def __init__(self, name, title, g, bodies, orbits):
        self.name, self.title, self.g = name, title, g
        sun = [b for b in bodies if b[0] == "Sun"]
        if len(sun) != 1:
            raise ValueError(f"{name}: need exactly one body named Sun")
        self.m_sun = sun[0][1]
        if any(abs(v) > 0.0 for v in sun[0][2]):
            raise ValueError(f"{name}: the Sun must start at the origin at rest (heliocentric)")
        planets = [b for b in bodies if b[0] != "Sun"]
        semi = [self._semi_major(b) for b in planets]
        order = sorted(range(len(planets)), key=lambda j: semi[j])
        self.planets = [planets[j] for j in order]
        self.semi = [semi[j] for j in order]
        a_in, m_in = self.semi[0], self.planets[0][1]
        self.p_in = 2.0 * math.pi * math.sqrt(a_in ** 3 / (g * (self.m_sun + m_in)))
        self.orbits = orbits
        self.span = orbits * self.p_in
        self.inner_name, self.outer_name = self.planets[0][0], self.planets[-1][0]

    def _semi_major(self, body):
        m, s = body[1], body[2]
        mu = self.g * (self.m_sun + m)
        r = math.sqrt(sum(v * v for v in s[:3]))
        v2 = sum(v * v for v in s[3:])
        return 1.0 / (2.0 / r - v2 / mu)

    def nsteps(self, k):
        n = self.orbits * k
        if abs(n - round(n)) > 1e-9:
            raise ValueError(f"orbits * k = {n} is not an integer")
        return int(round(n))

    def step(self, k):
        return self.span / self.nsteps(k)

    def write_state(self, path, ref):
        """The state file of the library contract (see the module docstring)."""
        names = [p[0] for p in self.planets] + ["Sun"]
        with open(path + ".tmp", "w") as f:
            f.write(f"# Planetary race, system '{self.name}': {self.title}\n")
            f.write("# Written by scripts/planets_race.py. Units: AU, days, solar masses.\n")
            f.write("# Heliocentric start: the Sun at the origin at rest; the reference state is\n")
            f.write("# IAS15's (REBOUND) at t_end in the same inertial frame.\n")
            f.write(f"# innermost {self.inner_name}: P = {self.p_in!r} days; t_end = "
                    f"{self.orbits} orbits of it\n#\n# G\n{self.g!r}\n# t_end_days\n"
                    f"{self.span!r}\n")
            f.write("# body mass x y z vx vy vz   (initial state, t = 0)\n")
            for name, m, s in self.planets + [("Sun", self.m_sun, [0.0] * 6)]:
                f.write(f"{name} {m:.17g} " + " ".join(f"{v:.17g}" for v in s) + "\n")
            f.write("# body x y z vx vy vz   (reference state, t = t_end)\n")
            for j, name in enumerate(names):
                f.write(f"{name} " + " ".join(f"{v:.17g}" for v in ref[j]) + "\n")
        os.replace(path + ".tmp", path)


def load_systems(names, orbits):
    shared = os.path.join(ROOT, "..", "shared", "data", "outer_solar_system.txt")
    if not os.path.exists(shared):
        shared = os.path.join(ROOT, "data", "outer_solar_system.txt")
    out = []
    for name in names:
        if name == "outer":
            g, b = load_outer(shared)
            out.append(System("outer", "Sun + Jupiter, Saturn, Uranus, Neptune, Pluto "
                              "(Hairer, Lubich & Wanner, GNI Sec. I.2.4)", g, b, orbits))
        elif name == "inner":
            g, b = load_inner(os.path.join(ROOT, "data", "inner_solar_system.txt"))
            out.append(System("inner", "Sun + Mercury, Venus, Earth-Moon barycentre, Mars "
                              "(Standish J2000 elements, DE405 masses)", g, b, orbits))
        else:
            raise SystemExit(f"unknown system {name!r} (outer, inner)")
    return out


# ------------------------------------------------------------------------------------------
# REBOUND side
# ------------------------------------------------------------------------------------------
def make_sim(rebound, sysd, settings, h):
    return new_sim(rebound, sysd.g, sysd.m_sun, [(m, s) for _, m, s in sysd.planets],
                   settings, h)


def new_sim(rebound, g, m_sun, planets, settings, h):
    """A REBOUND simulation: the Sun at rest at the origin, planets [(m, [x y z vx vy vz])]
    heliocentric, moved to the barycentre, the integrator set from `settings`."""
    sim = rebound.Simulation()
    sim.G = g
    sim.add(m=m_sun)
    for m, s in planets:
        sim.add(m=m, x=s[0], y=s[1], z=s[2], vx=s[3], vy=s[4], vz=s[5])
    sim.move_to_com()
    cfg = dict(settings)
    sim.integrator = cfg.pop("integrator")
    for key, val in cfg.items():
        setattr(sim.integrator, key, val)
    if str(sim.integrator) in ("whfast", "saba"):
        sim.integrator.safe_mode = 0
        sim.integrator.keep_unsynchronized = 1
    sim.dt = h
    return sim


def helio(sim):
    """Heliocentric positions of the planets, (n, 3)."""
    ps = sim.particles
    sun = np.array(ps[0].xyz)
    return np.array([np.array(p.xyz) - sun for p in ps[1:]])


def inertial_state(sim, com0):
    """Every body's state in the inertial frame of the heliocentric start, planets then Sun."""
    x0, v0, t = com0[0], com0[1], sim.t
    ps = sim.particles
    rows = []
    for p in list(ps[1:]) + [ps[0]]:
        x = np.array(p.xyz) + x0 + v0 * t
        v = np.array(p.vxyz) + v0
        rows.append(list(x) + list(v))
    return rows


def phase_angle(r, r_ref):
    return math.atan2(float(np.linalg.norm(np.cross(r, r_ref))), float(np.dot(r, r_ref)))


def centre_of_mass(sysd):
    ms = np.array([sysd.m_sun] + [p[1] for p in sysd.planets])
    xs = np.array([[0.0] * 6] + [p[2] for p in sysd.planets])
    c = (ms[:, None] * xs).sum(axis=0) / ms.sum()
    return c[:3], c[3:]


def rebound_reference(rebound, sysd, samples, epsilon=None):
    """IAS15 from 0 to T, energy sampled at S + 1 times; returns heliocentric end positions,
    the inertial end state, max |dE/E|, seconds and steps."""
    sim = make_sim(rebound, sysd, dict(integrator="ias15"), 1.0)
    if epsilon is not None:
        sim.integrator.epsilon = epsilon
    e0, maxde = sim.energy(), 0.0
    t0 = last = time.perf_counter()
    for j in range(1, samples + 1):
        sim.integrate(sysd.span * j / samples, exact_finish_time=1)
        maxde = max(maxde, abs((sim.energy() - e0) / e0))
        now = time.perf_counter()
        if now - last > HEARTBEAT:
            say(f"  {sysd.name} IAS15 reference: {100.0 * j / samples:.0f}% "
                f"({now - t0:.0f} s)")
            last = now
    secs = time.perf_counter() - t0
    return dict(helio=helio(sim), state=inertial_state(sim, centre_of_mass(sysd)),
                maxdE=maxde, seconds=secs, steps=int(sim.steps_done))


def rebound_run(rebound, sysd, label, settings, k, samples, ref):
    n = sysd.nsteps(k)
    if n % samples:
        raise ValueError(f"N = {n} is not a multiple of the {samples} samples")
    per = n // samples
    sim = make_sim(rebound, sysd, settings, sysd.step(k))
    e0, maxde = sim.energy(), 0.0
    c0 = time.process_time()
    t0 = last = time.perf_counter()
    for j in range(samples):
        sim.steps(per)
        sim.synchronize()
        maxde = max(maxde, abs((sim.energy() - e0) / e0))
        now = time.perf_counter()
        if now - last > HEARTBEAT:
            say(f"  {sysd.name} {label} k={k}: {100.0 * (j + 1) / samples:.0f}%")
            last = now
    secs = time.perf_counter() - t0
    cpu = time.process_time() - c0
    if abs(sim.t - sysd.span) > 1e-9 * sysd.span:
        raise RuntimeError(f"{label}: ended at t = {sim.t}, not {sysd.span}")
    r = helio(sim)
    return dict(maxdE=maxde, phase_in=phase_angle(r[0], ref["helio"][0]),
                phase_out=phase_angle(r[-1], ref["helio"][-1]), seconds=secs,
                cpu_seconds=cpu)


# ------------------------------------------------------------------------------------------
# library side (an external command; see the docstring)
# ------------------------------------------------------------------------------------------
REQUIRED = ("system", "method", "h", "maxdE", "phase_in", "phase_out", "seconds", "orbits")


def parse_race_line(text):
    """The one `race key=value ...` line of the contract, as a dict; None if absent."""
    found = [ln for ln in text.splitlines() if ln.strip().startswith("race ")]
    if len(found) != 1:
        return None
    out = {}
    for tok in found[0].split()[1:]:
        if "=" in tok:
            key, val = tok.split("=", 1)
            out[key] = val
    if any(k not in out for k in REQUIRED):
        return None
    for key in ("h", "maxdE", "phase_in", "phase_out", "seconds", "orbits", "evals",
                "cpu_seconds"):
        if key in out:
            out[key] = float(out[key].lower().replace("d", "e"))
    return out


def library_run(template, sysd, method, k, samples, state_path, timeout):
    fields = dict(state=state_path, system=sysd.name, method=method, h=repr(sysd.step(k)),
                  nsteps=sysd.nsteps(k), samples=samples, tend=repr(sysd.span),
                  orbits=sysd.orbits)
    argv = [tok.format(**fields) for tok in shlex.split(template)]
    # the clock starts before the process does: on a loaded machine the child may run for a
    # while before Popen returns to this process
    t0 = time.perf_counter()
    try:
        proc = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                text=True, cwd=ROOT)
    except OSError as exc:
        return None, f"cannot start {argv[0]!r}: {exc}"
    while True:
        try:
            out, err = proc.communicate(timeout=HEARTBEAT)
            break
        except subprocess.TimeoutExpired:
            if time.perf_counter() - t0 > timeout:
                proc.kill()
                proc.communicate()
                return None, f"timed out after {timeout} s"
            say(f"  {sysd.name} library {method} k={k}: running "
                f"({time.perf_counter() - t0:.0f} s)")
    wall = time.perf_counter() - t0
    if proc.returncode != 0:
        tail = (err or out).strip().splitlines()[-3:]
        return None, f"exit {proc.returncode}: " + " / ".join(t.strip() for t in tail)
    rec = parse_race_line(out)
    if rec is None:
        return None, "no valid `race ...` line in its output"
    if rec["system"] != sysd.name or rec["method"] != method:
        return None, f"line names {rec['system']}/{rec['method']}, not {sysd.name}/{method}"
    if abs(rec["h"] - sysd.step(k)) > 1e-12 * sysd.step(k):
        return None, f"line says h={rec['h']!r}, asked {sysd.step(k)!r}"
    if abs(rec["orbits"] - sysd.orbits) > 1e-3 * sysd.orbits:
        return None, f"line says orbits={rec['orbits']!r}, the span is {sysd.orbits} orbits"
    if not 0.0 < rec["seconds"] <= wall:
        return None, f"line says seconds={rec['seconds']!r}, the command took {wall:.3g} s"
    return rec, None


# ------------------------------------------------------------------------------------------
# the race
# ------------------------------------------------------------------------------------------
class Contender:
    def __init__(self, side, method, k, settings=None, evals=None):
        self.side, self.method, self.k, self.settings, self.evals = side, method, k, settings, \
            evals
        self.seconds, self.cpu, self.acc, self.error = [], [], None, None
        self.mismatch = False

    def record(self, rec):
        acc = (rec["maxdE"], rec["phase_in"], rec["phase_out"])
        if self.acc is None:
            self.acc = acc
        elif acc != self.acc:
            self.mismatch = True
        self.seconds.append(rec["seconds"])
        if rec.get("cpu_seconds") is not None:
            self.cpu.append(rec["cpu_seconds"])
        if rec.get("evals") is not None:
            self.evals = rec["evals"]


def interleave(a, b):
    out = []
    for j in range(max(len(a), len(b))):
        out += a[j:j + 1] + b[j:j + 1]
    return out


def run_system(rebound, sysd, args, lib, out_dir):
    say(f"{sysd.name}: {sysd.title}; innermost {sysd.inner_name} P = {sysd.p_in:.6g} d, "
        f"span {sysd.span:.6g} d = {sysd.orbits} orbits; outermost {sysd.outer_name}")
    ref = rebound_reference(rebound, sysd, args.samples)
    say(f"{sysd.name}: IAS15 reference: {ref['steps']} steps, {ref['seconds']:.1f} s, "
        f"max|dE/E| = {ref['maxdE']:.2e}")
    ref2 = rebound_reference(rebound, sysd, args.samples, epsilon=1e-10)
    floor = (phase_angle(ref2["helio"][0], ref["helio"][0]),
             phase_angle(ref2["helio"][-1], ref["helio"][-1]))
    say(f"{sysd.name}: IAS15 eps=1e-10 against the reference: phase_in {floor[0]:.2e}, "
        f"phase_out {floor[1]:.2e} (the reference floor)")
    state_path = os.path.join(out_dir, f"{sysd.name}.txt")
    sysd.write_state(state_path, ref["state"])
    rb = [Contender("REBOUND", lab, k, settings=st, evals=REBOUND_EVALS[lab])
          for lab, st, ks in REBOUND_METHODS for k in ks
          if not args.only or lab in args.only]
    lb = []
    if lib["missing"] is None:
        lb = [Contender("library", m, k) for m in lib["methods"] for k in lib["ks"]]
        if not lib["warmed"]:
            c = lb[0]
            say(f"library warm-up: {c.method} k={c.k} (untimed; checks the command)")
            rec, err = library_run(lib["cmd"], sysd, c.method, c.k, args.samples, state_path,
                                   args.timeout)
            if err:
                lib["missing"] = err
                say(f"library side missing: {err}")
                lb = []
            lib["warmed"] = True
    contenders = interleave(rb, lb)
    t_start = time.perf_counter()
    for rep in range(args.reps):
        for c in contenders:
            if c.error:
                continue
            if c.side == "REBOUND":
                rec = rebound_run(rebound, sysd, c.method, c.settings, c.k, args.samples, ref)
            else:
                rec, err = library_run(lib["cmd"], sysd, c.method, c.k, args.samples,
                                       state_path, args.timeout)
                if err:
                    c.error = err
                    say(f"  library {c.method} k={c.k} failed: {err}")
                    continue
            c.record(rec)
            say(f"{sysd.name} rep {rep + 1}/{args.reps} {c.side:7s} {c.method:14s} "
                f"h=P/{c.k:<4d} maxdE={rec['maxdE']:.2e} phase_in={rec['phase_in']:.2e} "
                f"phase_out={rec['phase_out']:.2e} {1e6 * rec['seconds'] / sysd.orbits:8.2f} "
                f"us/orbit  ({time.perf_counter() - t_start:.0f} s)")
    return dict(system=sysd, ref=ref, ref2=ref2, floor=floor, contenders=contenders,
                state=state_path)


# ------------------------------------------------------------------------------------------
# analysis and output
# ------------------------------------------------------------------------------------------
def tpo(c, sysd):
    return min(c.seconds) / sysd.orbits


def cpu_tpo(c, sysd):
    return f"{1e6 * min(c.cpu) / sysd.orbits:.2f}" if c.cpu else ""


def spread(c):
    return max(c.seconds) / min(c.seconds) - 1.0


def sweeps(res, side, metric):
    """{method: [(time per orbit, error)] in sweep order (h decreasing)} for one side."""
    sysd, idx = res["system"], {"maxdE": 0, "phase_in": 1, "phase_out": 2}[metric]
    out = {}
    for c in sorted(res["contenders"], key=lambda c: c.k):
        if c.side == side and c.seconds and not c.error:
            out.setdefault(c.method, []).append((tpo(c, sysd), c.acc[idx]))
    return out


def time_at(points, target):
    """Least time per orbit at which a sweep (in order of decreasing h) reaches `target`:
    (time, raw) or None. Candidates: every run whose error is <= target, and the log-log
    interpolation between consecutive runs whose errors bracket it; raw is True when the least
    is a run's own time (then the true crossing may be cheaper: an upper bound)."""
    cands = [(t, True) for t, e in points if e <= target]
    for (t0, e0), (t1, e1) in zip(points, points[1:]):
        if e0 > target >= e1 > 0.0:
            f = (math.log(e0) - math.log(target)) / (math.log(e0) - math.log(e1))
            cands.append((math.exp(math.log(t0) + f * (math.log(t1) - math.log(t0))), False))
    return min(cands) if cands else None


def best_at(sw, target):
    best = None
    for method, pts in sw.items():
        r = time_at(pts, target)
        if r is not None and (best is None or r[0] < best[1]):
            best = (method, r[0], r[1])
    return best


def fmt_t(us, bounded):
    return ("<= " if bounded else "") + f"{us:.3g}"


def targets_table(res, metric, lib_missing, floor):
    lines = [f"| target | REBOUND best | us/orbit | library best | us/orbit | ratio | "
             f"<= 0.8? |", "|---:|---|---:|---|---:|---:|---|"]
    rb, lb = sweeps(res, "REBOUND", metric), sweeps(res, "library", metric)
    for target in TARGETS:
        if floor is not None and target < 10.0 * floor:
            lines.append(f"| {target:.0e} | below 10x the reference floor ({floor:.1e}) | | | "
                         f"| | not measurable |")
            continue
        r, lbest = best_at(rb, target), best_at(lb, target)
        rs = (r[0], fmt_t(1e6 * r[1], r[2])) if r else ("not reached", "")
        if lib_missing:
            ls, ratio, verdict = ("library side missing", ""), "", "not measured"
        elif lbest:
            ls = (lbest[0], fmt_t(1e6 * lbest[1], lbest[2]))
            if r:
                q = lbest[1] / r[1]
                ratio, verdict = f"{q:.2f}", ("yes" if q <= 0.8 else f"no ({q / 0.8:.2f}x over)")
                if lbest[2] or r[2]:
                    verdict += " (a bound)"
            else:
                ratio, verdict = "", "yes (REBOUND does not reach it)"
        else:
            ls, ratio, verdict = ("not reached", ""), "", ("no" if r else "neither side")
        lines.append(f"| {target:.0e} | {rs[0]} | {rs[1]} | {ls[0]} | {ls[1]} | {ratio} | "
                     f"{verdict} |")
    return lines


def write_csv(path, results):
    with open(path + ".tmp", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["system", "side", "method", "k", "h_days", "nsteps", "orbits",
                    "evals_per_step", "maxdE", "phase_in", "phase_out", "seconds_min",
                    "seconds_max", "us_per_orbit", "ns_per_step", "seconds_all",
                    "cpu_seconds_min", "cpu_seconds_all", "error"])
        for res in results:
            sysd = res["system"]
            w.writerow([sysd.name, "reference", "IAS15", "", "", res["ref"]["steps"],
                        sysd.orbits, "", f"{res['ref']['maxdE']:.6e}", 0.0, 0.0,
                        f"{res['ref']['seconds']:.6f}", f"{res['ref']['seconds']:.6f}",
                        f"{1e6 * res['ref']['seconds'] / sysd.orbits:.6g}", "",
                        f"{res['ref']['seconds']:.6f}", "", "", ""])
            for c in res["contenders"]:
                n = sysd.nsteps(c.k)
                if c.seconds:
                    row = [f"{c.acc[0]:.6e}", f"{c.acc[1]:.6e}", f"{c.acc[2]:.6e}",
                           f"{min(c.seconds):.6f}", f"{max(c.seconds):.6f}",
                           f"{1e6 * tpo(c, sysd):.6g}", f"{1e9 * min(c.seconds) / n:.6g}",
                           ";".join(f"{s:.6f}" for s in c.seconds),
                           f"{min(c.cpu):.6f}" if c.cpu else "",
                           ";".join(f"{s:.6f}" for s in c.cpu)]
                else:
                    row = [""] * 10
                w.writerow([sysd.name, c.side, c.method, c.k, repr(sysd.step(c.k)), n,
                            sysd.orbits, "" if c.evals is None else f"{c.evals:g}"] + row +
                           [c.error or ""])
    os.replace(path + ".tmp", path)


def plot(results, png, pdf):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    metrics = [("maxdE", "max |dE/E|"), ("phase_in", "phase error, innermost (rad)"),
               ("phase_out", "phase error, outermost (rad)")]
    fig, axes = plt.subplots(len(results), 3, figsize=(15, 4.6 * len(results)), squeeze=False)
    markers = "os^vD<>ph*"
    for row, res in zip(axes, results):
        sysd = res["system"]
        for ax, (metric, label) in zip(row, metrics):
            for side, ls in (("REBOUND", "-"), ("library", "--")):
                for j, (method, pts) in enumerate(sweeps(res, side, metric).items()):
                    x = [1e6 * t for t, _ in pts]
                    y = [max(e, 1e-17) for _, e in pts]
                    ax.loglog(x, y, ls, marker=markers[j % len(markers)], ms=4,
                              label=f"{method} ({side})")
            if metric != "maxdE":
                fl = res["floor"][0 if metric == "phase_in" else 1]
                ax.axhline(max(fl, 1e-17), color="grey", lw=0.8, ls=":",
                           label="reference floor")
            ax.set_xlabel("wall time per orbit of the innermost planet (us)")
            ax.set_ylabel(label)
            who = sysd.inner_name if metric == "phase_in" else sysd.outer_name
            ax.set_title(f"{sysd.name}: {label.split(',')[0] if metric == 'maxdE' else who}")
            ax.grid(True, which="major", alpha=0.3)
        row[0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(png, dpi=100)
    fig.savefig(pdf)
    plt.close(fig)


def cpu_name():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def git_commit():
    try:
        c = subprocess.run(["git", "rev-parse", "HEAD"], cwd=ROOT, capture_output=True,
                           text=True, check=True).stdout.strip()
        # the race's own outputs do not count as a modification of the code that made them
        dirty = subprocess.run(["git", "status", "--porcelain", "--", ".",
                                ":!doc/planets-race*", ":!doc/figures/planets-race*"],
                               cwd=ROOT, capture_output=True, text=True).stdout.strip()
        return c + (" (modified)" if dirty else "")
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def write_markdown(path, results, args, lib, info):
    w = []
    w.append("# The planetary race: results\n")
    w.append(f"<!-- generated by `{info['command']}` (scripts/planets_race.py); do not edit. "
             "Definitions and the library contract: planets-race.md -->\n")
    w.append(f"- Machine: {info['cpu']}, {os.cpu_count()} cores shared with other jobs (load "
             f"average {info['load0']} before, {info['load1']} after); Python "
             f"{platform.python_version()}, REBOUND {info['rebound']}.")
    w.append(f"- Git commit: `{info['commit']}`; date {info['date']}; whole race "
             f"{info['wall']:.0f} s.")
    w.append(f"- Each run: {args.orbits} orbits of the innermost planet, {args.samples} energy "
             f"samples; {args.reps} repetitions interleaved (each repetition runs every "
             "contender once, in turn); time = minimum over the repetitions, spread = max/min - 1; "
             "CPU us/orbit: the minimum of the process CPU time of the same loop (not used for "
             "the targets; a cross-check of the wall time on a loaded machine).")
    if lib["missing"]:
        w.append(f"- **Library side missing**: `{lib['cmd']}` failed "
                 f"({lib['missing'].replace('|', chr(92) + '|')}). Only "
                 "REBOUND's numbers are shown; no library number is invented.")
    else:
        w.append(f"- Library command: `{lib['cmd']}`; methods {', '.join(lib['methods'])}.")
    w.append("")
    for res in results:
        sysd, ref = res["system"], res["ref"]
        w.append(f"## {sysd.name}: {sysd.title}\n")
        w.append(f"Innermost {sysd.inner_name}: P = {sysd.p_in:.6f} days; span {sysd.span:.6g} "
                 f"days ({sysd.orbits} orbits); outermost {sysd.outer_name}. Reference: IAS15, "
                 f"{ref['steps']} steps, max |dE/E| {ref['maxdE']:.1e}, {ref['seconds']:.1f} s "
                 f"({1e6 * ref['seconds'] / sysd.orbits:.0f} us/orbit). Reference floor (IAS15 "
                 f"with epsilon 1e-10 against it): phase_in {res['floor'][0]:.1e}, phase_out "
                 f"{res['floor'][1]:.1e} rad.\n")
        w.append("| side | method | h = P/k | evals/step | max \\|dE/E\\| | phase_in (rad) | "
                 "phase_out (rad) | us/orbit | ns/step | spread | CPU us/orbit |")
        w.append("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
        order = {}
        for c in res["contenders"]:
            order.setdefault((c.side, c.method), len(order))
        for c in sorted(res["contenders"],
                        key=lambda c: (c.side != "REBOUND", order[(c.side, c.method)], c.k)):
            if not c.seconds:
                why = c.error.replace("|", "\\|")
                w.append(f"| {c.side} | {c.method} | {c.k} | | failed: {why} | | | | | | |")
                continue
            n = sysd.nsteps(c.k)
            ev = "" if c.evals is None else f"{c.evals:g}"
            flag = " (accuracy differed between repetitions)" if c.mismatch else ""
            w.append(f"| {c.side} | {c.method}{flag} | {c.k} | {ev} | {c.acc[0]:.2e} | "
                     f"{c.acc[1]:.2e} | {c.acc[2]:.2e} | {1e6 * tpo(c, sysd):.2f} | "
                     f"{1e9 * min(c.seconds) / n:.0f} | {100 * spread(c):.1f}% | "
                     f"{cpu_tpo(c, sysd)} |")
        w.append("")
        for metric, label, fl in (("maxdE", "max |dE/E|", None),
                                  ("phase_in", f"phase error of {sysd.inner_name}",
                                   res["floor"][0])):
            w.append(f"Target (issue 22): at each accuracy in {label}, the library's best "
                     "method needs at most 0.8x the wall time per orbit of REBOUND's best "
                     "(interpolated log-log along the sweeps):\n")
            w += targets_table(res, metric, lib["missing"], fl)
            w.append("")
        if sysd.name == "outer":
            w += fixed_step_targets(res, lib["missing"])
    with open(path + ".tmp", "w") as f:
        f.write("\n".join(w) + "\n")
    os.replace(path + ".tmp", path)


def fixed_step_targets(res, lib_missing):
    """The targets at h = P_Jupiter / 40 on the outer solar system."""
    sysd, k = res["system"], TARGET_H_K
    at = {(c.side, c.method): c for c in res["contenders"] if c.k == k and c.seconds}
    w = [f"Targets at h = P_{sysd.inner_name}/{k} (issue 22):\n"]
    ckl = at.get(("REBOUND", "WHCKL"))
    if ckl is None:
        return w + ["- WHCKL did not run at this step: not measured.", ""]
    ns_ckl = 1e9 * min(ckl.seconds) / sysd.nsteps(k)
    w.append(f"- WHCKL: max |dE/E| {ckl.acc[0]:.2e}, phase_in {ckl.acc[1]:.2e}, phase_out "
             f"{ckl.acc[2]:.2e}, {ns_ckl:.0f} ns/step.")
    if lib_missing:
        return w + ["- Library side missing: the targets (accuracy at <= 2 force-equivalent "
                    "evaluations per step; a corrected step <= 0.8x WHCKL's cost) are not "
                    "measured.", ""]
    libs = [c for (side, _), c in at.items() if side == "library"]
    if not libs:
        return w + [f"- No library method ran at h = P/{k}: not measured.", ""]
    for c in sorted(libs, key=lambda c: c.acc[0]):
        ns = 1e9 * min(c.seconds) / sysd.nsteps(k)
        ev = "evals not reported" if c.evals is None else f"{c.evals:g} evals/step"
        acc_ok = c.acc[0] <= ckl.acc[0]
        evals_ok = c.evals is not None and c.evals <= 2
        w.append(f"- library {c.method} ({ev}): max |dE/E| {c.acc[0]:.2e} "
                 f"({c.acc[0] / ckl.acc[0]:.2g}x WHCKL's), phase_in {c.acc[1]:.2e}; "
                 f"{'at least as accurate as WHCKL' if acc_ok else 'less accurate than WHCKL'}"
                 f" in energy, {'<= 2' if evals_ok else 'not known to be <= 2'} evals/step"
                 f"; cost {ns:.0f} ns/step = {ns / ns_ckl:.2f}x WHCKL's per step "
                 f"({'<= 0.8x' if ns / ns_ckl <= 0.8 else '> 0.8x'}).")
    return w + [""]


def check_contract(args):
    """Runs scripts/planets_race_double.py (REBOUND's WHCKL behind the library contract) against
    the harness's own WHCKL on both systems (100 orbits): the state file, the template and the
    line parsing must reproduce the harness's numbers (energy error bitwise; phases to 1e-12
    relative or 1e-15 rad, since the reference goes through the file's inertial frame). Exit
    status 1 if not."""
    import rebound
    out_dir = os.path.join(args.out_dir, "contract-check")
    os.makedirs(out_dir, exist_ok=True)
    args.orbits, args.reps, args.only = 100, 1, ["WHCKL"]
    double = os.path.join(HERE, "planets_race_double.py")
    lib = dict(cmd=f"{shlex.quote(sys.executable)} {shlex.quote(double)} state={{state}} "
               "system={system} method={method} h={h} nsteps={nsteps} samples={samples} "
               "orbits={orbits}", methods=["WHCKL"], ks=[10, 40], missing=None, warmed=False)
    bad = 0
    for sysd in load_systems(["outer", "inner"], args.orbits):
        res = run_system(rebound, sysd, args, lib, out_dir)
        if lib["missing"]:
            say(f"contract check FAILED: {lib['missing']}")
            return 1
        own = {c.k: c for c in res["contenders"] if c.side == "REBOUND"}
        for c in (c for c in res["contenders"] if c.side == "library"):
            o = own[c.k]
            ok = (c.error is None and c.acc[0] == o.acc[0] and
                  all(abs(a - b) <= 1e-12 * abs(b) + 1e-15 for a, b in zip(c.acc[1:], o.acc[1:])))
            bad += not ok
            say(f"contract check {sysd.name} k={c.k}: {'ok' if ok else 'MISMATCH'} "
                f"(double {c.acc}, harness {o.acc}, error {c.error})")
    say("contract check " + ("passed" if bad == 0 else f"FAILED ({bad} mismatches)"))
    return 1 if bad else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--orbits", type=int, default=10000)
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--samples", type=int, default=100)
    ap.add_argument("--systems", default="outer,inner")
    ap.add_argument("--only", default="", help="comma-separated REBOUND methods (default all)")
    ap.add_argument("--timeout", type=float, default=900.0)
    ap.add_argument("--out-dir", default=os.path.join(ROOT, "out", "race"))
    ap.add_argument("--doc-dir", default=os.path.join(ROOT, "doc"))
    ap.add_argument("--smoke", action="store_true",
                    help="100 orbits, 1 repetition, output under out/race (a smoke test)")
    ap.add_argument("--check-contract", action="store_true",
                    help="run the test double through the library contract and check it")
    args = ap.parse_args()
    if args.check_contract:
        sys.exit(check_contract(args))
    if args.smoke:
        args.orbits, args.reps, args.doc_dir = 100, 1, args.out_dir
    args.only = [s for s in args.only.split(",") if s]
    import rebound
    os.makedirs(args.out_dir, exist_ok=True)
    os.makedirs(os.path.join(args.doc_dir, "figures"), exist_ok=True)
    lib = dict(cmd=os.environ.get("FSYM_RACE_CMD", DEFAULT_LIB_CMD),
               methods=[m for m in os.environ.get("FSYM_RACE_LIB_METHODS",
                                                  DEFAULT_LIB_METHODS).split(",") if m],
               ks=[int(k) for k in os.environ.get("FSYM_RACE_LIB_KS", LIB_KS).split(",")],
               missing=None, warmed=False)
    if not lib["methods"]:
        lib["missing"] = "no library methods listed (FSYM_RACE_LIB_METHODS is empty)"
    if os.environ.get("FSYM_RACE_MISSING"):
        lib["missing"] = os.environ["FSYM_RACE_MISSING"]
    info = dict(cpu=cpu_name(), rebound=rebound.__version__, commit=git_commit(),
                date=datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
                load0=" ".join(f"{v:.2f}" for v in os.getloadavg()),
                command=os.environ.get("FSYM_RACE_COMMAND",
                                       "python scripts/planets_race.py " + " ".join(sys.argv[1:])))
    say(f"CPU {info['cpu']}, {os.cpu_count()} cores, load {info['load0']}; REBOUND "
        f"{info['rebound']}; library command: {lib['cmd']}")
    t0 = time.perf_counter()
    results = [run_system(rebound, s, args, lib, args.out_dir)
               for s in load_systems(args.systems.split(","), args.orbits)]
    info["wall"] = time.perf_counter() - t0
    info["load1"] = " ".join(f"{v:.2f}" for v in os.getloadavg())
    csv_path = os.path.join(args.doc_dir, "planets-race.csv")
    md_path = os.path.join(args.doc_dir, "planets-race-results.md")
    png = os.path.join(args.doc_dir, "figures", "planets-race.png")
    write_csv(csv_path, results)
    write_markdown(md_path, results, args, lib, info)
    plot(results, png, png[:-4] + ".pdf")
    say(f"wrote {csv_path}, {md_path}, {png} (+ .pdf); {info['wall']:.0f} s")
    if lib["missing"]:
        say(f"library side missing: {lib['missing']} (REBOUND's numbers alone)")


if __name__ == "__main__":
    main()
