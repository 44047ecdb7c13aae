#!/usr/bin/env python3
"""Check HDF5 files written by the programs against H5MD 1.1 and doc/h5-layout.md.

Usage:
  check_h5md.py FILE.h5 ...                 check the given files
  check_h5md.py --energies E1,E2,.. [--tol T] (FILE.h5 ... | --in ...)
                                            also: the last energies of an imaginary-time
                                            file are E1, E2, .. within T (default 1e-9)
  check_h5md.py --run PROGRAM --out DIR     run `PROGRAM --out DIR` (no shell), then check
                                            every *.h5 file it wrote into DIR
  check_h5md.py --in DIR -- PROGRAM ARG...  run the command (no shell; `{out}` in an argument
                                            becomes DIR), then check every *.h5 in DIR

Checks, per file: the `h5md` group (version [1, 1], author/name, creator/name and version),
the units module (version, system); a `parameters` group with the run's settings (unit
system, compiler, flags, git commit; for the study's scenes also scene, eps, mu, q0, v0);
every particle group has a `label`, a safe name, a `box` with a scalar integer `dimension`
and a `boundary` of that many entries ("none" or "periodic"), and its settings in
`parameters/<name>`; every time series (`value` with `step`/`time`) has matching lengths,
integer steps and float times; every time, position, velocity and energy dataset carries a
`unit`; no temporary `.part` file is left.
Files of fsym_itp_run (itp/app, doc/imaginary-time.md: creator fsym_itp_run, or a `grid` or
`fields` group) are checked against that layout instead of the particle groups: parameters
problem, method, tau, steps, g, n, box; `grid/x1..xd` (unit L) = -box/2 + i box/n;
`observables/energy` and `observables/energy_norm` with step = 1..steps, time = step*tau
(unit E-1) and value [steps, nstates] (unit E); `fields/psi/value` (unit L-d/2) with every
state normalised (sum psi^2 dx^d = 1 within 1e-12) and the states orthogonal within 1e-10;
`fields/density/value` (unit L-d) = psi_1^2; with --energies, the last energies.
Exit status 0 when every file passes, 1 on a failure, 77 (skipped) when h5py is
missing.
"""
import glob
import os
import re
import shutil
import subprocess
import sys

try:
    import h5py
    import numpy as np
except ImportError as exc:  # pragma: no cover - depends on the environment
    print(f"SKIPPED: h5py/numpy not importable by {sys.executable} ({exc}); install them with "
          "`FSYM_PLOTS=1 bash scripts/setup.sh` (virtual environment "
          "~/.cache/forward-symplectic/venv) or point FSYM_PYTHON at a Python that has them")
    sys.exit(77)

SAFE = re.compile(r"^[A-Za-z0-9_.()+,\-]+$")
PARAMETERS = ["unit_system", "compiler", "compiler_flags", "git_commit"]
SCENE_PARAMETERS = ["eps", "mu", "q0", "v0"]
UNIT_NAMES = ("time", "position", "velocity")


def text(x):
    if isinstance(x, bytes):
        return x.decode()
    if isinstance(x, np.ndarray) and x.shape == ():
        return text(x[()])
    return str(x)


def safe_name(label):
    out = []
    for c in label:
        if c == "'":
            out.append("p")
        elif SAFE.match(c):
            out.append(c)
        else:
            out.append("_")
    return "".join(out)


def check_header(f, need):
    """The H5MD 1.1 header and the run's settings every program writes (fsym_h5md_header)."""
    need("h5md" in f, "no /h5md group")
    if "h5md" in f:
        h = f["h5md"]
        need(list(np.asarray(h.attrs.get("version", [])).ravel()) == [1, 1],
             "h5md version is not [1, 1]")
        for sub in ("author", "creator"):
            need(sub in h and "name" in h[sub].attrs, f"h5md/{sub} lacks a name")
        need("creator" in h and "version" in h["creator"].attrs, "h5md/creator lacks version")
        if "modules" in h and "units" in h["modules"]:
            u = h["modules/units"].attrs
            need("version" in u and "system" in u, "units module lacks version or system")
    need("parameters" in f, "no /parameters group")
    if "parameters" in f:
        pa = f["parameters"].attrs
        for key in PARAMETERS + (SCENE_PARAMETERS if "scene" in pa else []):
            need(key in pa, f"parameters lacks {key}")


