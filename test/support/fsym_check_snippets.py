#!/usr/bin/env python3
"""Every code snippet of a documentation page must occur in a compiled source file.

Usage: fsym_check_snippets.py PAGE.md SOURCE...
Each fenced block marked fortran or c in PAGE.md must occur, as consecutive lines (compared
without leading and trailing blanks), in one of the SOURCE files (the example programs and
clients that the test command compiles and runs). Prints one line per snippet; exits 1 when
one is found nowhere, 2 when the page has no snippet.
"""
import pathlib
import re
import sys


def norm(text: str) -> list[str]:
    return [line.strip() for line in text.split('\n')]


def main() -> int:
    page = pathlib.Path(sys.argv[1])
    sources = {p: norm(pathlib.Path(p).read_text()) for p in sys.argv[2:]}
    blocks = re.findall(r'^```(fortran|c)\n(.*?)^```', page.read_text(), re.S | re.M)
    if not blocks:
        print(f'{page}: no fortran or c snippet')
        return 2
    missing = 0
    for k, (lang, body) in enumerate(blocks, 1):
        want = [line for line in norm(body.rstrip('\n'))]
        where = None
        for path, lines in sources.items():
            for i in range(len(lines) - len(want) + 1):
                if lines[i:i + len(want)] == want:
                    where = f'{path}:{i + 1}'
                    break
            if where:
                break
        if where:
            print(f'snippet {k} ({lang}, {len(want)} lines): {where}')
        else:
            missing += 1
            print(f'snippet {k} ({lang}, {len(want)} lines) found in no source: {want[0]} ...')
    print(f'{len(blocks) - missing} of {len(blocks)} snippets found in the compiled sources')
    return 1 if missing else 0


if __name__ == '__main__':
    sys.exit(main())
