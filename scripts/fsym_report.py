"""Helpers shared by the report scripts (report_*.py)."""
import os


def text(x):
    """An HDF5 string attribute (bytes or str) as str."""
    return x.decode() if isinstance(x, bytes) else str(x)


def write_atomic(path, lines):
    """Write the lines to `path` through a temporary name in the same directory, then
    rename: a killed run never leaves a truncated page."""
    tmp = f"{path}.{os.getpid()}.part"
    with open(tmp, "w") as fh:
        fh.write("\n".join(lines) + "\n")
    os.replace(tmp, path)


def study_scenes(out):
    """The study's scenes as (name, kind) pairs, in the order fsym-study runs them, from
    OUT/scenes.txt, which fsym-study writes from its list SCENES (the one place that names
    them). Kinds: coefficients, points, acoef, scan, results."""
    path = os.path.join(out, "scenes.txt")
    if not os.path.exists(path):
        raise SystemExit(f"{path} missing: run fsym-study (bash scripts/main.sh), which "
                         "writes it beside its scene files")
    pairs = []
    with open(path) as fh:
        for line in fh:
            if line.strip():
                name, kind = line.split()
                pairs.append((name, kind))
    return pairs
