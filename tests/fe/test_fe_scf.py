"""SCF mode, FE part (UR M53 FE appendix, ``fe_crank.rules.m53.fe_cases``): stress measures, supports and
loads of its three cases on a real ``mesh_throw`` throw, checked against statics by hand.

The throw is tests/data/geometry_small.toml (D = 28 mm, D_G = 32 mm, L_pin = 18 mm,
W = 12 mm, B = 40 mm, L_journal = 12 mm, i.e. end faces at z = +-(9 + 12 + 12) = +-33 mm,
web centres at z = +-(9 + 6) = +-15 mm), meshed coarser than the ``test`` preset: these
tests check statics, which hold on any mesh.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest
from skfem import Basis, ElementTetP2

from fe_crank.fe.core.assembly import assemble_stiffness
from fe_crank.fe.core.stress import von_mises
from fe_crank.io.geometry import load_geometry
from fe_crank.mesh import MeshOptions, mesh_throw
from fe_crank.rules.m53.fe_cases import (
    PRINCIPAL_LIMIT,
    Peak,
    scf_stresses,
    solve_bending_torsion,
    solve_three_point,
    tau_equiv,
    web_centres_from_mesh,
)

ROOT = Path(__file__).resolve().parents[2]

Z_END, Z_WEB = 0.033, 0.015
OPTIONS = MeshOptions(coarse_divisions=1.2, fillet_divisions=0.8, grading=2.5)


@dataclass(frozen=True)
class Steel:
    youngs_modulus: float = 210e9
    poisson_ratio: float = 0.3


@pytest.fixture(scope="module")
def throw(tmp_path_factory):
    g = load_geometry(ROOT / "tests" / "data" / "geometry_small.toml")
    return mesh_throw(g, size=OPTIONS, cache_dir=tmp_path_factory.mktemp("cache"))


def test_stress_measures_closed_form():
    """tau_equiv (App. III 3.1.2) = (s1 - s3)/2: pure shear tau -> tau; uniaxial s -> s/2;
    von Mises of pure shear = sqrt(3) tau (bending measure of 3.2.2)."""
    shear = np.array([0, 0, 0, 5.0, 0, 0])[:, None]
    uni = np.array([8.0, 0, 0, 0, 0, 0])[:, None]
    assert tau_equiv(shear)[0] == pytest.approx(5.0, rel=1e-12)
    assert tau_equiv(uni)[0] == pytest.approx(4.0, rel=1e-12)
    assert von_mises(shear)[0] == pytest.approx(5.0 * np.sqrt(3), rel=1e-12)
    # App. III 2.3: a refined mesh is needed only when neither criterion holds
    p = Peak("g", 1.0, 0, (0, 0, 0), principal_ratio=PRINCIPAL_LIMIT * 1.01, averaging=0.01)
    assert not p.principal_ok and p.averaging_ok and p.mesh_ok
    assert not Peak("g", 1.0, 0, (0, 0, 0), 0.05, 0.06).mesh_ok


@pytest.fixture(scope="module")
def three_point(throw):
    """App. III 3.3's simply supported throw solved (``solve_three_point``, E = 210 GPa,
    nu = 0.3): its system, displacement and load, read by the tests of both its supports
    and its reactions."""
    return solve_three_point(throw.mesh, 210e9, 0.3)


def test_end_faces_are_the_bearing_centre_planes(throw, three_point):
    """The throw model ends at the main-bearing centre planes (App. III 2.1; a geometry's
    journal length is half a main bearing): the couplings' master nodes sit on the axis
    at z = -+33 mm; the web centres from the mesh's journal fillets agree with +-15 mm."""
    system, _, _ = three_point
    assert np.allclose(system.ref_points["end_1"], [0, 0, -Z_END], atol=1e-9)
    assert np.allclose(system.ref_points["end_2"], [0, 0, Z_END], atol=1e-9)
    z1, z2 = web_centres_from_mesh(throw, 0.012)
    assert (z1, z2) == pytest.approx((-Z_WEB, Z_WEB), abs=1e-6)