def check_particles(f, need):
    """The study's and fsym-solar's particle groups (doc/h5-layout.md)."""
    for name, g in f["particles"].items():
        where = f"particles/{name}"
        need(isinstance(g, h5py.Group), f"{where} is not a group")
        if not isinstance(g, h5py.Group):
            continue
        need("label" in g.attrs, f"{where} has no label")
        if "label" in g.attrs:
            need(name == safe_name(text(g.attrs["label"])),
                 f"{where}: name is not the safe form of its label")
        need(SAFE.match(name) is not None, f"{where}: unsafe group name")
        need("box" in g, f"{where} has no box")
        if "box" in g:
            b = g["box"].attrs
            dim = b.get("dimension")
            need(dim is not None and np.asarray(dim).shape == ()
                 and np.issubdtype(np.asarray(dim).dtype, np.integer),
                 f"{where}/box: dimension is not a scalar integer")
            bnd = [text(x) for x in np.asarray(b.get("boundary", [])).ravel()]
            need(dim is not None and len(bnd) == int(dim),
                 f"{where}/box: boundary has {len(bnd)} entries, not one per dimension")
            need(all(x in ("none", "periodic") for x in bnd),
                 f"{where}/box: boundary entries must be none or periodic")
        need("parameters" in f and name in f["parameters"],
             f"{where}: no parameters/{name} with the run's settings")
        if "parameters" in f and name in f["parameters"]:
            pa = f["parameters"][name].attrs
            need("method" in pa, f"parameters/{name} lacks method")
            if int(pa.get("splitting", 0)) == 1:
                need(all(k in pa for k in ("op", "c", "u")),
                     f"parameters/{name} lacks the coefficient table")


def check_series(f, need):
    """Every time series: lengths and types of step/time; units where H5MD wants them."""

    def visit(name, obj):
        if isinstance(obj, h5py.Group) and "value" in obj and isinstance(obj["value"],
                                                                          h5py.Dataset):
            n = obj["value"].shape[0] if obj["value"].shape else 0
            for key, kind in (("step", np.integer), ("time", np.floating)):
                if key in obj:
                    d = obj[key]
                    need(d.ndim == 1 and d.shape[0] == n,
                         f"{name}/{key}: length differs from value's {n}")
                    need(np.issubdtype(d.dtype, kind), f"{name}/{key}: wrong type")
        if isinstance(obj, h5py.Dataset):
            base = name.split("/")[-1]
            h5md_element = name.startswith(("particles/", "observables/", "fields/"))
            wants = (base in UNIT_NAMES
                     or (h5md_element and base == "value")
                     or (h5md_element and "energy" in base))
            if wants:
                need("unit" in obj.attrs, f"{name}: no unit attribute")

    f.visititems(visit)


ITP_PARAMETERS = ["problem", "method", "tau", "steps", "g", "n", "box"]
NORM_TOL = 1e-12        # |sum |psi|^2 dx^d - 1| of every state
ORTHO_TOL = 1e-10       # |<psi_i|psi_j>| of two states


def unit_is(f, name, unit, need):
    """`name` exists and carries the unit `unit`."""
    need(name in f, f"no /{name}")
    if name in f:
        got = text(f[name].attrs["unit"]) if "unit" in f[name].attrs else None
        need(got == unit, f"{name}: unit {got!r}, not {unit!r}")


