"""CPU time of the fatigue amplitude (minimum circumscribed ball) over a 720-angle cycle.

Synthetic but shaped like the check's data: 14 unit cases combined with cycle
coefficients (centrifugal, 12 half-wave pin weights, torque), so most paths are not
proportional and every node runs the Badoiu-Clarkson refinement.  Times
``fatigue.amplitude_mean`` and the von Mises evaluation of a path (plain formula vs
``von_mises_path`` and ``von_mises_planes``, the latter on the (6, n_t, k) component
planes the assessment holds), each in this process (CPU seconds, best of ``--repeat``), and
checks that the results are identical bit for bit.  ``--reference FILE`` also times
another version of ``fatigue.py`` (e.g. ``git show main:fe_crank/assess/fatigue.py >
/tmp/fatigue_main.py``) on the same data and compares its results.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/fatigue_bench.py --nodes 4096 \
        [--reference /tmp/fatigue_main.py]
"""

from __future__ import annotations

import argparse
import importlib.util
import os
import sys
import time

import numpy as np


def paths(n: int, n_t: int = 720, seed: int = 1) -> np.ndarray:
    rng = np.random.default_rng(seed)
    th = np.linspace(0.0, 4 * np.pi, n_t, endpoint=False)
    coeff = np.column_stack([np.full(n_t, 1e4)] + [np.maximum(0.0, np.cos(th * k / 2 + k)) * 1e4 for k in range(12)]
                            + [1e3 * np.sin(3 * th)])
    return np.tensordot(coeff, rng.normal(size=(14, 6, n)), axes=(1, 0))


def cpu(fn, repeat: int):
    best, out = np.inf, None
    for _ in range(repeat):
        t = time.process_time()
        out = fn()
        best = min(best, time.process_time() - t)
    return best, out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--nodes", type=int, default=4096)
    ap.add_argument("--chunk", type=int, default=2048, help="nodes per history chunk (assess_group's)")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--reference", help="another fatigue.py to time and compare")
    args = ap.parse_args(argv)

    from fe_crank.assess import fatigue
    from fe_crank.assess.stress import von_mises, von_mises_path, von_mises_planes

    h = paths(args.nodes)
    chunks = [np.ascontiguousarray(h[:, :, s:s + args.chunk]) for s in range(0, h.shape[-1], args.chunk)]
    c = [0.5 * (x.min(axis=0) + x.max(axis=0)) for x in chunks]

    def amp(mod):
        return lambda: [mod.amplitude_mean(x) for x in chunks]

    rows = []
    t_plain, a = cpu(lambda: [von_mises(x - cc[None]) for x, cc in zip(chunks, c)], args.repeat)
    t_path, b = cpu(lambda: [von_mises_path(x, cc) for x, cc in zip(chunks, c)], args.repeat)
    same = all(np.array_equal(x, y) for x, y in zip(a, b))
    rows.append(("von Mises of a path about its mid-range: plain / von_mises_path", t_plain, t_path, same))
    planes = [np.ascontiguousarray(x.transpose(1, 0, 2)) for x in chunks]   # (6, n_t, k), as assess_group holds them
    t_planes, d = cpu(lambda: [von_mises_planes(x, cc) for x, cc in zip(planes, c)], args.repeat)
    same = all(np.array_equal(x, y) for x, y in zip(a, d))
    rows.append(("the same: plain / von_mises_planes on component planes", t_plain, t_planes, same))
    t_new, new = cpu(amp(fatigue), args.repeat)
    if args.reference:
        spec = importlib.util.spec_from_file_location("fatigue_reference", args.reference)
        ref = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(ref)
        t_ref, old = cpu(amp(ref), args.repeat)
        same = all(np.array_equal(x, y) for o, n in zip(old, new) for x, y in zip(o, n))
        rows.append(("amplitude_mean: reference / this tree", t_ref, t_new, same))
    else:
        rows.append(("amplitude_mean (this tree)", np.nan, t_new, True))
    print(f"{args.nodes} nodes x 720 angles, chunks of {args.chunk}; load average {os.getloadavg()[0]:.2f}")
    for what, t0, t1, eq in rows:
        print(f"{what}: {t0:.3f} s / {t1:.3f} s = {t0 / t1:.2f}x; identical: {eq}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
