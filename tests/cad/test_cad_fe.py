"""CAD route, the mesh and the FE: a parametric throw exported to STEP and meshed by the
CAD route has the parametric mesh's named groups and fillet radii, and its fillet peak
stresses under the FE unit cases agree with the parametric route's.

Tolerance of the peaks: 6 %.  Both meshes are of the ``test`` preset (fillet edges about
the radius), whose fillet peaks lie a few per cent from converged ones (docs/geometry.md:
2-6 % below the ``coarse`` preset on the shipped cases); two different meshes of one
solid at that size differ by as much, the node that holds a peak sitting elsewhere on
the fillet.  Measured on this throw: at most 4.1 % apart over the four unit cases and
both fillet pairs (0.9 % between the parametric route's mirrored and whole meshes, which
share their surface mesh); with fillet edges of r/3 the two routes agree within 0.8 %
(docs/geometry.md, "Geometry from CAD").

The shipped throws (the single cylinder's through the check, tests/cad/test_cad_check.py):
at the ``test`` preset the two routes' peaks scatter with the meshes, and within 0.6 % on
the V4 with fillet edges of r/3.  The scatter measured over round-off realisations of
each route (``benchmarks/verification/mesh_scatter.py --only throws``: the drawing
translated along the axis by k x 10 nm, the parametric crank radius times 1 + k 1e-12,
k = 0..4, k = 0 the files this test meshes; each realisation another mesh of the same
solid): over the 25 pairs, drawn against parametric, the V4's crankpin fillets under the
pin force in y -5.0 % to +24.0 % (the drawn meshes alone 6351-7796 Pa per unit load, the
parametric 6289-6683), its journal fillets -10.8 % to +1.4 %, the inline-4's -11.4 % to
+13.6 %; asserted the largest, rounded up: 25 %.  (One pair of meshes, measured before
on another machine, had put it at 13.6 %.)"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pytest
from helpers.cad_files import parametric_step
from helpers.shared import locked

from fe_crank.assess.group.nodes import unit_stresses
from fe_crank.cad import CadInput, mesh_cad_throw, recognise
from fe_crank.cad.mesh import estimate_cad_elements
from fe_crank.fe import FeOptions, solve_unit_cases
from fe_crank.fe.core.stress import von_mises
from fe_crank.io.geometry import load_geometry
from fe_crank.mesh import mesh_throw

pytestmark = pytest.mark.heavy
TOL = 0.06
TOL_SHIPPED = 0.25  # the shipped throws' scatter at ``test`` (module doc)
CASES = ("centrifugal", "pin_x", "pin_y", "torque")
PAIRS = (("crankpin_fillet_1", "crankpin_fillet_2"), ("journal_fillet_1", "journal_fillet_2"))


@dataclass(frozen=True)
class Steel:
    youngs_modulus: float = 210e9
    poisson_ratio: float = 0.3
    density: float = 7850.0


def peaks(throw_mesh) -> dict[tuple[str, str], float]:
    """Largest von Mises stress over each mirror pair of fillets, per unit case (the pair,
    not one fillet: which of two mirror images holds the peak is round-off)."""
    us = unit_stresses(solve_unit_cases(throw_mesh, Steel(), FeOptions(cases=CASES)))
    out = {}
    for pair in PAIRS:
        idx = np.concatenate([us.groups[n] for n in pair])
        for i, case in enumerate(us.cases):
            out[(pair[0], case)] = float(von_mises(us.stress[i][:, idx]).max())
    return out


def test_the_cad_mesh_of_an_exported_throw_matches_the_parametric_one(small_throw_step, mesh_cache):
    g, step = small_throw_step
    param = mesh_throw(g, size="test", cache_dir=mesh_cache)
    # throw "1" named, as the check and ``fe-crank mesh`` name it: the same cache entry as theirs
    cad = mesh_cad_throw(CadInput(step, density=g.density), "1", size="test", cache_dir=mesh_cache)
    assert cad.throw == "1" and cad.symmetry == () and cad.options == param.options
    assert set(cad.mesh.boundaries) == set(param.mesh.boundaries)
    assert set(cad.mesh.subdomains) == set(param.mesh.subdomains)
    assert cad.fillet_radii == pytest.approx(param.fillet_radii, abs=1e-9)
    assert cad.msh_path.is_file() and cad.vtu_path.is_file()
    # the element budget's estimate (fe_crank.geometry.estimate's rule) within a factor 3
    n = estimate_cad_elements(recognise(CadInput(step, density=g.density)).throws[0], cad.options)
    assert cad.stats.elements / 3 <= n <= 3 * cad.stats.elements
    again = mesh_cad_throw(CadInput(step, density=g.density), "1", size="test", cache_dir=mesh_cache)
    assert again.stats.from_cache and again.key == cad.key
    # the first throw given as None or by its index: the same throw, the same cache entry
    for which in (None, 0):
        same = mesh_cad_throw(CadInput(step, density=g.density), which, size="test", cache_dir=mesh_cache)
        assert same.stats.from_cache and same.key == cad.key and same.throw == "1"
    a, b = peaks(cad), peaks(param)
    for k in b:
        assert a[k] == pytest.approx(b[k], rel=TOL), k


@pytest.mark.parametrize("geometry", ["v4_90_pneumatic", "inline4"])
def test_the_shipped_throws_fillet_peaks_by_both_routes(root, tmp_path, tmp_path_factory, mesh_cache, geometry):
    g = load_geometry(root / "geometry" / f"{geometry}.toml")
    step = parametric_step(g, tmp_path / "throw.step")
    with locked(tmp_path_factory, f"{geometry}_test_mesh"):  # the run's one mesh of it (tests/mesh/test_mesh_throw.py)
        param = mesh_throw(g, size="test", cache_dir=mesh_cache)
    cad = mesh_cad_throw(CadInput(step, density=g.density), size="test", cache_dir=mesh_cache)
    assert set(cad.mesh.boundaries) == set(param.mesh.boundaries)
    assert cad.fillet_radii == pytest.approx(param.fillet_radii, abs=1e-9)
    a, b = peaks(cad), peaks(param)
    for k in b:
        assert a[k] == pytest.approx(b[k], rel=TOL_SHIPPED), k