def check_itp(f, need, energies=None, tol=1e-9):
    """The layout of fsym_itp_run (itp/app/fsym_itp_run.f90, doc/imaginary-time.md): the
    parameters, the grid, the two energy histories and the states with their density."""
    pa = f["parameters"].attrs if "parameters" in f else {}
    for key in ITP_PARAMETERS:
        need(key in pa, f"parameters lacks {key}")
    if not all(key in pa for key in ITP_PARAMETERS):
        return
    n = np.asarray(pa["n"]).ravel()
    tau, box, steps = float(pa["tau"]), float(pa["box"]), int(pa["steps"])
    d = len(n)
    good_n = 1 <= d <= 3 and np.issubdtype(n.dtype, np.integer) and all(n > 0)
    need(good_n, f"parameters/n = {n}: not 1 to 3 positive integers")
    good_run = np.isfinite(tau) and tau > 0 and box > 0 and steps >= 1
    need(good_run, f"parameters: tau {tau}, box {box}, steps {steps} not positive")
    if not (good_n and good_run):
        return
    dv = np.prod(box / n)   # the volume of a grid cell, dx^d
    for j in range(1, 4):
        name = f"grid/x{j}"
        if j > d:
            need(name not in f, f"{name} in a {d}-dimensional run")
            continue
        unit_is(f, name, "L", need)
        if name in f:
            x = f[name][...]
            want = -box / 2 + np.arange(n[j - 1]) * box / n[j - 1]
            need(x.shape == want.shape and np.max(np.abs(x - want)) <= 1e-12 * box,
                 f"{name}: not -box/2 + i box/n, i = 0..n-1")
    nstates = None
    for group in ("observables/energy", "observables/energy_norm"):
        for key in ("step", "time", "value"):
            need(f"{group}/{key}" in f, f"no /{group}/{key}")
        if not all(f"{group}/{key}" in f for key in ("step", "time", "value")):
            continue
        unit_is(f, f"{group}/time", "E-1", need)
        unit_is(f, f"{group}/value", "E", need)
        step, time = f[f"{group}/step"][...], f[f"{group}/time"][...]
        value = f[f"{group}/value"][...]
        need(np.array_equal(step, np.arange(1, steps + 1)),
             f"{group}/step: not 1..{steps} (parameters/steps)")
        need(time.shape == step.shape == (steps,)
             and np.max(np.abs(time - step * tau)) <= 1e-12 * tau * steps,
             f"{group}/time: not step*tau")
        need(value.ndim == 2 and value.shape[0] == steps and np.all(np.isfinite(value)),
             f"{group}/value: shape {value.shape}, not [{steps}, nstates] finite values")
        if value.ndim == 2:
            need(nstates in (None, value.shape[1]), f"{group}/value: another number of states")
            nstates = value.shape[1]
        if group == "observables/energy" and energies is not None and value.ndim == 2:
            last = value[-1]
            need(len(last) == len(energies)
                 and np.max(np.abs(last - np.asarray(energies))) <= tol,
                 f"{group}/value: last energies {[float(e) for e in last]}, expected {energies} "
                 f"within {tol}")
    unit_is(f, "fields/psi/value", f"L-{d}/2", need)
    unit_is(f, "fields/density/value", f"L-{d}", need)
    if "fields/psi/value" not in f or "fields/density/value" not in f:
        return
    npts = int(np.prod(n))
    psi = f["fields/psi/value"][...]   # Fortran (n1, n2*n3, nstates): h5py [nstates, n2*n3, n1]
    need(psi.shape == (nstates, npts // n[0], n[0]),
         f"fields/psi/value: shape {psi.shape}, not [{nstates}, {npts // n[0]}, {n[0]}]")
    if psi.size != (nstates or 0) * npts:
        return
    psi = psi.reshape(nstates, npts)
    overlap = psi @ psi.T * dv
    for s in range(nstates):
        need(abs(overlap[s, s] - 1) <= NORM_TOL,
             f"fields/psi/value: state {s + 1} has norm {float(overlap[s, s])!r}, not 1 "
             f"within {NORM_TOL}")
        for r in range(s):
            need(abs(overlap[s, r]) <= ORTHO_TOL,
                 f"fields/psi/value: states {r + 1} and {s + 1} overlap by {overlap[s, r]:.3e}")
    rho = f["fields/density/value"][...]
    need(rho.shape == (npts // n[0], n[0])
         and np.max(np.abs(rho.reshape(npts) - psi[0] ** 2)) <= 1e-14 * np.max(psi[0] ** 2),
         "fields/density/value: not psi_1^2")


def is_itp(f):
    """A file of fsym_itp_run (itp/app): by its creator or by its grid and fields."""
    creator = f["h5md/creator"].attrs.get("name", "") if "h5md/creator" in f else ""
    return text(creator) == "fsym_itp_run" or "fields" in f or "grid" in f


def check_file(path, energies=None, tol=1e-9):
    """The errors found in one file (empty: it conforms). `energies`: the expected last
    energies of an imaginary-time file, one per state, within `tol`."""
    errors = []

    def need(cond, what):
        if not cond:
            errors.append(what)

    with h5py.File(path, "r") as f:
        check_header(f, need)
        if is_itp(f):
            check_itp(f, need, energies, tol)
        else:
            need(energies is None, "--energies given for a file that is not fsym_itp_run's")
            if "particles" in f:
                check_particles(f, need)
        check_series(f, need)
    return errors


def main(argv):
    files = []
    energies, tol = None, 1e-9
    while argv[:1] in (["--energies"], ["--tol"]):
        if len(argv) < 2:
            sys.exit(f"usage: check_h5md.py {argv[0]} VALUE ...")
        if argv[0] == "--energies":
            energies = [float(x) for x in argv[1].split(",")]
        else:
            tol = float(argv[1])
        argv = argv[2:]
    if argv[:1] == ["--in"]:
        if len(argv) < 4 or argv[2] != "--":
            sys.exit("usage: check_h5md.py --in DIR -- PROGRAM ARG...")
        out = argv[1]
        shutil.rmtree(out, ignore_errors=True)
        os.makedirs(out)
        env = dict(os.environ, FSYM_GIT_COMMIT=os.environ.get("FSYM_GIT_COMMIT", "test"))
        cmd = [a.replace("{out}", out) for a in argv[3:]]
        r = subprocess.run(cmd, env=env)
        if r.returncode != 0:
            print(f"FAIL: {cmd[0]} exited with {r.returncode}")
            return 1
        files = sorted(glob.glob(os.path.join(out, "*.h5")))
        left = glob.glob(os.path.join(out, "*.part"))
        if left or not files:
            print(f"FAIL: temporary files left ({left}) or no .h5 file in {out}")
            return 1
    elif argv[:1] == ["--run"]:
        if len(argv) < 4 or argv[2] != "--out":
            sys.exit("usage: check_h5md.py --run PROGRAM --out DIR")
        prog, out = argv[1], argv[3]
        shutil.rmtree(out, ignore_errors=True)
        env = dict(os.environ, FSYM_GIT_COMMIT=os.environ.get("FSYM_GIT_COMMIT", "test"))
        r = subprocess.run([prog, "--out", out], env=env)
        if r.returncode != 0:
            print(f"FAIL: {prog} exited with {r.returncode}")
            return 1
        files = sorted(glob.glob(os.path.join(out, "*.h5")))
        left = glob.glob(os.path.join(out, "*.part"))
        if left:
            print(f"FAIL: temporary files left: {left}")
            return 1
        if not files:
            print(f"FAIL: {prog} wrote no .h5 file into {out}")
            return 1
    else:
        files = argv
    bad = 0
    for path in files:
        errs = check_file(path, energies, tol)
        if errs:
            bad += 1
            print(f"FAIL {path}:")
            for e in errs[:20]:
                print(f"    {e}")
        else:
            print(f"ok   {path}")
    print(f"{len(files) - bad} of {len(files)} files conform")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
