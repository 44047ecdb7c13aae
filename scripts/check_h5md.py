#!/usr/bin/env python3
"""Check HDF5 files written by the programs against H5MD 1.1 and doc/h5-layout.md.

Usage:
  check_h5md.py FILE.h5 ...                 check the given files
  check_h5md.py --run PROGRAM --out DIR     run `PROGRAM --out DIR` (no shell), then check
                                            every *.h5 file it wrote into DIR
  check_h5md.py --in DIR -- PROGRAM ARG...  run the command (no shell; `{out}` in an argument
                                            becomes DIR), then check every *.h5 in DIR

Checks, per file: the `h5md` group (version [1, 1], author/name, creator/name and version),
the units module (version, system); a `parameters` group with the run's settings (unit
system, compiler, flags, git commit; for the study's scenes also scene, eps, mu, q0, v0); every particle group has a `label`, a
safe name, a `box` with a scalar integer `dimension` and a `boundary` of that many entries
("none" or "periodic"), and its settings in `parameters/<name>`; every time series
(`value` with `step`/`time`) has matching lengths, integer steps and float times; every
time, position, velocity and energy dataset carries a `unit`; no temporary `.part` file is
left. Exit status 0 when every file passes, 1 on a failure, 77 (skipped) when h5py is
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


def check_file(path):
    errors = []

    def need(cond, what):
        if not cond:
            errors.append(what)

    with h5py.File(path, "r") as f:
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
        if "particles" in f:
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
                parent = name.split("/")[-2] if "/" in name else ""
                h5md_element = name.startswith(("particles/", "observables/"))
                wants = (base in UNIT_NAMES
                         or (h5md_element and base == "value")
                         or (h5md_element and "energy" in base))
                if wants:
                    need("unit" in obj.attrs, f"{name}: no unit attribute")

        f.visititems(visit)
    return errors


def main(argv):
    files = []
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
        errs = check_file(path)
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
