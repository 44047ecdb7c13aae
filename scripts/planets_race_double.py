#!/usr/bin/env python3
"""Test double for the library side of the planetary race: fulfils the contract of
scripts/planets_race.py (reads the state file, integrates, prints one `race ...` line) with
REBOUND's own integrators, so that `planets_race.py --check-contract` can check the state file,
the command template and the line parsing without the library. Its numbers are REBOUND's, not
the library's: it is never used for a published table.

    planets_race_double.py state=FILE system=S method=M h=H nsteps=N samples=K orbits=O
(M: a REBOUND label of planets_race.REBOUND_METHODS, e.g. WHCKL)
"""
import sys
import time

import numpy as np
import rebound

import planets_race as pr


def read_state(path):
    """G, t_end, initial bodies [(name, [m, x, y, z, vx, vy, vz])] and reference bodies."""
    section, g, tend, ini, ref = 0, None, None, [], []
    with open(path) as f:
        for raw in f:
            line = raw.strip()
            if not line:
                continue
            if line.startswith("#"):
                section = 3 if "(initial state" in line else 4 if "(reference state" in line \
                    else section
                continue
            if g is None:
                g = float(line)
            elif tend is None:
                tend = float(line)
            else:
                t = line.split()
                (ini if section == 3 else ref).append((t[0], [float(v) for v in t[1:]]))
    return g, tend, ini, ref


def main():
    kv = dict(a.split("=", 1) for a in sys.argv[1:])
    g, _, ini, ref = read_state(kv["state"])
    settings = {lab: st for lab, st, _ in pr.REBOUND_METHODS}[kv["method"]]
    m_sun = [b for b in ini if b[0] == "Sun"][0][1][0]
    planets = [b for b in ini if b[0] != "Sun"]
    h, n, s = float(kv["h"]), int(kv["nsteps"]), int(kv["samples"])
    sim = pr.new_sim(rebound, g, m_sun, [(v[0], v[1:]) for _, v in planets], settings, h)
    e0, maxde = sim.energy(), 0.0
    c0 = time.process_time()
    t0 = time.perf_counter()
    for _ in range(s):
        sim.steps(n // s)
        sim.synchronize()
        maxde = max(maxde, abs((sim.energy() - e0) / e0))
    secs = time.perf_counter() - t0
    cpu = time.process_time() - c0
    refx = {name: np.array(v[:3]) for name, v in ref}
    sun = np.array(sim.particles[0].xyz)

    def phase(j, name):
        r = np.array(sim.particles[j].xyz) - sun
        return pr.phase_angle(r, refx[name] - refx["Sun"])

    print("(test double: REBOUND through the library contract)")
    print(f"race system={kv['system']} method={kv['method']} h={h!r} maxdE={maxde!r} "
          f"phase_in={phase(1, planets[0][0])!r} "
          f"phase_out={phase(len(planets), planets[-1][0])!r} seconds={secs!r} "
          f"orbits={float(kv['orbits'])!r} "
          f"evals={pr.REBOUND_EVALS[kv['method']]} cpu_seconds={cpu!r}")


if __name__ == "__main__":
    main()
