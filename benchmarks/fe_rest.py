"""CPU seconds of the FE stage's work around PARDISO, former route against current, in one process.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/fe_rest.py \
        loadcases/single_cylinder_seed001.toml --preset coarse [--repeat 3]

Meshes (cached) the case's first throw and times, in CPU seconds (user + system of all
threads, ``time.process_time``; best of ``--repeat``), each piece of ``solve_unit_cases`` on the symmetric
path that is neither the factorisation nor a PARDISO solve, both as the stage formed it
before and as it does now, on the same inputs:

* the half's stiffness: a basis on the half's elements, the stiffness in the whole
  numbering, indexed down to the half's dofs, ``scipy.sparse.triu`` -- against
  ``assembly.part_stiffness`` from the whole basis, ``assembly.upper_triangle``;
* the selection P of the free dofs: ``setdiff1d`` and a COO matrix -- against
  ``symsystem.selection``;
* the per-case equilibrium check of the 14 unit cases: the whole-vector residual and
  three ``applied`` resultants per case -- against ``System.equilibrium_error`` on the
  constrained rows with one ``applied`` per case;
* the rigid motion taken off the rebuilt displacements (3 N x 14): the whole motion built,
  then subtracted -- against ``symsolve._remove_rigid_fit`` in place.

The equilibrium pieces run on displacements of the right size without solving (their
cost does not depend on the values), so no factor is built and the process stays small.
Every pair is also compared: the script stops if any result differs in a bit.
"""

from __future__ import annotations

import argparse
import os
import sys
import time

import numpy as np

_cpu = time.process_time  # CPU seconds (user + system) of this process, finer than os.times


def _best(fn, repeat):
    best, out = None, None
    for _ in range(repeat):
        c = _cpu()
        out = fn()
        t = _cpu() - c
        best = t if best is None else min(best, t)
    return best, out


def _former_resultant(v, x, sdofs):
    fn = v.reshape(-1, 3)[sdofs]
    xs = x[:, sdofs].T
    return np.concatenate([fn.sum(axis=0), np.cross(xs, fn).sum(axis=0)])


def _former_applied(system, f):
    x = system.points
    fn = f.reshape(-1, 3)
    res = _former_resultant(f, x, np.arange(x.shape[1]))
    return res, np.linalg.norm(fn, axis=1).sum(), np.linalg.norm(np.cross(x.T, fn), axis=1).sum()