def _section_resultant(mesh, u, E, nu, z_cut):
    """Force and moment about (0, 0, z_cut) that the rest of the body exerts on the part
    z < z_cut (elements by centroid): K_part u at the interface nodes.  At every other
    node of the part K_part u is the external load there (zero away from the supports)."""
    basis = Basis(mesh, ElementTetP2(), intorder=2)
    part = np.flatnonzero(mesh.p[2, mesh.t[:4]].mean(axis=0) < z_cut)
    rest = np.setdiff1d(np.arange(mesh.t.shape[1]), part)
    Kp = assemble_stiffness(Basis(mesh, ElementTetP2(), intorder=2, elements=part), E, nu)
    f = (Kp @ u).reshape(-1, 3)
    iface = np.intersect1d(np.unique(basis.element_dofs[:, part]), np.unique(basis.element_dofs[:, rest]))
    x = basis.doflocs[:, iface].T - np.array([0, 0, z_cut])
    return f[iface].sum(axis=0), np.cross(x, f[iface]).sum(axis=0)


def test_pure_bending_and_torsion_reactions_and_section_moments(throw):
    """App. III 3.1/3.2: a moment at the free master node is reacted whole at the held one,
    and every section carries it: at the web-1 centre plane the FE section moment is
    M_x = 1 N m (bending) and M_z = 1 N m (torsion), forces zero (statics of a free body)."""
    E, nu = 210e9, 0.3
    system, U, loads = solve_bending_torsion(throw.mesh, E, nu)
    zero = np.zeros(U.shape[0])
    for k, axis in ((0, 3), (1, 5)):
        err, reac = system.equilibrium_error(U[:, k], zero, loads[k])
        assert err < 1e-9
        expected = np.zeros(6)
        expected[axis] = -1.0
        assert reac["end_1"] == pytest.approx(expected, abs=1e-8)
        force, moment = _section_resultant(throw.mesh, U[:, k], E, nu, -Z_WEB)
        assert np.abs(force).max() < 1e-8
        assert moment == pytest.approx(expected[3:] * -1.0, abs=1e-8)


def test_three_point_bending_reactions_lever_and_web_moment(throw, three_point):
    """App. III 3.3, simply supported throw, F = 1 N at the pin centre (z = 0) towards the
    axis: by hand Q_3P = F/2 = 0.5 N at each master node (symmetric supports at -+33 mm),
    lever to the web centre L = 33 - 15 = 18 mm, web-centre moment Q L = 9.0e-3 N m.  The
    FE reactions, the lever and the FE section moment at the web-1 centre plane agree."""
    E, nu = 210e9, 0.3
    system, u, f = three_point
    err, reac = system.equilibrium_error(u, f)
    assert err < 1e-9
    assert f.reshape(-1, 3).sum(axis=0) == pytest.approx([0, -1.0, 0], abs=1e-12)
    assert reac["end_1"][1] + reac["end_2"][1] == pytest.approx(1.0, abs=1e-10)
    # the traction's resultant passes through the pin centre plane z = 0 (pin symmetric): 0.5 N each
    assert reac["end_1"][1] == pytest.approx(0.5, abs=1e-4)
    force, moment = _section_resultant(throw.mesh, u, E, nu, -Z_WEB)
    assert force[1] == pytest.approx(-reac["end_1"][1], abs=1e-9)
    assert abs(moment[0]) == pytest.approx(reac["end_1"][1] * (Z_END - Z_WEB), rel=1e-7)
    st = scf_stresses(throw, Steel(), web_centres=(-Z_WEB, Z_WEB))
    assert st.lever == pytest.approx({"end_1": 0.018, "end_2": 0.018}, abs=1e-9)
    assert st.reaction["end_1"] == pytest.approx(abs(reac["end_1"][1]), rel=1e-12)
    assert st.section_moment["end_1"] == pytest.approx(abs(moment[0]), rel=1e-7)
    assert max(st.equilibrium_error.values()) < 1e-9
    # every measure peaks on its own fillet surface and is positive
    for peaks in (st.bending, st.torsion, st.three_point):
        assert all(p.value > 0 and 0 <= p.principal_ratio <= 1 and p.averaging >= 0 for p in peaks.values())
    assert set(st.three_point) == {"journal_fillet_1", "journal_fillet_2"}
