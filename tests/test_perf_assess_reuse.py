"""Work the assessment of one load case no longer repeats, with the same results.

* The counterweights' mass properties (an OpenCASCADE build of the throw and its B-rep
  integrals, ``geometry.mass``) are computed once per distinct solid: throws that differ
  only in name and angle are one solid, because ``geometry.throw.add_throw`` builds a
  throw in its own frame from the geometry and the throw's counterweights.  Checked on
  the shipped inline-four geometry (throws 1 and 4 carry bolted counterweights at 0 deg,
  throws 2 and 3 the default ones at 180 deg): two builds for four throws, and every
  throw's counterweight data equal (dataclass equality, exact) to its own build.
* Keys of one load case whose FE solution is the same object (equal meshes, solved once by
  the check) share its unit stresses: the whole shipped cases give the same results.json,
  every figure equal (``benchmarks/compare_results.py --rtol 0``, docs/performance.md);
  here the cheap part, the grouping of equal solids, is tested.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest

import fe_crank.io.geometry as geo_io
from fe_crank.assess.adapters import counterweights_of

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def inline4():
    return geo_io.load_geometry(ROOT / "geometry" / "inline4.toml")


def test_equal_throw_solids_are_built_once_with_the_same_counterweight_data(inline4):
    names = [t.name for t in inline4.throws]
    assert names == ["1", "2", "3", "4"]
    solids: list = []
    shared = {n: counterweights_of(inline4, n, 0.1 * i, "main", None, solids=solids) for i, n in enumerate(names)}
    assert len(solids) == 2  # {1, 4} and {2, 3}
    for i, n in enumerate(names):
        own = counterweights_of(inline4, n, 0.1 * i, "main", None)
        assert shared[n] == own and own, n


def test_a_different_counterweight_is_another_solid(inline4):
    t1 = inline4.throw("1")
    cw = tuple(dataclasses.replace(c, outer_radius=c.outer_radius - 0.005) for c in t1.counterweights)
    g = dataclasses.replace(inline4, throws=inline4.throws + (dataclasses.replace(t1, name="5", counterweights=cw),))
    solids: list = []
    a = counterweights_of(g, "1", 0.0, "main", None, solids=solids)
    b = counterweights_of(g, "5", 0.0, "main", None, solids=solids)
    assert len(solids) == 2
    assert b[0].built_unbalance < a[0].built_unbalance  # the smaller sector, its own build
