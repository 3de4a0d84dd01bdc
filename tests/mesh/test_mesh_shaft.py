"""The whole-shaft mesh: rotated-copy end faces, extruded end journals, the joined mesh."""

from __future__ import annotations

import numpy as np
import pytest
from helpers.shaft import small_engine, small_geometry
from scipy.spatial import cKDTree

from fe_crank.errors import InputError
from fe_crank.fe.core.bases import cell_basis
from fe_crank.geometry.shaft import shaft_layout
from fe_crank.gmsh_io import corner_jacobians
from fe_crank.mesh.extrude import extrude, round_disc
from fe_crank.mesh.interface import sectors_for
from fe_crank.mesh.shaft import _face_nodes, mesh_shaft


def test_sectors_for_the_angles_between_throws():
    assert sectors_for([np.pi, 0.0, -np.pi]) == 2
    assert sectors_for([2 * np.pi / 3, -4 * np.pi / 3]) == 3
    assert sectors_for([np.pi / 2, np.pi]) == 4
    assert sectors_for([0.0]) == 1
    assert sectors_for([0.1]) == 0


@pytest.fixture(scope="module")
def flat4(tmp_path_factory):
    angles = [0.0, np.pi, np.pi, 0.0]
    layout = shaft_layout(small_geometry(angles), small_engine(angles), geometry_file="g", engine_file="e")
    return mesh_shaft(layout, size="test", cache_dir=tmp_path_factory.mktemp("cache"))


def test_end_faces_map_onto_themselves_under_the_throw_angles(flat4):
    sm = flat4
    assert sm.sectors == 2
    mesh = sm.meshes[sm.pieces[1].mesh]
    assert [p.kind for p in sm.pieces] == ["end", "throw", "throw", "throw", "throw", "end"]
    assert len({p.mesh for p in sm.pieces if p.kind == "throw"}) == 1  # one mesh for every throw
    for face in ("end_1", "end_2"):
        x = np.asarray(mesh.doflocs)[:, _face_nodes(mesh, face)].T
        turned = x * np.array([-1.0, -1.0, 1.0])  # 180 deg about z
        d, _ = cKDTree(x).query(turned)
        assert d.max() < 1e-12


def test_joined_mesh_is_conforming_and_named(flat4):
    sm = flat4
    whole = sm.whole()
    assert 3 * whole.doflocs.shape[1] == sm.n_dof
    # every facet of a joint face became interior: the boundary is the pieces' boundaries minus the joints
    outer = sum(sm.meshes[p.mesh].boundary_facets().size for p in sm.pieces)
    joint = sum(sm.meshes[p.mesh].boundaries["end_2"].size for p in sm.pieces[:-1])
    assert whole.boundary_facets().size == outer - 2 * joint
    assert corner_jacobians(whole).min() > 0
    names = set(whole.boundaries)
    for t in "1234":
        assert {f"crankpin_fillet_1@{t}", f"journal_fillet_2@{t}", f"crankpin@{t}"} <= names
    assert {f"journal@{j}" for j in "12345"} | {"end_front", "end_rear"} <= names
    vol = cell_basis(whole, 2).dx.sum()
    parts = sum(cell_basis(sm.meshes[p.mesh], 2).dx.sum() for p in sm.pieces)
    assert vol == pytest.approx(parts, rel=1e-12)


def test_throw_angles_that_cannot_be_joined_are_refused(tmp_path):
    angles = [0.0, np.deg2rad(50.0)]
    layout = shaft_layout(small_geometry(angles), small_engine(angles), geometry_file="g.toml", engine_file="e")
    with pytest.raises(InputError, match="not multiples of 360/24 deg"):
        mesh_shaft(layout, size="test", cache_dir=tmp_path)


def test_extruded_cylinder():
    r, h = 0.01, 0.05
    disc = round_disc(r, r / 1.2)
    m = extrude(disc, np.linspace(0.0, h, 6), {"band": (0.02, 0.03)})
    assert corner_jacobians(m).min() > 0
    vol = cell_basis(m, 2).dx.sum()
    assert vol == pytest.approx(np.pi * r**2 * h, rel=2e-3)  # the quadratic rim's chords
    zc = m.p[2][m.facets[:, m.boundaries["band"]]].mean(axis=0)
    assert np.all((zc > 0.02) & (zc < 0.03))
    assert m.boundaries["end_1"].size == m.boundaries["end_2"].size == disc.tri.shape[0]
