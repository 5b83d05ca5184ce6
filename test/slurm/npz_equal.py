#!/usr/bin/python3
"""npz_equal.py A.npz B.npz: exit 0 when both hold the same arrays (names, types, shapes, bytes:
NaN where NaN), else 1 with the first difference."""
import sys

import numpy as np

a, b = (np.load(p, allow_pickle=False) for p in sys.argv[1:3])
if sorted(a.files) != sorted(b.files):
    sys.exit("arrays differ: %s has %s, %s has %s" % (sys.argv[1], sorted(a.files), sys.argv[2],
                                                      sorted(b.files)))
for name in a.files:
    x, y = a[name], b[name]
    if x.dtype != y.dtype or x.shape != y.shape:
        sys.exit("%s: %s %s against %s %s" % (name, x.dtype, x.shape, y.dtype, y.shape))
    if x.tobytes() != y.tobytes():
        rows = np.nonzero([r.tobytes() != s.tobytes() for r, s in zip(x.reshape(len(x), -1),
                                                                      y.reshape(len(y), -1))])[0] \
            if x.ndim else [0]
        sys.exit("%s: differs, first at row %d" % (name, rows[0]))
print("equal: %d arrays (%s), %d scenes" % (len(a.files), ", ".join(a.files), len(a["scene"])))
