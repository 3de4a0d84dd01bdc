"""gmsh session handling and the gmsh -> scikit-fem quadratic tetrahedron conversion."""

from __future__ import annotations

import numpy as np
import pytest
from skfem import Basis, ElementTetP2, FacetBasis, Functional

from fe_crank.errors import MeshError
from fe_crank.gmsh_io import corner_jacobians, gmsh_session, model_to_skfem


def _box_and_cylinder(order: int = 2, size: float = 0.25):
    """Unit box fused with a cylinder r 0.3 (axis z, from z=1 to 1.5): two named volumes."""
    import gmsh

    occ = gmsh.model.occ
    box = occ.addBox(0, 0, 0, 1, 1, 1)
    cyl = occ.addCylinder(0.5, 0.5, 1.0, 0, 0, 0.5, 0.3)
    out, _ = occ.fragment([(3, box)], [(3, cyl)])
    occ.synchronize()
    vols = [t for d, t in gmsh.model.getEntities(3)]
    com = {v: occ.getCenterOfMass(3, v) for v in vols}
    box_v = [v for v in vols if com[v][2] < 1.0]
    cyl_v = [v for v in vols if com[v][2] > 1.0]
    gmsh.model.addPhysicalGroup(3, box_v, name="box")
    gmsh.model.addPhysicalGroup(3, cyl_v, name="pin")
    bottom, mantle = [], []
    for _, s in gmsh.model.getEntities(2):
        c = occ.getCenterOfMass(2, s)
        if abs(c[2]) < 1e-9:
            bottom.append(s)
        bb = gmsh.model.getBoundingBox(2, s)
        if bb[2] > 1.0 - 1e-6 and bb[5] > 1.4 and abs(c[2] - 1.25) < 1e-6:
            mantle.append(s)
    gmsh.model.addPhysicalGroup(2, bottom, name="bottom")
    gmsh.model.addPhysicalGroup(2, mantle, name="mantle")
    gmsh.option.setNumber("Mesh.MeshSizeMax", size)
    gmsh.model.mesh.generate(3)
    if order == 2:
        gmsh.model.mesh.setOrder(2)


def test_session_finalises_on_exception():
    import gmsh

    with pytest.raises(RuntimeError, match="boom"):
        with gmsh_session():
            assert gmsh.isInitialized()
            raise RuntimeError("boom")
    assert not gmsh.isInitialized()
    with gmsh_session() as g:  # a fresh session opens again
        assert g.isInitialized()


def test_nested_session_refused():
    with gmsh_session():
        with pytest.raises(MeshError, match="already open"):
            with gmsh_session():
                pass


def test_quadratic_tet_conversion_groups_volume_and_node_order():
    with gmsh_session():
        _box_and_cylinder()
        mesh = model_to_skfem()
    # named groups present and non-empty
    assert set(mesh.subdomains) == {"box", "pin"}
    assert set(mesh.boundaries) == {"bottom", "mantle"}
    assert all(v.size > 0 for v in mesh.subdomains.values())
    assert all(v.size > 0 for v in mesh.boundaries.values())
    assert mesh.subdomains["box"].size + mesh.subdomains["pin"].size == mesh.nelements

    # positive Jacobians everywhere
    assert np.all(corner_jacobians(mesh) > 0)
    basis = Basis(mesh, ElementTetP2())

    # isoparametric volume: box 1 + cylinder pi r^2 h, curved faces exact to ~1e-5 with P2 geometry
    vol = Functional(lambda w: 1.0 + 0 * w.x[0]).assemble(basis)
    exact = 1.0 + np.pi * 0.3**2 * 0.5
    assert vol == pytest.approx(exact, rel=2e-4)
    vol_pin = Functional(lambda w: 1.0 + 0 * w.x[0]).assemble(
        Basis(mesh, ElementTetP2(), elements=mesh.subdomains["pin"])
    )
    assert vol_pin == pytest.approx(np.pi * 0.3**2 * 0.5, rel=5e-4)

    # boundary areas: bottom face 1, mantle 2 pi r h
    fb = FacetBasis(mesh, ElementTetP2(), facets=mesh.boundaries["bottom"])
    assert Functional(lambda w: 1.0 + 0 * w.x[0]).assemble(fb) == pytest.approx(1.0, rel=1e-12)
    fm = FacetBasis(mesh, ElementTetP2(), facets=mesh.boundaries["mantle"])
    assert Functional(lambda w: 1.0 + 0 * w.x[0]).assemble(fm) == pytest.approx(2 * np.pi * 0.3 * 0.5, rel=5e-4)


def test_quadratic_node_order_mid_edge_nodes_at_midpoints():
    """On a straight-sided model every mid-edge dof lies at the midpoint of its edge."""
    import gmsh

    with gmsh_session():
        gmsh.model.occ.addBox(0, 0, 0, 1, 0.7, 0.4)
        gmsh.model.occ.synchronize()
        gmsh.model.addPhysicalGroup(3, [1], name="all")
        gmsh.option.setNumber("Mesh.MeshSizeMax", 0.2)
        gmsh.model.mesh.generate(3)
        gmsh.model.mesh.setOrder(2)
        mesh = model_to_skfem()
    basis = Basis(mesh, ElementTetP2())
    edofs = basis.element_dofs  # 4 vertex dofs then 6 edge dofs in mesh.t2e order
    mids = mesh.doflocs[:, edofs[4:]]  # (3, 6, ne)
    ends = mesh.doflocs[:, mesh.edges[:, mesh.t2e]]  # (3, 2, 6, ne)
    assert np.allclose(mids, ends.mean(axis=1), atol=1e-12)
    assert np.all(corner_jacobians(mesh) > 0)
    vol = Functional(lambda w: 1.0 + 0 * w.x[0]).assemble(basis)
    assert vol == pytest.approx(0.28, rel=1e-12)


def test_first_order_mesh_refused():
    with gmsh_session():
        _box_and_cylinder(order=1, size=0.5)
        with pytest.raises(MeshError, match="setOrder"):
            model_to_skfem()


def test_conversion_needs_session():
    with pytest.raises(MeshError, match="no gmsh session"):
        model_to_skfem()


def test_sessions_from_threads_are_serialised():
    import threading

    import gmsh

    inside, overlap = [], []

    def work():
        with gmsh_session():
            inside.append(1)
            if len(inside) > 1:
                overlap.append(1)
            gmsh.model.occ.addBox(0, 0, 0, 1, 1, 1)
            gmsh.model.occ.synchronize()
            gmsh.model.mesh.generate(3)
            inside.pop()

    threads = [threading.Thread(target=work) for _ in range(3)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not overlap and not inside
