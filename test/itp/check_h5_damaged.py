#!/usr/bin/env python3
"""scripts/check_h5md.py rejects damaged files of fsym_itp_run.

Usage: check_h5_damaged.py GOOD.h5 SCRATCH_DIR E1,E2,...

GOOD.h5 is a file fsym_itp_run wrote (test itp_h5.pt1d_conforms) whose last energies are
E1, E2, ... (at least two states). The undamaged copy must pass; then every damage below, one
at a time on a fresh copy written by h5py (a unit removed or wrong, a state scaled by 1+1e-9,
two states mixed by 1e-8, the density or the grid or a time changed, a series cut short, the
header or a parameter broken, an energy moved by 1e-8), must be reported by the checker. A
check loosened until it cannot fail makes this test fail. Exit 0 on success, 1 on failure,
77 (skipped) when h5py is missing.
"""
import os
import shutil
import sys

try:
    import h5py
    import numpy as np
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                    "scripts"))
    import check_h5md
except ImportError as exc:
    print(f"skipped: {exc}")
    sys.exit(77)


def replace(f, name, data):
    """Write `data` in place of the dataset `name`, keeping its attributes."""
    attrs = dict(f[name].attrs)
    del f[name]
    f[name] = data
    for key, val in attrs.items():
        f[name].attrs[key] = val


def psi_states(f):
    """The states as [nstates, npts] and a function that writes such an array back."""
    shape = f["fields/psi/value"].shape
    psi = f["fields/psi/value"][...].reshape(shape[0], -1)
    return psi, lambda p: replace(f, "fields/psi/value", p.reshape(shape))


def scale_state(f):
    psi, put = psi_states(f)
    psi[1] *= 1 + 1e-9
    put(psi)


def mix_states(f):
    psi, put = psi_states(f)
    mixed = psi[-1] + 1e-8 * psi[0]
    psi[-1] = mixed * np.sqrt(np.sum(psi[-1] ** 2) / np.sum(mixed ** 2))   # norm kept
    put(psi)


def density_of_state_2(f):
    psi, _ = psi_states(f)
    replace(f, "fields/density/value", (psi[1] ** 2).reshape(f["fields/density/value"].shape))


def shift_grid(f):
    x = f["grid/x1"][...]
    replace(f, "grid/x1", x + 0.5 * (x[1] - x[0]))


def time_off(f):
    t = f["observables/energy_norm/time"][...]
    t[-1] *= 1 + 1e-6
    replace(f, "observables/energy_norm/time", t)


def cut_steps(f):
    replace(f, "observables/energy/step", f["observables/energy/step"][:-1])


def move_energy(f):
    e = f["observables/energy/value"][...]
    e[-1, 1] += 1e-8
    replace(f, "observables/energy/value", e)


def drop(name, attr):
    def damage(f):
        del f[name].attrs[attr]
    return damage


def set_attr(name, attr, value):
    def damage(f):
        f[name].attrs[attr] = value
    return damage


DAMAGES = {
    "unit of observables/energy/value removed": drop("observables/energy/value", "unit"),
    "unit of grid/x1 removed": drop("grid/x1", "unit"),
    "unit of fields/density/value removed": drop("fields/density/value", "unit"),
    "unit of observables/energy_norm/time wrong": set_attr("observables/energy_norm/time",
                                                           "unit", "E"),
    "unit of fields/psi/value wrong": set_attr("fields/psi/value", "unit", "L-1"),
    "h5md version [1, 0]": set_attr("h5md", "version", np.array([1, 0], dtype=np.int32)),
    "creator lacks its name": drop("h5md/creator", "name"),
    "parameters lack tau": drop("parameters", "tau"),
    "parameters/tau differs from the times": set_attr("parameters", "tau", 0.051),
    "state 2 scaled by 1+1e-9": scale_state,
    "last state mixed with the first by 1e-8": mix_states,
    "density of state 2": density_of_state_2,
    "grid shifted by half a cell": shift_grid,
    "last time off by 1e-6": time_off,
    "energy steps one short": cut_steps,
    "last energy of state 2 moved by 1e-8": move_energy,
}


def main(argv):
    if len(argv) != 3:
        sys.exit("usage: check_h5_damaged.py GOOD.h5 SCRATCH_DIR E1,E2,...")
    good, scratch = argv[0], argv[1]
    energies = [float(x) for x in argv[2].split(",")]
    shutil.rmtree(scratch, ignore_errors=True)
    os.makedirs(scratch)
    failed = 0
    errs = check_h5md.check_file(good, energies)
    print(f"{'ok  ' if not errs else 'FAIL'} undamaged file passes: {errs[:3]}")
    failed += bool(errs)
    wrong = [e + 1e-8 for e in energies]
    errs = check_h5md.check_file(good, wrong)
    print(f"{'ok  ' if errs else 'FAIL'} expected energies moved by 1e-8: {errs[:1]}")
    failed += not errs
    for i, (what, damage) in enumerate(DAMAGES.items()):
        path = os.path.join(scratch, f"damaged{i}.h5")
        shutil.copyfile(good, path)
        with h5py.File(path, "r+") as f:
            damage(f)
        errs = check_h5md.check_file(path, energies)
        print(f"{'ok  ' if errs else 'FAIL'} {what}: {errs[:1] if errs else 'accepted'}")
        failed += not errs
    print(f"{failed} failure(s)")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
