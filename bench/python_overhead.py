#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""The Python module's overhead on arm7 (docs/benchmarks.md#python-module):

1. one forward_dynamics call from Python (1-D arrays of 7), timed by timeit
   as the best of 5 runs of 200,000 calls; issue 34's target: <= 1.5 us;
2. a batch of 10,000 states (2-D arrays, one state per row) in one call,
   against a plain C++ loop calling the same kernel from the same kernels.so
   over the same states (bench/python_overhead_loop.cpp, compiled here with
   c++ -O2, no Python involved); target: <= 1.2x. The batch includes the
   allocation of its (10000, 7) result; the C++ loop writes into a buffer
   allocated once. Both are the best of 50 runs.

Run from the repository root, with the module built:
    PYTHONPATH=$PWD/build/python /usr/bin/python3 bench/python_overhead.py
"""
import os
import subprocess
import sys
import tempfile
import timeit

import numpy as np

import kanegen

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
N = 10_000


def main():
    m = kanegen.load(os.path.join(ROOT, "models", "arm7.urdf"))
    rng = np.random.default_rng(0)
    q, u, tau = rng.uniform(-1, 1, 7), rng.uniform(-1, 1, 7), rng.uniform(-5, 5, 7)
    f = m.forward_dynamics
    calls = 200_000
    single = min(timeit.repeat(lambda: f(q, u, tau), number=calls, repeat=5)) / calls

    Q, U, T = rng.uniform(-1, 1, (N, 7)), rng.uniform(-1, 1, (N, 7)), rng.uniform(-5, 5, (N, 7))
    batch = min(timeit.repeat(lambda: f(Q, U, T), number=1, repeat=50)) / N
    udot = f(Q, U, T)

    with tempfile.TemporaryDirectory() as tmp:
        loop = os.path.join(tmp, "loop")
        subprocess.run(["c++", "-std=c++17", "-O2", "-I", os.path.join(ROOT, "runtime", "include"),
                        os.path.join(ROOT, "bench", "python_overhead_loop.cpp"), "-o", loop, "-ldl"], check=True)
        states = os.path.join(tmp, "states.bin")
        np.hstack([Q, U, T]).astype(np.float64).tofile(states)
        out = subprocess.run([loop, m.library, states, str(N), "50"], check=True, capture_output=True,
                             text=True).stdout.split()
        cpp_ns, checksum = float(out[0]), float(out[1])
    if abs(checksum - udot.sum()) > 1e-9 * max(1.0, abs(checksum)):
        sys.exit("the C++ loop and the Python batch disagree (%r vs %r)" % (checksum, udot.sum()))
    kernel_only = cpp_ns * 1e-9

    print("arm7 forward_dynamics (%s)" % m.library)
    print("  one call from Python:        %.3f us   (target <= 1.5 us; the kernel alone: %.3f us)"
          % (single * 1e6, kernel_only * 1e6))
    print("  batch of %d, per state:   %.1f ns   (one call, 2-D arrays)" % (N, batch * 1e9))
    print("  C++ loop, per state:         %.1f ns   (bench/python_overhead_loop.cpp)" % cpp_ns)
    print("  batch / C++ loop:            %.3f    (target <= 1.2)" % (batch * 1e9 / cpp_ns))


if __name__ == "__main__":
    main()
