"""The counterweight-to-web transition fillet is assessed for fatigue like the shaft fillets:
its stress cycles with the pin force and the torque.  A real small throw (fillet r_c = 3 mm)
under a fully reversed torque T_a cos(theta): the history at every node is proportional,
S(theta) = T_a cos(theta) S_t, so the equivalent amplitude is T_a vM(S_t) and Goodman's n
is k sigma_W / (T_a max vM(S_t)) over the fillet's nodes (zero mean), with k the fillet's
own factors: as-forged surface (unless stated), the size factor's 254-mm fallback (no
section diameter), 50 % reliability here."""

from __future__ import annotations

import numpy as np
import pytest

from fe_crank.assess import ThrowContext, assess_throw, unit_stresses
from fe_crank.assess.factors import size_factor
from fe_crank.assess.stress import von_mises
from fe_crank.io.geometry import geometry_from_dict
from fe_crank.io.material import load_material


@pytest.mark.heavy
def test_counterweight_fillet_fatigue_under_reversed_torque():
    from helpers.counterweights import square_cornered_throw as _small

    from fe_crank.fe import solve_unit_cases
    from fe_crank.mesh import MeshOptions, mesh_throw

    g = geometry_from_dict(_small("3 mm"), "g.toml")
    tm = mesh_throw(g, size=MeshOptions(coarse_divisions=1.5, fillet_divisions=1.0, grading=2.0), cache_dir=None)
    mat = load_material("C45", reliability=0.5)
    units = solve_unit_cases(tm, mat)
    unit = unit_stresses(units)
    assert {"counterweight_fillet_1", "counterweight_fillet_2"} <= set(unit.groups)
    theta = np.deg2rad(np.arange(360.0))
    t_a = 40.0
    t = assess_throw(
        ThrowContext(
            "1",
            unit,
            theta,
            np.zeros((360, 2)),
            t_a * np.cos(theta),
            omega=0.0,
            overspeed=None,
            material=mat,
            crank_radius=0.02,
        )
    )
    by = {grp.group: grp for grp in t.groups}
    k = 272.0 * 580.0**-0.995 * size_factor(None)  # as forged 0.48376 x 0.63300, k_e = 1
    s_t = unit.stress[unit.cases.index("torque")] * (t_a / abs(unit.torque_mz))
    for name in ("counterweight_fillet_1", "counterweight_fillet_2"):
        grp = by[name]
        exact = von_mises(s_t[:, unit.groups[name]])
        assert grp.fatigue_factors.surface == pytest.approx(272.0 * 580.0**-0.995, rel=1e-12)
        assert grp.additional_bending == 0.0  # UR M53's sigma_add belongs to the shaft fillets
        assert grp.fatigue_safety.value == pytest.approx(k * 290e6 / exact.max(), rel=1e-9)
    # the counterweight bodies themselves keep their stress criteria only
    assert by["counterweight_1"].fatigue_safety is None
