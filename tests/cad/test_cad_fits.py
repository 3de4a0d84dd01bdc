"""CAD route: the fitted numbers of a drawing are the same on every machine.

A face's fit (``fe_crank.cad.survey``: a least-squares circle, an eigenvector of the
normals) ends in the linear-algebra library, whose kernels, and so whose last bits and
the sign of an eigenvector, depend on the processor; gmsh turns a last-bit change of a
cut or a size field into another mesh.  The fits are therefore rounded (lengths to 1 nm,
direction cosines to 1e-12, an axis's sense fixed) and the throw frame's products summed
in a fixed order (``fe_crank.cad.frame.turn``).  Checked here: the rounding against
closed forms; the recognised single-cylinder throw equal to its specification exactly
(``geometry/single_cylinder.toml``: millimetre dimensions are multiples of the quantum);
and the recognition in another process with OpenBLAS's kernels for another processor
(``OPENBLAS_CORETYPE``: the unrounded fits gave a fillet's spine radius and an oil bore's
direction that differed in the last bit there, the bore's axis of the opposite sense, and
a drawn mesh of another node count) bit for bit the same as in this one.
"""

from __future__ import annotations

import dataclasses
import math
import os
import pickle
import subprocess
import sys

import numpy as np
import pytest
from helpers.shared import copy_of

from fe_crank.cad import CadInput, recognise
from fe_crank.cad.frame import turn
from fe_crank.cad.survey import snap_direction, snap_length, snap_point


def test_a_fitted_length_is_its_nanometre():
    assert snap_length(0.027999999999999997) == 0.028  # a fit's last bit off a 28 mm radius
    assert snap_length(2.25 * 0.0254 * (1 + 1e-15)) == 0.05715  # 2.25 in: a multiple of 1 nm
    assert snap_length(-3e-18) == 0.0
    assert list(snap_point(np.array([1e-17, -0.0235000000000000001, 0.1]))) == [0.0, -0.0235, 0.1]


def test_a_fitted_axis_is_rounded_renormalised_and_of_one_sense():
    assert list(snap_direction(np.array([1e-17, -2e-17, -1.0]))) == [0.0, 0.0, 1.0]
    assert list(snap_direction(np.array([-1.0, 3e-17, 0.0]))) == [1.0, 0.0, 0.0]
    c = math.sqrt(0.5)
    d = snap_direction(np.array([c * (1 + 1e-16), 0.0, -c]))
    # the cosines rounded to 12 decimals, then scaled to unit length in correctly rounded arithmetic
    r = round(c, 12)
    assert list(d) == [r / math.sqrt(math.fsum([r * r, r * r])), 0.0, -r / math.sqrt(math.fsum([r * r, r * r]))]
    assert math.fsum(v * v for v in d) == pytest.approx(1.0, abs=1e-15)


def test_the_frame_turns_points_as_the_matrix_product():
    rng = np.random.default_rng(7)
    m = np.linalg.qr(rng.normal(size=(3, 3)))[0]
    p = rng.normal(size=(5, 3))
    assert turn(m, p) == pytest.approx(p @ m.T, abs=1e-15)
    assert turn(m, p[0]) == pytest.approx(m @ p[0], abs=1e-15)


def _floats(o, path: str = "features") -> dict[str, str]:
    """Every number of ``o`` (dataclasses, tuples, dicts, arrays) by its path, as hex."""
    out: dict[str, str] = {}
    if dataclasses.is_dataclass(o):
        for f in dataclasses.fields(o):
            out.update(_floats(getattr(o, f.name), f"{path}.{f.name}"))
    elif isinstance(o, (tuple, list)):
        for i, x in enumerate(o):
            out.update(_floats(x, f"{path}[{i}]"))
    elif isinstance(o, dict):
        for k, x in o.items():
            out.update(_floats(x, f"{path}[{k}]"))
    elif isinstance(o, np.ndarray):
        out[path] = o.tobytes().hex() if o.dtype.kind == "f" else repr(o.tolist())
    elif isinstance(o, float):
        out[path] = float.hex(o)
    else:
        out[path] = repr(o)
    return out


RECOGNISE = """
import pickle, sys
from pathlib import Path
from fe_crank.cad import CadInput, recognise
features = recognise(CadInput(Path(sys.argv[1]), density=float(sys.argv[2])))
Path(sys.argv[3]).write_bytes(pickle.dumps(features))
"""


@pytest.mark.heavy  # two recognitions of the single-cylinder throw, one in another process
def test_the_recognition_is_the_same_with_another_processors_kernels(tmp_path, single_cylinder_step):
    g, shared = single_cylinder_step
    step = copy_of(shared, tmp_path / "throw.step")
    here = recognise(CadInput(step, density=g.density))
    t = here.throws[0]
    # millimetre dimensions recognised as their decimal values, not a fit's last bits away
    assert t.crank_radius == g.crank_radius
    assert t.crankpin.diameter == g.crankpin_diameter
    assert [j.diameter for j in t.journals] == [g.journal_diameter] * 2
    assert {f.name: f.radius for f in t.fillets} == {
        "crankpin_fillet_1": g.crankpin_fillet,
        "crankpin_fillet_2": g.crankpin_fillet,
        "journal_fillet_1": g.journal_fillet,
        "journal_fillet_2": g.journal_fillet,
    }
    env = {**os.environ, "OPENBLAS_CORETYPE": "Prescott", "OPENBLAS_NUM_THREADS": "1"}
    out = tmp_path / "features.pickle"
    subprocess.run(
        [sys.executable, "-c", RECOGNISE, str(step), repr(g.density), str(out)], env=env, check=True, timeout=300
    )
    there = pickle.loads(out.read_bytes())
    a, b = _floats(here), _floats(there)
    assert a.keys() == b.keys()
    assert [k for k in a if a[k] != b[k]] == []
