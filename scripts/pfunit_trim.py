#!/usr/bin/env python3
"""Trims the build of pFUnit's gFTL-shared to the containers that pFUnit and fArgParse use.

Usage: pfunit_trim.py PFUNIT_SOURCE_TREE   (edits the tree in place; called by scripts/pfunit.sh
on its own unpacked copy). Prints one line saying what it did.

gFTL-shared generates a vector, queue, stack, deque, set, map and ordered map for every element
kind (integers and reals of every kind, complex, logical, strings, unlimited polymorphic) and
every key kind: some 400 modules, most of pFUnit's build time. pFUnit 4.14 and fArgParse use
only string, integer and real vectors and the string-to-unlimited map, so the element types
are cut to the integer, real and string kinds (the "ordered" list, kept whole because the
default-kind containers are aliases of the sized ones) plus unlimited polymorphic, the keys to
strings, the v2 containers to vectors and maps (no queue, stack, deque, set or ordered map);
v1's demo program is not built. When a CMakeLists.txt does not read as expected,
nothing is changed and the full build runs.
"""
import pathlib
import re
import sys

# (pattern, replacement, allowed match counts): 0 allowed where the edit may already be made
EDITS = [
    (r'set \(T_types\s+\$\{T_types_ordered\}[^)]*\)', 'set (T_types ${T_types_ordered} Unlimited)',
     (1,)),
    (r'set \(Key_types[^)]*\)', 'set (Key_types String)', (1,)),
    (r'list \(APPEND T_types [^)]*\)', '', (0, 1)),
    (r'add_executable \(demo\.x demo\.F90\)\s*target_link_libraries \(demo\.x [^)]*\)', '',
     (0, 1)),
]
# v2 only: no queues, stacks, deques, sets or ordered maps (vectors and maps are used)
EDITS_V2 = [
    (r'foreach \(Container Queue Stack\)', 'foreach (Container)', (0, 1)),
    (r'foreach \(Container Deque\)', 'foreach (Container)', (0, 1)),
    (r'foreach \(Container Set\)', 'foreach (Container)', (0, 1)),
    (r'foreach \(Container Map OrderedMap\)', 'foreach (Container Map)', (0, 1)),
]


def main() -> int:
    if len(sys.argv) != 2:
        print('usage: pfunit_trim.py PFUNIT_SOURCE_TREE', file=sys.stderr)
        return 2
    base = pathlib.Path(sys.argv[1]) / 'extern/fArgParse/extern/gFTL-shared/src'
    texts = {}
    for version in ('v1', 'v2'):
        path = base / version / 'CMakeLists.txt'
        if not path.is_file():
            print(f'gFTL-shared not trimmed: no {path}; full build')
            return 0
        text = path.read_text()
        edits = EDITS + (EDITS_V2 if version == 'v2' else [])
        for pattern, replacement, counts in edits:
            if version == 'v2' and 'demo' in pattern:
                continue
            text, n = re.subn(pattern, replacement, text)
            if n not in counts:
                print(f'gFTL-shared not trimmed: {path} does not read as expected; full build')
                return 0
        texts[path] = text
    for path, text in texts.items():
        path.write_text(text)
    print('gFTL-shared trimmed to the containers pFUnit uses (integer, real, string and '
          'unlimited elements; string keys)')
    return 0


if __name__ == '__main__':
    sys.exit(main())
