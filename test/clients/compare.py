"""Compare the clients' final states with the modern API's, bit for bit.

Usage: python3 compare.py modern.txt client1.txt [client2.txt ...]
Each line: <way> <method> <body> x y z vx vy vz, or <way> <method> counts nf ng.
Exits non-zero when any number differs or a method is missing."""
import sys
from collections import defaultdict


def load(path):
    runs = defaultdict(dict)
    with open(path) as f:
        for line in f:
            t = line.split()
            try:
                if len(t) == 9:
                    runs[t[0]][(t[1], int(t[2]))] = [float(x) for x in t[3:]]
                elif len(t) == 5 and t[2] == 'counts':
                    runs[t[0]][(t[1], 'counts')] = [int(t[3]), int(t[4])]
            except ValueError:
                pass  # a message line, not a record
    return runs


ref = load(sys.argv[1])['modern']
bad = 0
for path in sys.argv[2:]:
    for way, got in load(path).items():
        diff = [k for k in ref if got.get(k) != ref[k]]
        print(f"{path}: {way}: {len(ref) - len(diff)}/{len(ref)} records identical to the modern API"
              + ("" if not diff else f"; differ: {diff[:4]}"))
        bad += len(diff)
if not ref:
    print("no modern reference records")
    bad = 1
sys.exit(1 if bad else 0)
