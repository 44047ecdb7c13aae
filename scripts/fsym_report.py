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
