"""FE stage: shaft-shoulder fillet Kt against the Peterson/Roark fit, convergence.

Reference: Roark's Formulas for Stress and Strain, 7th ed. (Young & Budynas), Table 17.1
case 17b (square shoulder with fillet in a circular shaft, bending), a fit of Peterson's
data: Kt = C1 + C2 (2h/D) + C3 (2h/D)^2 + C4 (2h/D)^3, sigma_nom = 32 M / (pi d^3).
FE studies (Tipton, Sorem & Rolovic, J. Mech. Des. 118 (1996) 321) found the chart values
low for small r/d; the geometry here (r/d = 0.2, D/d = 1.5) is where the fit is good.
"""

from __future__ import annotations

import numpy as np
import pytest
from helpers.verification_meshes import stepped_shaft

from fe_crank.fe import Coupling, build_system
from fe_crank.fe.core.stress import averaging_indicator, principal, stress_at_nodes

E, NU = 210e9, 0.3
ALL6 = ("ux", "uy", "uz", "rx", "ry", "rz")
D_SMALL, D_LARGE, R_FILLET = 0.02, 0.03, 0.004
FILLET_SIZES = (1.0, 1 / 2, 1 / 3, 1 / 4, 1 / 6)  # element size on the fillet / r


def roark_kt_bending(d: float, D: float, r: float) -> float:
    """Roark 7th ed. Table 17.1 case 17b, 0.25 <= h/r <= 20, h = (D - d)/2."""
    h = (D - d) / 2
    q = h / r
    s = np.sqrt(q)
    if q <= 2.0:
        c = (
            0.927 + 1.149 * s - 0.086 * q,
            0.015 - 3.281 * s + 0.837 * q,
            0.847 + 1.716 * s - 0.506 * q,
            -0.790 + 0.417 * s - 0.246 * q,
        )
    else:
        c = (
            1.225 + 0.831 * s - 0.010 * q,
            -3.790 + 0.958 * s - 0.257 * q,
            7.374 - 4.834 * s + 0.862 * q,
            -3.809 + 3.046 * s - 0.595 * q,
        )
    x = 2 * h / D
    return c[0] + c[1] * x + c[2] * x**2 + c[3] * x**3


def test_roark_fit_reproduces_a_chart_value():
    # Peterson chart (stepped shaft in bending), D/d = 1.5, r/d = 0.1: Kt ~ 1.7
    assert roark_kt_bending(0.02, 0.03, 0.002) == pytest.approx(1.73, abs=0.01)


@pytest.fixture(scope="module")
def series():
    out = []
    M = 10.0
    for frac in FILLET_SIZES:
        mesh = stepped_shaft(D_SMALL, D_LARGE, R_FILLET, fillet_size=frac * R_FILLET, size=0.005)
        s = build_system(mesh, E, NU, couplings=[Coupling("end_2", fixed=ALL6), Coupling("end_1")])
        load = {"end_1": np.array([0, 0, 0, M, 0, 0.0])}
        zero = np.zeros(3 * s.basis.N)
        u = s.solve(zero, [load])
        assert s.equilibrium_error(u, zero, load)[0] < 1e-6
        sig = stress_at_nodes(mesh, u, E, NU)
        nodes = s.basis.get_dofs(mesh.boundaries["fillet"]).all()
        kt = principal(sig[:, nodes])[0].max() / (32 * M / (np.pi * D_SMALL**3))
        ind = averaging_indicator(mesh, u, E, NU, ["fillet"])["fillet"]
        out.append((frac * R_FILLET, kt, ind, s.n_dof))
    return out


@pytest.mark.heavy
def test_fillet_kt_matches_roark_within_5_percent(series):
    h, kt, ind, _ = series[3]  # fillet elements r/4 (M53 guidance)
    assert kt == pytest.approx(roark_kt_bending(D_SMALL, D_LARGE, R_FILLET), rel=0.05)
    assert abs(ind) < 0.05  # M53 averaged vs unaveraged check


@pytest.mark.heavy
def test_fillet_peak_stress_converges_with_a_fitted_rate(series):
    h = np.array([x[0] for x in series])
    kt = np.array([x[1] for x in series])
    err = np.abs(kt[:-1] - kt[-1])  # against the finest mesh
    rate = np.polyfit(np.log(h[:-1]), np.log(err), 1)[0]
    assert rate > 1.0
    assert np.all(np.diff(kt) > -0.005 * kt[-1])  # monotone from below, up to noise
    assert err[-1] < 0.01 * kt[-1]  # r/4 within 1 % of r/6
