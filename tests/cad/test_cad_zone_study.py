"""The hot-spot convergence study by zones on a drawn throw (``fe.refinement.zone_study``
with ``cad.zone.cad_zone_solid``) against the full re-mesh of the drawn throw.

The shipped single-cylinder throw (shaft fillets, counterweight transition fillets, an
oil bore) exported to STEP (``helpers.cad_files.parametric_step``, once in the run:
``tests/cad/conftest.py``), meshed by the CAD route at the ``test`` preset and solved for
real; the study's refined level r/2 from the zones cut from the drawn solid equals the
whole drawn throw re-meshed and re-solved at r/2 within ``NOISE_TOL`` of its family.

The tolerances are the zones' difference from the full re-mesh at ``test``, measured over
five round-off realisations of the drawing (``benchmarks/verification/mesh_scatter.py
--only zones``: the file translated along the crank axis by k x 10 nm, k = 0 the file
this test meshes; each realisation is another pair of meshes of the same solid), twice
the largest, rounded up to a whole per cent:

* shaft fillets: -0.7 % to +0.4 % under the pin force, -2.0 % to -0.6 % under the torque: 4 %;
* counterweight fillets: -4.8 % to -1.6 % and -0.5 % to +2.0 %: 10 %;
* the oil bore, whose peak is the largest of a plateau of averaged nodal stresses on its
  wall, each mesh picking another node (docs/fe.md):
  -9.7 % to -0.3 % and -8.3 % to -2.9 %: 20 %.

At ``test`` a fillet is about one element across at r/1, and the zones are driven by that
solution: the counterweight fillets and the outlet read low here, by more than at
``coarse``, where the zones are within about 1 % of the full re-mesh at the fillets and a
few per cent at the outlet (docs/performance.md, "The hot-spot convergence study").  This
test holds the drawn route's zones to the full re-mesh at the test mesh's scatter; the
accuracy claim is the coarse benchmark's.  The refined level is r/2, as in the parametric test
(tests/fe/test_fe_zone_study.py): at r/1.5 the drawn throw's full mesh is the noisier
one.
"""

from __future__ import annotations

import dataclasses

import pytest
from helpers.drawn_zones import LOADS, OPTIONS, zones_and_full
from helpers.shared import copy_of, locked
from helpers.verification_meshes import Steel

from fe_crank.cad import CadInput, mesh_cad_throw
from fe_crank.fe import solve_unit_cases
from fe_crank.fe.refinement.convergence import zones_apply
from fe_crank.fe.refinement.levels import COUNTERWEIGHT_PREFIX, OIL_BORE_PREFIX
from fe_crank.fe.refinement.zone_study import zone_solid

#: by the entry's family (module doc): shaft fillets, counterweight fillets, the oil-bore outlet
NOISE_TOL = {"": 0.04, COUNTERWEIGHT_PREFIX: 0.10, OIL_BORE_PREFIX: 0.20}


@pytest.mark.heavy  # the drawn throw's zones at r/2, and the whole drawn throw at r/2 for the comparison
def test_drawn_throw_zone_study_equals_its_full_refinement(
    tmp_path, tmp_path_factory, single_cylinder_step, mesh_cache
):
    g, step = single_cylinder_step
    cad = CadInput(copy_of(step, tmp_path / "throw.step"), density=g.density)
    with locked(tmp_path_factory, "single_cylinder_test_meshes"):  # the mesh tests/cad/test_cad_check.py takes too
        tm = mesh_cad_throw(cad, "1", size="test", cache_dir=mesh_cache)
    opts = OPTIONS
    units = solve_unit_cases(tm, Steel(), opts)
    units.system.factorisation.free()
    # the check's study takes the zones for a drawn throw, not the whole-throw re-mesh
    assert zones_apply(cad, (tm, units), LOADS, dataclasses.replace(opts, cases=()))
    solid = zone_solid(cad, tm)
    assert solid.throw == "1" and solid.label == "throw.step"
    assert solid.lengths == pytest.approx(
        {"counterweight_fillet_1": 0.005, "counterweight_fillet_2": 0.005, "oil_bore": g.oil_bore.diameter}
    )
    zones, full = zones_and_full(cad, tm, units, mesh_cache)
    assert zones.method == "zones" and zones.levels[1].zones > 0 and full.method == "full"
    assert zones.levels[1].n_dof < full.levels[1].n_dof
    assert set(zones.changes) == set(full.changes)
    assert len(full.changes) == 6  # shaft fillets, counterweight fillets, oil bore under each load set
    for name in full.changes:
        assert zones.levels[0].peaks[name] == full.levels[0].peaks[name]  # the assessed mesh's own
        family = next((p for p in (COUNTERWEIGHT_PREFIX, OIL_BORE_PREFIX) if name.startswith(p)), "")
        assert zones.levels[1].peaks[name] == pytest.approx(full.levels[1].peaks[name], rel=NOISE_TOL[family]), name
