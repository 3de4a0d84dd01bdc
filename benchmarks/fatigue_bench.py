"""CPU time of the fatigue amplitude (minimum circumscribed ball) over a 720-angle cycle.

Synthetic but shaped like the check's data: 14 unit cases combined with cycle
coefficients (centrifugal, 12 half-wave pin weights, torque), so most paths are not
proportional and every node runs the Badoiu-Clarkson refinement.  Times
``fatigue.amplitude_mean`` and the von Mises evaluation of a path (plain formula vs
``von_mises_path`` and ``von_mises_planes``, the latter on the (6, n_t, k) component
planes the assessment holds), each in this process (CPU seconds, best of ``--repeat``), and
checks that the results are identical bit for bit.  ``--reference FILE`` also times
another version of ``fatigue.py`` (e.g. ``git show main:fe_crank/assess/fatigue.py >
/tmp/fatigue_main.py``) on the same data and compares its results.  ``--threads N`` also
runs the fatigue blocks (``amplitude_mean`` of 128-node blocks) and a whole
``assess_group`` (superposition, static, Goodman, Gough-Pollard, overspeed peak) on a
synthetic group of ``--nodes`` nodes on 1 and on N threads (``assess.workers``), each
``--repeat`` times alternately, and prints the best wall and CPU seconds of each, the
parallelism CPU / wall (above 1 only if the threads really run at the same time, i.e.
numpy released the interpreter lock) and whether the results are identical.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/fatigue_bench.py --nodes 4096 \
        [--reference /tmp/fatigue_main.py] [--threads 2]
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
    coeff = np.column_stack(
        [np.full(n_t, 1e4)]
        + [np.maximum(0.0, np.cos(th * k / 2 + k)) * 1e4 for k in range(12)]
        + [1e3 * np.sin(3 * th)]
    )
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
    ap.add_argument("--threads", type=int, default=0, help="also time the blocks on 1 and on N threads")
    args = ap.parse_args(argv)
    if args.threads:
        threaded(args.nodes, args.threads, args.repeat)
        return 0

    from fe_crank.assess import fatigue
    from fe_crank.assess.stress import von_mises, von_mises_path, von_mises_planes

    h = paths(args.nodes)
    chunks = [np.ascontiguousarray(h[:, :, s : s + args.chunk]) for s in range(0, h.shape[-1], args.chunk)]
    c = [0.5 * (x.min(axis=0) + x.max(axis=0)) for x in chunks]

    def amp(mod):
        return lambda: [mod.amplitude_mean(x) for x in chunks]

    rows = []
    t_plain, a = cpu(lambda: [von_mises(x - cc[None]) for x, cc in zip(chunks, c)], args.repeat)
    t_path, b = cpu(lambda: [von_mises_path(x, cc) for x, cc in zip(chunks, c)], args.repeat)
    same = all(np.array_equal(x, y) for x, y in zip(a, b))
    rows.append(("von Mises of a path about its mid-range: plain / von_mises_path", t_plain, t_path, same))
    planes = [np.ascontiguousarray(x.transpose(1, 0, 2)) for x in chunks]  # (6, n_t, k), as assess_group holds them
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


def _wall_cpu(fn):
    w, c = time.perf_counter(), time.process_time()
    out = fn()
    return time.perf_counter() - w, time.process_time() - c, out


def _synthetic_group(n: int, seed: int = 2):
    """A group of ``n`` nodes shaped like the check's: 14 unit cases, 720 angles."""
    from fe_crank.assess.superpose import UnitStresses, load_coefficients
    from fe_crank.fe.unit_cases import CASES

    rng = np.random.default_rng(seed)
    pts = np.vstack(
        [
            0.03 * np.cos(np.linspace(0, 2 * np.pi, n)),
            0.03 * np.sin(np.linspace(0, 2 * np.pi, n)),
            np.linspace(-0.01, 0.01, n),
        ]
    )
    us = UnitStresses(
        stress=rng.normal(size=(len(CASES), 6, n)) * 1e3,
        points=pts,
        groups={"journal_fillet_1": np.arange(n)},
        node_ids=np.arange(n),
        cases=CASES,
    )
    th = np.linspace(0.0, 4 * np.pi, 720, endpoint=False)
    pin = np.column_stack([3e3 * np.sin(th), 2e4 * np.cos(th) + 5e3])
    co = load_coefficients(pin, 400.0 * np.sin(2 * th) + 150.0, 293.0, cases=CASES, torque_mz=-1.0)
    return us, th, co


def threaded(n: int, threads: int, repeat: int) -> None:
    from fe_crank.assess import fatigue
    from fe_crank.assess.group import assess_group
    from fe_crank.assess.workers import run_blocks
    from fe_crank.io.material import load_material

    h = paths(n)
    planes = np.ascontiguousarray(h.transpose(1, 0, 2))
    B = fatigue.NODE_BLOCK

    def blocks(k):
        amp = np.empty(n)

        def one(s, _scratch):
            amp[s : s + B] = fatigue.amplitude_mean(planes[:, :, s : s + B].transpose(1, 0, 2))[0]

        run_blocks(one, range(0, n, B), k)
        return amp

    us, th, co = _synthetic_group(n)
    mat = load_material("42CrMo4")

    def group(k):
        return assess_group(
            us,
            "journal_fillet_1",
            co,
            th,
            mat,
            crank_radius=0.0,
            overspeed=330.0,
            overspeed_coefficients=1.3 * co,
            threads=k,
        )

    print(
        f"{n} nodes x 720 angles, 1 vs {threads} threads, best of {repeat}; "
        f"cores of this process {len(os.sched_getaffinity(0))}; load average {os.getloadavg()[0]:.2f}"
    )
    for what, fn, same in (
        ("fatigue blocks (amplitude_mean)", blocks, np.array_equal),
        (
            "assess_group",
            group,
            lambda a, b: a == b and all(np.array_equal(a.fields[k], b.fields[k]) for k in a.fields),
        ),
    ):
        best = {1: (np.inf, np.inf), threads: (np.inf, np.inf)}
        outs = {}
        for _ in range(repeat):
            for k in (1, threads):
                w, c, outs[k] = _wall_cpu(lambda fn=fn, k=k: fn(k))
                best[k] = (min(best[k][0], w), min(best[k][1], c))
        (w1, c1), (wn, cn) = best[1], best[threads]
        print(
            f"{what}: wall {w1:.3f} -> {wn:.3f} s ({w1 / wn:.2f}x), CPU {c1:.3f} -> {cn:.3f} s "
            f"(parallelism CPU/wall {c1 / w1:.2f} -> {cn / wn:.2f}); identical: {same(outs[1], outs[threads])}"
        )
    # the interpreter's share of a block, measured in one thread (so whatever the load):
    # the same calls on a 1-node, 32-angle path, where the array kernels do next to
    # nothing, take about the time a block spends outside the kernels, holding the lock
    tiny = paths(1, n_t=32)
    n_blocks = -(-n // B)
    reps = 20 * n_blocks
    t_tiny, _ = cpu(lambda: [fatigue.amplitude_mean(tiny) for _ in range(reps)], 3)
    t_full, _ = cpu(lambda: blocks(1), 3)
    held = t_tiny / reps * n_blocks
    print(
        f"fatigue blocks, one thread: {t_full:.3f} s CPU, of which interpreter overhead (the same calls "
        f"on 1 node x 32 angles) {held:.3f} s = {100 * held / t_full:.0f} %: the share that holds the lock; "
        f"Amdahl bound on 2 cores {1 / (held / t_full + (1 - held / t_full) / 2):.2f}x"
    )
    print(f"load average at the end {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    sys.exit(main())