def _former_check(system, u, f):
    """The per-case check as the stage ran it: reactions on the whole residual vector,
    ``applied`` three times (the error, the point check, the record)."""
    x = system.points
    R = system.determinate.reactions(f)
    fe = f + np.asarray(system.determinate.G @ R).reshape(f.shape)
    reac = system.determinate.reaction_resultants(R)
    rs = -(system.Ks @ u)
    del rs
    resid = np.zeros_like(u)
    resid[system.rows] = system.K_rows @ u + (system.Ks @ u)[system.rows] - fe[system.rows]
    rp = np.zeros_like(u)
    pos = np.searchsorted(system.rows, system.point_dofs)
    rp[system.point_dofs] = system.K_rows[pos] @ u + (system.Ks @ u)[system.point_dofs] - fe[system.point_dofs]
    reac["point_constraints"] = _former_resultant(rp, x, np.unique(system.point_dofs // 3))
    total = _former_applied(system, f)[0]
    for r in reac.values():
        total = total + r
    _former_applied(system, f)
    applied = _former_applied(system, f)
    return total, reac, applied[0]


def _current_check(system, u, f):
    applied = system.applied(f)
    _, reac = system.equilibrium_error(u, f, applied=applied)
    total = applied[0]
    for r in reac.values():
        total = total + r
    return total, reac, applied[0]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("loadcase")
    ap.add_argument("--preset", default="coarse")
    ap.add_argument("--cache-dir", default=".cache/meshes")
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args(argv)

    import scipy.sparse as sp
    from skfem import Basis

    from fe_crank.fe import symsolve
    from fe_crank.fe.assembly import assemble_stiffness, part_stiffness, upper_triangle
    from fe_crank.fe.bases import cell_basis
    from fe_crank.fe.determinate import DeterminateLayout, determinate_support
    from fe_crank.fe.fe_options import FeOptions, axial_journal
    from fe_crank.fe.loads import centrifugal_load, face_torque_load, pin_pressure_load, pin_surface
    from fe_crank.fe.pin_directions import pin_direction, unit_force
    from fe_crank.fe.symmetry import mesh_mirror
    from fe_crank.fe.symsystem import selection, stiffness_rows
    from fe_crank.fe.system import System
    from fe_crank.io.loadcase import load_loadcase
    from fe_crank.mesh import mesh_throw

    lc = load_loadcase(args.loadcase)
    tm = mesh_throw(lc.geometry, size=args.preset, cache_dir=args.cache_dir)
    mesh, opts, mat = tm.mesh, lc.fe or FeOptions(), lc.material
    E, nu = mat.youngs_modulus, mat.poisson_ratio
    basis = cell_basis(mesh, opts.intorder)
    sup = determinate_support(
        basis,
        DeterminateLayout(journals=tuple(opts.journals), torque_face=opts.reaction_face, axial=axial_journal(opts)),
    )
    mirror = mesh_mirror(mesh, basis, tuple(getattr(tm, "symmetry", None) or ()))
    if mirror is None:
        print("the mesh states no verified mirror plane: nothing of the symmetric path to time")
        return 1
    rows_out = []

    def pair(name, former, current, same):
        cf, a = _best(former, args.repeat)
        cc, b = _best(current, args.repeat)
        if not same(a, b):
            raise SystemExit(f"{name}: the two routes differ")
        rows_out.append((name, cf, cc))
        del a, b

    el = basis.element_dofs
    centroid = basis.doflocs[:, el[:4]].mean(axis=1)
    part = np.flatnonzero(np.all([centroid[a] > 0 for a in mirror.axes], axis=0))
    nodes = np.unique(el[:, part])

    def former_half():
        pb = Basis(
            mesh, basis.elem, mapping=basis.mapping, quadrature=(basis.X, basis.W), dofs=basis.dofs, elements=part
        )
        ldofs = (3 * nodes[:, None] + np.arange(3)).ravel()
        K = sp.triu(assemble_stiffness(pb, E, nu)[ldofs][:, ldofs], format="csr")
        K.sort_indices()
        return K

    def current_half():
        K = upper_triangle(part_stiffness(basis, part, nodes, E, nu))
        K.sort_indices()
        return K

    def same_csr(a, b):
        return a.shape == b.shape and all(
            np.array_equal(getattr(a, k), getattr(b, k)) for k in ("indptr", "indices", "data")
        )

    pair("half stiffness (triu)", former_half, current_half, same_csr)

    n = 3 * basis.N
    held = np.unique(sup.held)

    def former_selection():
        free = np.setdiff1d(np.arange(n), held)
        return sp.csr_matrix((np.ones(free.size), (free, np.arange(free.size))), shape=(n, free.size))

    pair("selection P", former_selection, lambda: selection(n, held), same_csr)

    system = System(
        mesh=mesh,
        basis=basis,
        K_rows=stiffness_rows(basis, E, nu, held),
        rows=held,
        Ks=sp.csr_matrix((n, n)),
        P=selection(n, held),
        foundations=(),
        couplings=(),
        ref_points={},
        ref_columns={},
        slave_dofs={},
        dirichlet_dofs=np.zeros(0, int),
        foundation_dofs={},
        factorisation=None,
        point_dofs=held,
        determinate=sup,
    )
    loads = [centrifugal_load(basis, mat.density, 1.0), face_torque_load(basis, -1.0, boundary=opts.torque_face)]
    surf = pin_surface(basis, opts.pin_boundary, opts.pin_centre)
    loads += [
        pin_pressure_load(
            basis, unit_force(c), boundary=opts.pin_boundary, half_angle=opts.pin_half_angle, surface=surf
        )[0]
        for c in opts.cases
        if pin_direction(c) is not None
    ]
    rng = np.random.default_rng(1)
    U = rng.normal(size=(n, len(loads))) * 1e-9

    def checks(fn):
        return lambda: [fn(system, U[:, i], f) for i, f in enumerate(loads)]

    def same_checks(a, b):
        return all(
            np.array_equal(x[0], y[0])
            and np.array_equal(x[2], y[2])
            and x[1].keys() == y[1].keys()
            and all(np.array_equal(x[1][k], y[1][k]) for k in x[1])
            for x, y in zip(a, b)
        )

    pair(f"equilibrium checks x{len(loads)}", checks(_former_check), checks(_current_check), same_checks)

    def current_rigid():
        V = U.copy()  # the rebuilt U the solve owns; its copy is timed on both sides
        symsolve._remove_rigid_fit(basis.doflocs, sup.held, V)
        return V

    def former_rigid_copy():  # the whole motion built, then subtracted into a new array
        V = U.copy()
        a = symsolve._rigid_coefficients(basis.doflocs, sup.held, V)
        Un = np.zeros((basis.N, 3, V.shape[1]))
        Un += a[None, :3, :]
        Un += np.cross(a[3:].T[:, None, :], basis.doflocs.T[None, :, :]).transpose(1, 2, 0)
        return V - Un.reshape(V.shape)

    pair(f"rigid motion off U (3N x {len(loads)})", former_rigid_copy, current_rigid, np.array_equal)

    print(
        f"{args.loadcase} --preset {args.preset}: {n} DOF, {mesh.t.shape[1]} elements, half {part.size} "
        f"elements / {3 * nodes.size} dofs, {len(loads)} unit loads; CPU s, best of {args.repeat}"
    )
    print(f"{'piece':<32} {'former':>8} {'current':>8} {'ratio':>6}")
    for name, cf, cc in rows_out:
        print(f"{name:<32} {cf:8.3f} {cc:8.3f} {cf / cc if cc >= 0.005 else float('inf'):6.1f}")
    tf, tc = sum(r[1] for r in rows_out), sum(r[2] for r in rows_out)
    print(f"{'total':<32} {tf:8.3f} {tc:8.3f} {tf / max(tc, 1e-9):6.1f}")
    print(f"every pair identical bit for bit; load average at the end: {os.getloadavg()[0]:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
