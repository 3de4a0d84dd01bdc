"""CalculiX input decks of an fe-crank throw model, and readers of CalculiX's results.

The deck carries the same mesh (the P2 tetrahedra as C3D10, node numbers = fe-crank's
node numbers + 1), the same material, the same supports and the same nodal loads as the
FE stage (the consistent load vectors fe-crank assembled, written as *CLOAD), one
*STEP per unit case, as CalculiX solves several load cases (it factorises in every step;
``*CLOAD, OP=NEW`` so that each step carries its own case only).

Supports, translated from the FE stage's ``System``:

* single held dofs (``point_dofs``: the six point constraints of the statically
  determinate model, whose reactions are part of the nodal loads) and held boundary
  components (``dirichlet_dofs``): *BOUNDARY on those node dofs;
* rigid end-face couplings (RBE2): *RIGID BODY with a reference and a rotation node at
  fe-crank's reference point, their held dofs as *BOUNDARY;
* elastic foundations (Winkler, k int (u.n_r)(v.n_r) dA): one SPRING1 per surface node
  acting radially (*ORIENTATION, SYSTEM=C about the crank axis) with the row-sum of the
  consistent foundation matrix as its stiffness -- a lumped approximation of the same
  foundation (CalculiX has no surface foundation element), so displacements agree to
  the lumping error, not to round-off.

C3D10 node order (CalculiX manual, element C3D10) is the VTK/scikit-fem order: corners
1-4, then the mid-nodes of edges 1-2, 2-3, 3-1, 1-4, 2-4, 3-4.  Elements of negative
volume are renumbered (corners 1 and 2 swapped) because CalculiX needs positive ones.  Numbers are written with 14 significant digits (CalculiX
reads at most 20 characters a field).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

#: new local order of an element whose corners 0 and 1 are swapped (edges follow)
_SWAP = np.array([1, 0, 2, 3, 4, 6, 5, 8, 7, 9])


def unit_loads(units) -> dict[str, np.ndarray]:
    """The load vectors of the solved unit cases, rebuilt as the FE stage builds them and
    checked against its solutions (a mismatch stops the benchmark).  With the statically
    determinate support model the FE stage's ``System.solve`` adds to each load its
    distributed reactions (``System.determinate``), held by six point constraints only:
    CalculiX gets the same self-equilibrated nodal loads."""
    from fe_crank.fe.core.loads import centrifugal_load, face_torque_load, pin_pressure_load, pin_surface
    from fe_crank.fe.throw.pin_directions import unit_force

    basis, opt = units.system.basis, units.options
    surf, loads = None, {}
    for name in units.cases:
        if name == "centrifugal":
            loads[name] = centrifugal_load(basis, units.material.density, 1.0)
        elif name == "torque":
            loads[name] = face_torque_load(basis, -1.0, boundary=opt.torque_face)
        else:
            surf = surf or pin_surface(basis, opt.pin_boundary, opt.pin_centre)
            loads[name] = pin_pressure_load(basis, unit_force(name), half_angle=opt.pin_half_angle, surface=surf)[0]
    sup = getattr(units.system, "determinate", None)
    if sup is not None:
        loads = {name: sup.self_equilibrated(f)[0] for name, f in loads.items()}
    for name, f in loads.items():
        u = units.system.solve(f)
        ref = units.cases[name].displacement
        if np.abs(u - ref).max() > 1e-8 * np.abs(ref).max():
            raise SystemExit(f"benchmark: the rebuilt load of {name} is not the one the FE stage solved")
    return loads


def c3d10_connectivity(element_dofs: np.ndarray, points: np.ndarray) -> np.ndarray:
    """(ne, 10) 1-based C3D10 connectivity with positive volume."""
    t = np.asarray(element_dofs).T.copy()  # (ne, 10)
    p = points.T
    a, b, c, d = (p[t[:, k]] for k in range(4))
    vol = np.einsum("ij,ij->i", np.cross(b - a, c - a), d - a)
    neg = vol < 0
    t[neg] = t[neg][:, _SWAP]
    mid = 0.5 * (p[t[:, 0]] + p[t[:, 1]])
    edge = np.linalg.norm(p[t[:, 1]] - p[t[:, 0]], axis=1)
    if np.any(np.linalg.norm(p[t[:, 4]] - mid, axis=1) > 0.25 * edge):
        raise ValueError("node 5 of a C3D10 is not near the middle of edge 1-2: unexpected node order")
    return t + 1


def _lines(rows, fmt: str) -> str:
    return "\n".join(fmt % tuple(r) for r in rows)


def write_deck(path: Path, units, loads: dict[str, np.ndarray], output_nodes: np.ndarray) -> Path:
    """Write ``path`` (.inp): mesh, material, supports of ``units.system`` and one step per load."""
    sys_ = units.system
    x = np.asarray(units.points)  # (3, N)
    N = x.shape[1]
    mat = units.material
    conn = c3d10_connectivity(sys_.basis.element_dofs, x)
    out = [
        "*HEADING",
        "fe-crank throw model (benchmarks/verification/calculix_compare.py)",
        "*NODE, NSET=NALL",
        _lines(np.column_stack([np.arange(1, N + 1), x.T]), "%d, %.13e, %.13e, %.13e"),
    ]
    extra = N
    rigid = []
    for c in sys_.couplings:
        ref = sys_.ref_points[c.boundary]
        out.append(f"{extra + 1}, {ref[0]:.13e}, {ref[1]:.13e}, {ref[2]:.13e}")
        out.append(f"{extra + 2}, {ref[0]:.13e}, {ref[1]:.13e}, {ref[2]:.13e}")
        rigid.append((c, extra + 1, extra + 2))
        extra += 2
    out += [
        "*ELEMENT, TYPE=C3D10, ELSET=EALL",
        _lines(np.column_stack([np.arange(1, conn.shape[0] + 1), conn]), "%d" + ", %d" * 10),
    ]
    out += [
        "*MATERIAL, NAME=STEEL",
        "*ELASTIC",
        f"{mat.youngs_modulus:.13e}, {mat.poisson_ratio:.13e}",
        "*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL",
    ]
    eid = conn.shape[0]
    held = [np.asarray(getattr(sys_, "point_dofs", np.zeros(0, int))), np.asarray(sys_.dirichlet_dofs)]
    held = np.unique(np.concatenate(held)).astype(int)
    bcs = [(d // 3 + 1, d % 3 + 1) for d in held]
    for c, rnode, qnode in rigid:
        s = sys_.slave_dofs[c.boundary]
        out += [f"*NSET, NSET=RB_{c.boundary}", _chunks(s + 1)]
        out.append(f"*RIGID BODY, NSET=RB_{c.boundary}, REF NODE={rnode}, ROT NODE={qnode}")
        for k, dof in enumerate(("ux", "uy", "uz", "rx", "ry", "rz")):
            if dof in c.fixed:
                bcs.append((rnode if k < 3 else qnode, k % 3 + 1))
    if sys_.foundations:
        out += ["*ORIENTATION, NAME=CYL, SYSTEM=CYLINDRICAL", "0., 0., 0., 0., 0., 1."]
        r = np.column_stack([x[0], x[1], np.zeros(N)])
        r /= np.maximum(np.linalg.norm(r, axis=1, keepdims=True), 1e-300)
        # row-sum lumping: the radial force at each node for a unit radial displacement of all
        F = (sys_.Ks @ r.ravel()).reshape(-1, 3)
        for fd in sys_.foundations:
            for s in sys_.foundation_dofs[fd.boundary]:
                k = float(F[s] @ r[s])
                if k <= 0:
                    continue
                eid += 1
                out += [
                    f"*ELEMENT, TYPE=SPRING1, ELSET=SP{eid}",
                    f"{eid}, {s + 1}",
                    f"*SPRING, ELSET=SP{eid}, ORIENTATION=CYL",
                    "1",
                    f"{k:.13e}",
                ]
    if bcs:
        out += ["*BOUNDARY", _lines([(n, d, d) for n, d in sorted(set(bcs))], "%d, %d, %d")]
    out += ["*NSET, NSET=NOUT", _chunks(np.asarray(output_nodes) + 1)]
    for _name, f in loads.items():
        out += static_step(f.reshape(-1, 3), op_new=True)
    path.write_text("\n".join(out) + "\n")
    return path


def static_step(nodal_forces: np.ndarray, *, op_new: bool = False) -> list[str]:
    """A linear static step: the nodal forces (n, 3) as *CLOAD (non-zero entries, 1-based
    node ids), displacements printed and stresses written at the node set NOUT."""
    fn = nodal_forces
    nz = np.flatnonzero(np.any(fn != 0.0, axis=1))
    rows = [(n + 1, j + 1, fn[n, j]) for n in nz for j in range(3) if fn[n, j] != 0.0]
    cload = "*CLOAD, OP=NEW" if op_new else "*CLOAD"
    return ["*STEP", "*STATIC", cload, _lines(rows, "%d, %d, %.13e"), "*NODE PRINT, NSET=NOUT", "U"] + [
        "*NODE FILE, NSET=NOUT",
        "S",
        "*END STEP",
    ]


def plane_nodes(element_dofs: np.ndarray, points: np.ndarray, axes) -> dict[str, int]:
    """How the deck's nodes on the mirror planes ``axes`` (coordinate exactly 0) join the two
    halves: nodes on a plane, those used by elements of both sides (each element placed
    by its centroid), and coincident nodes anywhere (0 for one connected model)."""
    p = np.asarray(points)
    t = np.asarray(element_dofs)
    out = {"duplicate_coordinates": int(p.shape[1] - np.unique(p.T, axis=0).shape[0])}
    for ax in axes:
        on = np.flatnonzero(p[ax] == 0.0)
        side = p[ax][t[:4]].mean(axis=0)
        lo, hi = np.zeros(p.shape[1], bool), np.zeros(p.shape[1], bool)
        lo[t[:, side < 0].ravel()] = True
        hi[t[:, side > 0].ravel()] = True
        out[f"plane_{ax}_nodes"] = int(on.size)
        out[f"plane_{ax}_nodes_in_both_halves"] = int((lo[on] & hi[on]).sum())
    return out


def _chunks(ids, per: int = 16) -> str:
    ids = [str(int(i)) for i in ids]
    return "\n".join(", ".join(ids[i : i + per]) for i in range(0, len(ids), per))


def read_dat_displacements(path: Path) -> list[dict[int, np.ndarray]]:
    """Displacements per step from CalculiX's .dat (*NODE PRINT U): [{node: (3,)}]."""
    steps, cur = [], None
    for line in Path(path).read_text().splitlines():
        if line.strip().startswith("displacements"):
            cur = {}
            steps.append(cur)
            continue
        parts = line.split()
        if cur is not None and len(parts) == 4:
            try:
                cur[int(parts[0])] = np.array([float(v) for v in parts[1:]])
            except ValueError:
                cur = None
    return steps


def read_frd_stresses(path: Path) -> list[dict[int, np.ndarray]]:
    """Nodal stresses per step from CalculiX's .frd (ASCII, *NODE FILE S): [{node: (6,)}],
    components SXX SYY SZZ SXY SYZ SZX (the extrapolated, averaged nodal values)."""
    steps, cur = [], None
    for line in Path(path).read_text().splitlines():
        if line.startswith(" -4  STRESS"):
            cur = {}
            steps.append(cur)
        elif line.startswith(" -3"):
            cur = None
        elif cur is not None and line.startswith(" -1"):
            node = int(line[3:13])
            cur[node] = np.array([float(line[13 + 12 * i : 25 + 12 * i]) for i in range(6)])
    return steps
