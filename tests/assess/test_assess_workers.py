"""The assess stage's blocks of nodes and their worker threads (``assess.workers``): the
results do not depend on the block size or on the thread count.

A block of nodes reads only its own unit stresses and writes only its own slice, and the
unit-stress recovery treats every displacement field on its own (``assess.workers``), so
threads change where the operations run, never which operations on which operands: the
per-node fields, the extremes and the unit stresses must be equal with
``np.array_equal`` (no tolerance: a block written to the wrong slice, a scratch buffer
shared by two threads or a reduction in another order changes values by far more than
nothing).  Real gmsh mesh with real fillets, real scikit-fem solves; blocks of 16 nodes so
that each group has many blocks and the threads interleave.  Blocks of 128 nodes against
one block of every node: the per-node results to 1e-12 (the history products may differ
in the last bit between block sizes).

The worker count: the cores of the process's affinity shared among the batch's processes
(``pipeline.options.assess_threads``), checked against ``os.sched_getaffinity``.
"""

from __future__ import annotations

import os
import threading

import numpy as np
import pytest

from fe_crank.assess import assessed_groups, unit_stresses
from fe_crank.assess.group.assessment import assess_group
from fe_crank.assess.superpose import load_coefficients
from fe_crank.assess.throw import ThrowContext, assess_throw
from fe_crank.assess.workers import run_blocks
from fe_crank.assess.workers import threads as threads_context
from fe_crank.io.material import load_material
from fe_crank.pipeline.options import CheckOptions, assess_threads, cores_available

FIELDS = ("node_ids", "max_von_mises", "amplitude", "mean", "fatigue_safety", "gough_pollard_safety")


def _loads(n=72):
    th = np.linspace(0.0, 4 * np.pi, n, endpoint=False)
    pin = np.column_stack([3e3 * np.sin(th), 2e4 * np.cos(th) + 5e3])
    return th, pin, 400.0 * np.sin(2 * th) + 150.0


def _same_group(a, b):
    assert a == b  # dataclass equality: every extreme, factor, safety
    for k in FIELDS:
        assert np.array_equal(a.fields[k], b.fields[k]), k


@pytest.mark.heavy
def test_unit_stresses_on_threads_equal_one_thread_bitwise(filleted_throw):
    groups = assessed_groups(filleted_throw)
    one = unit_stresses(filleted_throw, groups)
    for threads in (2, 4, 50):  # 50: more threads than cases, one case each
        with threads_context(threads):
            got = unit_stresses(filleted_throw, groups)
        assert got.cases == one.cases
        assert np.array_equal(got.stress, one.stress), threads
        assert np.array_equal(got.node_ids, one.node_ids)


@pytest.mark.heavy
def test_assess_group_on_threads_equals_one_thread_bitwise(filleted_throw):
    us = unit_stresses(filleted_throw)
    th, pin, torque = _loads()
    co = load_coefficients(pin, torque, 300.0, cases=us.cases, torque_mz=us.torque_mz)
    mat = load_material("42CrMo4")
    kw = dict(crank_radius=0.045, overspeed=360.0, overspeed_coefficients=1.44 * co, chunk=16)
    for g in sorted(us.groups):
        assert us.groups[g].size > 3 * 16, g  # several blocks per group, so threads interleave
        one = assess_group(us, g, co, th, mat, **kw)
        for threads in (2, 3):
            with threads_context(threads):
                _same_group(assess_group(us, g, co, th, mat, **kw), one)


@pytest.mark.heavy
def test_assess_group_does_not_depend_on_the_block(filleted_throw_cycle):
    """128-node blocks against one block of every node: the per-node results to 1e-12
    (the history products may differ in the last bit between block sizes)."""
    us, co = filleted_throw_cycle
    theta = np.linspace(0.0, 4 * np.pi, co.shape[0], endpoint=False)
    mat = load_material("42CrMo4")
    kw = dict(crank_radius=0.045, overspeed=360.0, overspeed_coefficients=1.44 * co)
    for g in ("journal_fillet_1", "crankpin_fillet_2"):
        a = assess_group(us, g, co, theta, mat, **kw)
        b = assess_group(us, g, co, theta, mat, chunk=10**6, **kw)
        assert a.max_von_mises == b.max_von_mises and a.max_von_mises_overspeed == b.max_von_mises_overspeed
        for k in ("max_von_mises", "amplitude", "mean", "fatigue_safety", "gough_pollard_safety"):
            x, y = a.fields[k], b.fields[k]
            fin = np.isfinite(y)
            np.testing.assert_array_equal(np.isfinite(x), fin)
            assert np.abs(x[fin] - y[fin]).max() <= 1e-12 * np.abs(y[fin]).max(), (g, k)


@pytest.mark.heavy
def test_assess_throw_on_threads_equals_one_thread_bitwise(filleted_throw):
    """The whole throw (every group, static, overspeed, both fatigue criteria) through
    ``assess_throw``, as ``assess_case`` calls it."""
    us = unit_stresses(filleted_throw)
    th, pin, torque = _loads()
    mat = load_material("42CrMo4")
    kw = dict(omega=300.0, overspeed=360.0, material=mat, crank_radius=0.045)
    one = assess_throw(ThrowContext("t", us, th, pin, torque, **kw))
    with threads_context(2):
        two = assess_throw(ThrowContext("t", us, th, pin, torque, **kw))
    assert len(one.groups) == len(two.groups) > 0
    for a, b in zip(one.groups, two.groups):
        _same_group(a, b)


def test_run_blocks_calls_every_item_once_with_a_buffer_per_thread():
    seen, owners = [], {}
    lock = threading.Lock()

    def fn(item, scratch):
        scratch.setdefault("owner", threading.get_ident())
        with lock:
            seen.append(item)
            owners.setdefault(id(scratch), set()).add(scratch["owner"])

    run_blocks(fn, range(200), threads=3)
    assert sorted(seen) == list(range(200))
    assert all(len(o) == 1 for o in owners.values())  # no scratch dict shared by two threads
    assert 1 <= len(owners) <= 3
    seen.clear()
    run_blocks(fn, range(5), threads=1)
    assert seen == list(range(5))  # one thread: in order


def test_run_blocks_raises_a_blocks_error():
    def fn(item, _scratch):
        if item == 7:
            raise ValueError("block 7")

    with pytest.raises(ValueError, match="block 7"):
        run_blocks(fn, range(20), threads=2)


def test_assess_threads_share_the_affinity_among_the_batch_processes():
    cores = len(os.sched_getaffinity(0))
    assert cores_available() == cores
    assert assess_threads(CheckOptions()) == cores  # one process: every core
    assert assess_threads(CheckOptions(), processes=2) == max(1, cores // 2)
    assert assess_threads(CheckOptions(), processes=cores + 1) == 1  # never 0
    assert assess_threads(CheckOptions(assess_threads=3), processes=2) == 3  # an explicit value wins
