#!/usr/bin/env python3
"""Rendering a page twice from the same files gives the same text.

Usage: render_twice.py [--results OUT_DIR] [--solar SOLAR_H5] [--workprec WORKPREC_H5]
                       [--stability STABILITY_H5] [--committed]

Each page named is rendered twice by its script (scripts/report_results.py,
report_solar.py, report_workprec.py, report_stability.py) into a scratch directory and the
two texts compared byte for byte; a page must also name the git commit of its numbers when
the script writes one. With --committed the first rendering is also compared with the page
committed under doc/ (a page edited by hand after rendering then fails). Exit 0 when every
page agrees, 1 otherwise, 77 (skipped) without h5py.
"""
import os
import subprocess
import sys
import tempfile

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
PAGES = {  # option: (script, committed page, line that names the commit or None)
    "--results": ("report_results.py", "doc/results.md", "Git commit that made the numbers"),
    "--solar": ("report_solar.py", "doc/solar-system.md", "Git commit of the run"),
    "--workprec": ("report_workprec.py", "doc/work-precision.md",
                   "Git commit that made the numbers"),
    "--stability": ("report_stability.py", "doc/stability.md",
                    "Git commit that made the numbers"),
}


def render(script, src, md, scratch):
    args = [sys.executable, os.path.join(ROOT, "scripts", script), src, md]
    if script == "report_workprec.py":
        args.append(os.path.join(scratch, "figures"))
    r = subprocess.run(args, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"{script} failed:\n{r.stdout}{r.stderr}")
    with open(md) as fh:
        return fh.read()


def main(argv):
    try:
        import h5py  # noqa: F401
    except ImportError:
        print("skipped: h5py is not installed")
        return 77
    committed = "--committed" in argv
    argv = [a for a in argv if a != "--committed"]
    if len(argv) % 2 or not argv:
        print(__doc__)
        return 2
    fails, passed = [], 0
    with tempfile.TemporaryDirectory() as scratch:
        for opt, src in zip(argv[0::2], argv[1::2]):
            script, page, commit_line = PAGES[opt]
            texts = [render(script, src, os.path.join(scratch, f"{opt[2:]}{i}.md"), scratch)
                     for i in (1, 2)]
            checks = [(texts[0] == texts[1], f"{page}: two renderings differ")]
            if commit_line:
                checks.append((commit_line in texts[0], f"{page}: no line '{commit_line}'"))
            if committed:
                with open(os.path.join(ROOT, page)) as fh:
                    checks.append((fh.read() == texts[0], f"{page}: the committed page is "
                                   "not what the script renders from these files"))
            for ok, what in checks:
                passed += ok
                if not ok:
                    fails.append(what)
    for f in fails:
        print("FAIL", f)
    print(f"render_twice: {passed} passed, {len(fails)} failed")
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
