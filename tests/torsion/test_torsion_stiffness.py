"""Throw stiffness: Carter's formula by hand, the FE twist measurement on a round bar
(closed form T L / (G J)), and FE throw vs Carter on the shipped inline-4 throw."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from helpers.verification_meshes import round_bar, simple_throw

from fe_crank.fe import Coupling, build_system
from fe_crank.fe.core.loads import face_torque_load
from fe_crank.io.loadcase import load_loadcase
from fe_crank.torsion.build import pitch_stiffness, shear_modulus
from fe_crank.torsion.stiffness import carter_throw_stiffness, face_rotation

ROOT = Path(__file__).resolve().parents[2]
CASE = ROOT / "loadcases" / "inline4_genset_torsion.toml"
E, NU = 210e9, 0.3


@pytest.fixture(scope="module")
def case():
    return load_loadcase(CASE)


def test_carter_by_hand_for_the_inline4_throw(case):
    """geometry/inline4.toml on engines/inline4.toml: D_j 56, web h 17, pin D_p 48 x 24 mm,
    R 43 mm; the journal stubs reach the bearing centres the 92 mm pitch puts at mid-gap,
    2 x (92 - 24 - 2 x 17)/2 = 34 mm of journal in the throw; web width at mid-overlap
    (UR M53 3.1): y = ((43 - 24) + 28)/2 = 23.5 mm, b = 2 (42 + (33 - 42) 23.5/43) = 74.163 mm.
    L_e = (34 + 0.8*17) + 0.75*24*(56/48)^4 + 1.5*43*56^4/(17*74.163^3)
        = 47.6 + 33.346 + 91.475 = 172.42 mm;
    G = 210e9 / 2.6 = 80.769 GPa, I_p = pi 0.056^4 / 32 = 9.6550e-7 m^4,
    k = G I_p / L_e = 4.523e5 N m/rad."""
    G = shear_modulus(case.material)
    assert G == pytest.approx(80.769e9, rel=1e-4)
    assert case.geometry.journal_length == pytest.approx(0.017)
    b = 2 * (42 + (33 - 42) * 23.5 / 43)
    le = (34 + 0.8 * 17) + 0.75 * 24 * (56 / 48) ** 4 + 1.5 * 43 * 56**4 / (17 * b**3)
    assert le == pytest.approx(172.42, abs=0.01)
    k = carter_throw_stiffness(case.geometry, G)
    assert k == pytest.approx(G * np.pi * 0.056**4 / 32 / (le * 1e-3), rel=1e-9)
    assert k == pytest.approx(4.523e5, rel=1e-3)


def test_pitch_adds_the_missing_journal_in_series(case):
    """FE route: 1/k = 1/k_FE + (pitch - span)/(G I_p); the throw model of the check spans
    the pitch (its journal stubs reach the bearing centres), a longer pitch adds journal."""
    G = shear_modulus(case.material)
    k_fe = 5.0e5
    ip = np.pi * 0.056**4 / 32
    assert pitch_stiffness(case.geometry, G, 0.092, method="fe", fe_stiffness=k_fe) == pytest.approx(k_fe, rel=1e-12)
    k = pitch_stiffness(case.geometry, G, 0.104, method="fe", fe_stiffness=k_fe)
    assert 1 / k == pytest.approx(1 / k_fe + 0.012 / (G * ip), rel=1e-12)


def test_face_rotation_of_an_fe_round_bar_matches_tl_over_gj():
    """Round bar d 20 mm, L 80 mm, clamped end_1, the FE stage's shear-flow torque on
    end_2: phi = T L / (G J) (Saint-Venant).  P2 on 3 mm elements is within 0.5 % of it;
    1 % would catch a wrong J (r^2 weights) or a sign/axis slip of the measurement."""
    d, length, T = 0.02, 0.08, 10.0
    mesh = round_bar(d, length, size=0.003)
    s = build_system(mesh, E, NU, couplings=[Coupling("end_1", fixed=("ux", "uy", "uz", "rx", "ry", "rz"))])
    u = s.solve(face_torque_load(s.basis, T, boundary="end_2"))
    phi = face_rotation(s.basis, u, "end_2") - face_rotation(s.basis, u, "end_1")
    G = E / (2 * (1 + NU))
    assert phi == pytest.approx(T * length / (G * np.pi * d**4 / 32), rel=0.01)


@pytest.mark.heavy
def test_fe_throw_stiffness_vs_carter(case, mesh_cache):
    """The FE throw of the generating set's load case (geometry/inline4.toml, journals
    2 x 17 mm; test mesh, the model the chain takes) twists under the torque unit case
    with k_FE = 4.962e5 N m/rad (determinate support; radial foundation 5.067e5, coarse
    mesh 4.935e5, measured 2026-11-29); Carter gives 4.523e5, about 9 % softer.  The gap is
    the empirical formula's: docs/torsion.md.
    Band 5-16 %: outside it either the FE twist measurement or the formula changed."""
    from fe_crank.cli.torsion import fe_stiffness_of

    G = shear_modulus(case.material)
    k_fe = fe_stiffness_of(case, "test", mesh_cache)  # the run's: the inline-4 throw is meshed by other tests too
    k_c = carter_throw_stiffness(case.geometry, G)
    assert 0.84 < k_c / k_fe < 0.95


def test_face_rotation_is_work_conjugate_so_the_stiffness_holds_the_models_strain_energy():
    """A box-web throw (journal stubs 30 mm: the end faces do not turn rigidly under the
    shear flow), 1 N m as the shear flow on end_1, end_2 held rigidly: the measured twist
    phi makes T^2 / (2 k) the model's strain energy U = 1/2 int sigma : eps dV, integrated
    here independently of the solve (Castigliano, phi = dU/dT).  An equal-weight fit over
    the face's nodes does not have this property (on the inline-4 throw it moved k by 5 %
    with the end faces' meshing, docs/torsion.md)."""
    from skfem import Basis, ElementTetP2, ElementVector, Functional
    from skfem.helpers import ddot, sym_grad, trace

    mesh = simple_throw(size=0.012)
    all6 = ("ux", "uy", "uz", "rx", "ry", "rz")
    s = build_system(mesh, E, NU, couplings=[Coupling("end_2", fixed=all6)])
    u = s.solve(face_torque_load(s.basis, 1.0, boundary="end_1"))
    phi = face_rotation(s.basis, u, "end_1") - face_rotation(s.basis, u, "end_2")
    lam, mu = E * NU / ((1 + NU) * (1 - 2 * NU)), E / (2 * (1 + NU))

    @Functional
    def energy(w):
        eps = sym_grad(w["u"])
        return 0.5 * (lam * trace(eps) ** 2 + 2 * mu * ddot(eps, eps))

    vector = Basis(mesh, ElementVector(ElementTetP2()), intorder=2)  # dofs x, y, z per P2 node, as u
    U = energy.assemble(vector, u=vector.interpolate(u))
    assert phi > 0 and face_rotation(s.basis, u, "end_2") == pytest.approx(0.0, abs=1e-12 * phi)
    assert 1.0 / phi == pytest.approx(1.0 / (2 * U), rel=1e-8)
