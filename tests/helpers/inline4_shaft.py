"""The shipped inline-4's whole shaft as the parametric model builds it, analysed once per
test run (``helpers.shared.shared_value``).

``loadcases/inline4_rated.toml`` at its rated speed on ``test`` meshes: the whole-shaft
result (main-bearing loads with and without counterweights), the oil film of its
hydrodynamic bearings under those loads and each throw's fillet peaks.  The test files
that read this shaft (the oil film on it, and the drawn shaft compared with it) take the
one value, computed by whichever process needs it first and read back by the others.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest

from fe_crank.assess.group.extremes import Wanted, group_extremes
from fe_crank.assess.loads import FIRING
from fe_crank.assess.oil_film import FilmState, film_sweep
from fe_crank.assess.shaft import BearingState, piece_unit_stresses
from fe_crank.fe.shaft.whole_shaft import WholeShaftResult, analyse_whole_shaft, throw_masses
from fe_crank.geometry.shaft import ShaftLayout
from fe_crank.io.loadcase import LoadCase, load_loadcase
from fe_crank.io.material import Material
from fe_crank.mechanism.dynamics import DynamicsResult, analyse
from fe_crank.mesh.shaft import ShaftMesh
from helpers.paths import ROOT
from helpers.shared import shared_value

#: the fillet peaks alone: no fatigue criterion is read
STATIC = Wanted(fatigue=False, gough_pollard=False)
CASE = ROOT / "loadcases" / "inline4_rated.toml"


@dataclasses.dataclass(frozen=True)
class ShaftRun:
    """One whole shaft analysed: its layout, result, films and fillet peaks (Pa, by
    (throw, group)); ``mesh`` the shaft mesh when kept (``None`` in the shared value)."""

    layout: ShaftLayout
    result: WholeShaftResult
    peaks: dict[tuple[str, str], float]
    films: tuple[FilmState, ...]
    mesh: ShaftMesh | None = None


def rated_inline4() -> tuple[LoadCase, DynamicsResult]:
    """The load case and its operating cycle at the rated speed (``analyse``; the full-load
    curve's other speeds are not read)."""
    lc = load_loadcase(CASE)
    return lc, analyse(lc.engine, dataclasses.replace(lc.operating, full_load=None))


def fillet_peaks(cases, result, theta, material: Material, crank_radius: float) -> dict[tuple[str, str], float]:
    """Each throw's fillet peaks (von Mises over the operating cycle, Pa) by (throw, group):
    ``assess_shaft_throws``'s unit stresses and group code with only the static peak wanted
    (``group_extremes``: the peak an evaluation of every node gives, without the fatigue
    criteria)."""
    coeffs = result.cycles[0].weights
    out = {}
    for k, pp in enumerate(cases.model.pieces):
        if pp.kind != "throw":
            continue
        unit = piece_unit_stresses(cases, k, material)
        for group in sorted(unit.groups):
            if "fillet" in group and len(unit.groups[group]):
                x = group_extremes(unit, group, coeffs, theta, material, crank_radius=crank_radius, wanted=STATIC)
                out[str(pp.throw), group] = x.max_von_mises.value
    return out


def analyse_route(shaft_mesh: ShaftMesh, layout: ShaftLayout, lc: LoadCase, dyn: DynamicsResult, mass) -> ShaftRun:
    """``shaft_mesh`` of ``layout`` analysed at ``dyn`` (``analyse_whole_shaft``), its
    films and fillet peaks; the factorisations freed, the mesh kept."""
    assert layout.geometry is not None
    result, cases = analyse_whole_shaft(shaft_mesh, lc.material, dyn, mass=mass)
    peaks = fillet_peaks(cases, result, dyn.theta, lc.material, layout.geometry.crank_radius)
    films = film_sweep(layout, (BearingState(dyn.speed, FIRING, result.bearings),), result.crank_angle_deg)
    cases.model.free_factors()
    return ShaftRun(layout, result, peaks, films, cases.model.mesh)


def parametric_inline4(factory: pytest.TempPathFactory, mesh_cache: Path) -> ShaftRun:
    """The parametric model of ``loadcases/inline4_rated.toml``'s whole shaft at ``test``
    (``mesh_shaft`` into ``mesh_cache``), analysed once in the run (module doc); without
    its mesh."""

    def compute() -> ShaftRun:
        from fe_crank.mesh.shaft import mesh_shaft
        from fe_crank.pipeline.stages import shaft_layout

        lc, dyn = rated_inline4()
        layout = shaft_layout(lc)
        assert layout is not None
        sm = mesh_shaft(layout, size="test", cache_dir=mesh_cache)
        return dataclasses.replace(analyse_route(sm, layout, lc, dyn, throw_masses(layout)), mesh=None)

    return shared_value(factory, "inline4_parametric_shaft.pickle", compute)
