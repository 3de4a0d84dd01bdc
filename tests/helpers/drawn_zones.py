"""The drawn throw's study at r/2 by both methods, as the zone test compares them and the
scatter benchmark repeats it over realisations of the drawing
(tests/cad/test_cad_zone_study.py, benchmarks/verification/mesh_scatter.py)."""

from __future__ import annotations

from pathlib import Path

from fe_crank.cad import CadInput
from fe_crank.fe import FeOptions
from fe_crank.fe.refinement.convergence import fillet_convergence
from fe_crank.fe.refinement.levels import ConvergenceStudy
from fe_crank.fe.refinement.zone_study import zone_convergence
from fe_crank.mesh import PRESETS
from helpers.verification_meshes import Steel

#: the load sets compared: the pin force with the centrifugal load, and a torque
LOADS = {"pin force": {"pin_-y": 1.0e5, "centrifugal": 250.0**2}, "torque": {"torque": 5.0e3}}
#: the unit cases they need
CASES = ("centrifugal", "pin_-y", "torque")
OPTIONS = FeOptions(cases=CASES)


def zones_and_full(cad: CadInput, tm, units, cache_dir: Path) -> tuple[ConvergenceStudy, ConvergenceStudy]:
    """The study's levels r/1 and r/2 of the drawn throw mesh ``tm`` (solved: ``units``) by
    zones and by the whole throw re-meshed at ``test`` (into ``cache_dir``)."""
    zones = zone_convergence(cad, Steel(), tm, units, LOADS, factors=(1.0, 2.0))
    full = fillet_convergence(
        cad,
        Steel(),
        throw=tm.throw,
        base=PRESETS["test"],
        loads=LOADS,
        fe_options=OPTIONS,
        factors=(1.0, 2.0),
        cache_dir=cache_dir,
        first=(tm, units),
    )
    return zones, full
