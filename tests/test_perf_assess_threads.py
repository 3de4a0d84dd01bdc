"""The assess stage on several threads gives the one-thread results bit for bit.

A block of nodes reads only its own unit stresses and writes only its own slice, and the
unit-stress recovery treats every displacement field on its own (``assess.workers``), so
threads change where the operations run, never which operations on which operands: the
per-node fields, the extremes and the unit stresses must be equal with
``np.array_equal`` (no tolerance: a block written to the wrong slice, a scratch buffer
shared by two threads or a reduction in another order changes values by far more than
nothing).  Real gmsh mesh with real fillets, real scikit-fem solves; blocks of 16 nodes so
that each group has many blocks and the threads interleave.

The worker count: the cores of the process's affinity shared among the batch's processes
(``check.options.assess_threads``), checked against ``os.sched_getaffinity``.
"""

from __future__ import annotations

import os
import threading

import numpy as np
import pytest
from verification_meshes import Steel, simple_throw

from fe_crank.assess import assessed_groups, unit_stresses
from fe_crank.assess.group import assess_group
from fe_crank.assess.superpose import load_coefficients
from fe_crank.assess.throw import assess_throw
from fe_crank.assess.workers import run_blocks
from fe_crank.check.options import CheckOptions, assess_threads, cores_available
from fe_crank.fe import FeOptions, solve_unit_cases
from fe_crank.io.material import load_material

FIELDS = ("node_ids", "max_von_mises", "amplitude", "mean", "fatigue_safety", "gough_pollard_safety")


@pytest.fixture(scope="module")
def units():
    mesh = simple_throw(size=0.012, fillet=0.004, fillet_size=0.004)
    cases = ("centrifugal", "pin_x", "pin_y", "pin_-x", "pin_-y", "torque")
    return solve_unit_cases(mesh, Steel(), FeOptions(solver="superlu", cases=cases))


def _loads(n=72):
    th = np.linspace(0.0, 4 * np.pi, n, endpoint=False)
    pin = np.column_stack([3e3 * np.sin(th), 2e4 * np.cos(th) + 5e3])
    return th, pin, 400.0 * np.sin(2 * th) + 150.0


def _same_group(a, b):
    assert a == b  # dataclass equality: every extreme, factor, safety
    for k in FIELDS:
        assert np.array_equal(a.fields[k], b.fields[k]), k


def test_unit_stresses_on_threads_equal_one_thread_bitwise(units):
    groups = assessed_groups(units)
    one = unit_stresses(units, groups)
    for threads in (2, 4, 50):  # 50: more threads than cases, one case each
        got = unit_stresses(units, groups, threads=threads)
        assert got.cases == one.cases
        assert np.array_equal(got.stress, one.stress), threads
        assert np.array_equal(got.node_ids, one.node_ids)


def test_assess_group_on_threads_equals_one_thread_bitwise(units):
    us = unit_stresses(units)
    th, pin, torque = _loads()
    co = load_coefficients(pin, torque, 300.0, cases=us.cases, torque_mz=us.torque_mz)
    mat = load_material("42CrMo4")
    kw = dict(crank_radius=0.045, overspeed=360.0, overspeed_coefficients=1.44 * co, chunk=16)
    for g in sorted(us.groups):
        assert us.groups[g].size > 3 * 16, g  # several blocks per group, so threads interleave
        one = assess_group(us, g, co, th, mat, **kw)
        for threads in (2, 3):
            _same_group(assess_group(us, g, co, th, mat, threads=threads, **kw), one)


def test_assess_throw_on_threads_equals_one_thread_bitwise(units):
    """The whole throw (every group, static, overspeed, both fatigue criteria) through
    ``assess_throw``, as ``assess_case`` calls it."""
    us = unit_stresses(units)
    th, pin, torque = _loads()
    mat = load_material("42CrMo4")
    kw = dict(omega=300.0, overspeed=360.0, material=mat, crank_radius=0.045)
    one = assess_throw("t", us, th, pin, torque, **kw)
    two = assess_throw("t", us, th, pin, torque, threads=2, **kw)
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
