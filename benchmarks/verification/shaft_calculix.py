"""The whole shaft against CalculiX on the same whole-shaft mesh with linear-spring bearings.

    .venv/bin/python benchmarks/verification/shaft_calculix.py --loadcase loadcases/inline4_rated.toml --preset test

fe-crank (its own process): the whole-shaft model of the load case (``mesh_shaft`` and ``analyse_whole_shaft``:
mesh, exact condensation, unit cases, the operating cycle of 720 angles with and without
counterweights) with every main bearing a linear radial spring of ``--stiffness`` N/m,
and the whole mesh's field at the angle of the largest bearing load (``piece_fields``).

CalculiX (``ccx``, its own process): the same joined C3D10 mesh (``ShaftMesh.whole``),
material and nodal loads at that one angle (the pins' cosine pressures, the centrifugal
body forces of the shaft and its counterweights, the torque reacted at the power
take-off's face as its shear flow: the same consistent load vectors, placed into the
shaft frame), and the same bearings: a reference node on the axis at each bearing
centre whose displacement is the distributing coupling's (RBE3) weighted average of its
journal surface, written as *EQUATION (the work-conjugate of fe-crank's coupling, so
the force a spring puts on the reference node reaches the surface as fe-crank
distributes it), a SPRING1 of the same stiffness on its x and y, the thrust bearing's z
held; one node of the power take-off's face held tangentially against the rotation
about the axis (the loads are balanced about it: its reaction is round-off).

Compared: the bearings' forces, the displacement at the bearings' reference points, the
von Mises stress at every shaft fillet node (relative to the largest; CalculiX
extrapolates its integration points to the corners, fe-crank evaluates its P2 field at
the nodes: docs/performance.md, "CalculiX"), wall time, CPU time and peak memory of each
process (fe-crank: the whole cycle; CalculiX: one angle).  CalculiX is installed by
``calculix_compare.ensure_ccx`` when it is missing (never by the tests).
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

FILLETS = ("crankpin_fillet_1", "crankpin_fillet_2", "journal_fillet_1", "journal_fillet_2")


def _patterns(cond, kind: str, material, half_angle: float) -> dict[str, np.ndarray]:
    from fe_crank.fe.shaft.patterns import end_patterns, surface_patterns, throw_patterns

    faces = ("end_1", "end_2")
    basis = cond.basis
    pats = (
        throw_patterns(basis, material.density, half_angle, faces)
        if kind == "throw"
        else end_patterns(basis, material.density, faces)
    )
    for s in cond.phi_names:
        surf = s.split(".")[0]
        if s.endswith(".P0"):
            pats.update(surface_patterns(basis, surf)[0])
    return pats


def fe_worker(args) -> int:
    """fe-crank's side; writes <work>/fe.npz and the CalculiX deck."""
    from ccx_deck import c3d10_connectivity

    from fe_crank.fe.core.stress import stress_at_selected_nodes, von_mises
    from fe_crank.fe.shaft.cases import _terms, applied_loads
    from fe_crank.fe.shaft.fields import piece_fields
    from fe_crank.fe.shaft.whole_shaft import analyse_whole_shaft, throw_masses
    from fe_crank.geometry.shaft import engine_shaft_layout
    from fe_crank.geometry.spec import BearingLaw
    from fe_crank.io.loadcase import load_loadcase
    from fe_crank.mechanism.cycles import engine_cycles
    from fe_crank.mesh.shaft import mesh_shaft, node_maps, tet10

    work = Path(args.work)
    lc = load_loadcase(args.loadcase)
    layout = engine_shaft_layout(lc.geometry, lc.engine, geometry_file=lc.geometry.file, engine_file=lc.engine_file)
    laws = [BearingLaw("spring", args.stiffness)] * len(layout.bearings)
    dyn = engine_cycles(lc.engine, lc.operating).operating
    t0 = time.perf_counter()
    sm = mesh_shaft(layout, size=args.preset, cache_dir=".cache")
    result, cases = analyse_whole_shaft(sm, lc.material, dyn, mass=throw_masses(layout), laws=laws)
    peaks = np.array([np.hypot(*b.with_counterweights.load_n.T) for b in result.bearings])  # (nb, n)
    i = int(np.argmax(peaks.max(axis=0)))
    W = result.cycles[0].weights[i]
    fields = piece_fields(cases, W, lc.material)
    t_fe = time.perf_counter() - t0
    # the bearings' reference displacements at that angle (shaft frame; their forces -k d)
    model = cases.model
    d = result.cycles[0].displacement[i]
    sm = model.mesh
    whole = sm.whole()
    maps = node_maps(sm, whole)
    n = whole.doflocs.shape[1]
    u = np.zeros((3, n))
    load = np.zeros((3, n))
    weights = np.zeros((len(model.bearings), 3, 3 * n))
    names, loads = applied_loads(model)
    a_applied = _terms(model, loads)  # the applied loads without the base bearings' reactions
    applied = [cases.index(x) for x in names]
    torque = float(cases.base[5] @ W)  # reaction of the power take-off about z (statics)
    pats_by = {}
    for k, pp in enumerate(model.pieces):
        c = pp.cond
        if id(c) not in pats_by:
            pats_by[id(c)] = _patterns(c, pp.kind, lc.material, np.deg2rad(60.0))
        pats = pats_by[id(c)]
        a = a_applied[k] @ W[applied]
        f = sum(a[j] * pats[nm] for j, nm in enumerate(c.names) if a[j] != 0.0)
        if (k, model.torque_term[1]) == model.torque_term:
            f = f + torque * pats[model.torque_term[1]]
        load[:, maps[k]] += pp.R @ np.asarray(f).reshape(-1, 3).T
        u[:, maps[k]] = pp.R @ fields[k].reshape(-1, 3).T
        for b, bc in enumerate(model.bearings):
            for kk in range(3):
                for (p, pat), w in bc.terms[kk].items():
                    if p == k:
                        local = pats[pat].reshape(-1, 3)  # functional rows, local frame
                        weights[b, kk].reshape(n, 3)[maps[k]] += w * (local @ pp.R.T)
    conn = c3d10_connectivity(tet10(whole), whole.doflocs)
    fillet_nodes = np.unique(
        np.concatenate(
            [np.unique(whole.facets[:, whole.boundaries[b]]) for b in whole.boundaries if b.split("@")[0] in FILLETS]
        )
    )
    fillet_nodes = np.unique(np.concatenate([fillet_nodes, _edge_nodes(whole, fillet_nodes)]))
    E, nu = lc.material.youngs_modulus, lc.material.poisson_ratio
    vm_fe = von_mises(stress_at_selected_nodes(whole, [u.T.ravel()], E, nu, fillet_nodes)[0])  # P2, averaged
    np.savez(
        work / "fe.npz",
        d=d,
        u=u,
        load=load,
        weights=weights,
        points=whole.doflocs,
        conn=conn,
        t_fe=t_fe,
        angle=float(result.crank_angle_deg[i]),
        n_dof=3 * n,
        fillet_nodes=fillet_nodes,
        vm_fe=vm_fe,
        bearing_z=np.array([b.z for b in layout.bearings]),
        thrust=np.array([b.thrust for b in layout.bearings]),
        pto_face=np.unique(
            whole.facets[:, whole.boundaries["end_rear" if layout.power_takeoff == "rear" else "end_front"]]
        ),
        youngs=lc.material.youngs_modulus,
        poisson=lc.material.poisson_ratio,
    )
    return 0


def _edge_nodes(mesh, vertices: np.ndarray) -> np.ndarray:
    """The mid-edge P2 nodes of the edges between the given vertices (a surface's P2 nodes)."""
    on = np.zeros(mesh.nvertices, bool)
    on[vertices] = True
    e = np.flatnonzero(on[mesh.edges[0]] & on[mesh.edges[1]])
    return mesh.nvertices + e


def write_deck(work: Path, stiffness: float) -> Path:
    from ccx_deck import _chunks, _lines, static_step

    z = np.load(work / "fe.npz")
    x, conn, load, weights = z["points"], z["conn"], z["load"], z["weights"]
    N = x.shape[1]
    out = ["*HEADING", "fe-crank whole shaft (benchmarks/verification/shaft_calculix.py)", "*NODE, NSET=NALL"]
    out.append(_lines(np.column_stack([np.arange(1, N + 1), x.T]), "%d, %.13e, %.13e, %.13e"))
    refs = N + 1 + np.arange(len(z["bearing_z"]))
    out.append(_lines([(r, 0.0, 0.0, zz) for r, zz in zip(refs, z["bearing_z"])], "%d, %.13e, %.13e, %.13e"))
    out += [
        "*ELEMENT, TYPE=C3D10, ELSET=EALL",
        _lines(np.column_stack([np.arange(1, len(conn) + 1), conn]), "%d" + ", %d" * 10),
    ]
    out += [
        "*MATERIAL, NAME=STEEL",
        "*ELASTIC",
        f"{float(z['youngs']):.13e}, {float(z['poisson']):.13e}",
        "*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL",
    ]
    eid = len(conn)
    bcs = []
    for b, r in enumerate(refs):
        dirs = (0, 1, 2) if z["thrust"][b] else (0, 1)
        for k in dirs:
            w = weights[b, k]
            nz = np.flatnonzero(np.abs(w) > 1e-14 * np.abs(w).max())
            first = nz[np.argmax(np.abs(w[nz]))]  # the dependent dof: the largest weight
            terms = [(first // 3 + 1, first % 3 + 1, w[first])]
            terms += [(j // 3 + 1, j % 3 + 1, w[j]) for j in nz if j != first]
            terms.append((r, k + 1, -1.0))
            out += ["*EQUATION", str(len(terms))]
            for s in range(0, len(terms), 4):
                out.append(", ".join(f"{nd}, {dof}, {c:.13e}" for nd, dof, c in terms[s : s + 4]))
        for k in (0, 1):
            eid += 1
            out += [
                f"*ELEMENT, TYPE=SPRING1, ELSET=SP{eid}",
                f"{eid}, {r}",
                f"*SPRING, ELSET=SP{eid}",
                str(k + 1),
                f"{stiffness:.13e}",
            ]
        bcs.append((r, 3))  # the thrust bearing's z is tied to its journal; the others' is free of all
    face = z["pto_face"]
    far = face[np.argmax(x[0, face])]  # on +x: its y is the tangential direction
    bcs.append((far + 1, 2))
    out += ["*BOUNDARY", _lines([(nd, d, d) for nd, d in bcs], "%d, %d, %d")]
    out += ["*NSET, NSET=NOUT", _chunks(np.concatenate([z["fillet_nodes"] + 1, refs]))]
    out += static_step(load.T)
    path = work / "shaft.inp"
    path.write_text("\n".join(out) + "\n")
    return path


def main(argv=None) -> int:
    from calculix_compare import _threads_env, ensure_ccx, run_measured
    from ccx_deck import read_dat_displacements, read_frd_stresses

    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--loadcase", default="loadcases/inline4_rated.toml")
    p.add_argument("--preset", default="test")
    p.add_argument("--stiffness", type=float, default=5e8, help="radial stiffness of every bearing, N/m")
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--work", default="reports/shaft_calculix")
    p.add_argument("--reuse-ccx", action="store_true", help="take CalculiX's results of the last run (same deck)")
    p.add_argument("--worker", action="store_true", help=argparse.SUPPRESS)
    p.add_argument("--json")
    args = p.parse_args(argv)
    work = Path(args.work)
    work.mkdir(parents=True, exist_ok=True)
    if args.worker:
        return fe_worker(args)
    env = _threads_env(args.threads)
    me = [
        sys.executable,
        __file__,
        "--worker",
        "--loadcase",
        args.loadcase,
        "--preset",
        args.preset,
        "--stiffness",
        str(args.stiffness),
        "--work",
        str(work),
    ]
    fe_wall, fe_mem, rc, fe_cpu = run_measured(me, None, env, quiet=False)
    if rc:
        return rc
    deck = write_deck(work, args.stiffness)
    if args.reuse_ccx:  # the deck is the same: CalculiX's results and figures of the last run
        cx_wall, cx_mem, cx_cpu = json.loads((work / "ccx_run.json").read_text())
    else:
        ccx = ensure_ccx()
        cx_wall, cx_mem, rc, cx_cpu = run_measured([ccx, "-i", deck.stem], work, env)
        if rc:
            print(f"CalculiX failed (exit {rc}): {work / 'last_run.log'}")
            return rc
        (work / "ccx_run.json").write_text(json.dumps([cx_wall, cx_mem, cx_cpu]))
    z = np.load(work / "fe.npz")
    N = z["points"].shape[1]
    refs = N + 1 + np.arange(len(z["bearing_z"]))
    (disp,) = read_dat_displacements(work / "shaft.dat")
    (stress,) = read_frd_stresses(work / "shaft.frd")
    d_cx = np.array([disp[r][:2] for r in refs])
    d_fe = z["d"]
    f_fe, f_cx = -args.stiffness * d_fe, -args.stiffness * d_cx
    from fe_crank.fe.core.stress import von_mises

    nodes = z["fillet_nodes"]
    vm_cx = np.array([von_mises(stress[n + 1]) for n in nodes])
    vm_fe = z["vm_fe"]
    rec = {
        "loadcase": args.loadcase,
        "preset": args.preset,
        "n_dof": int(z["n_dof"]),
        "stiffness_n_per_m": args.stiffness,
        "angle_deg": float(z["angle"]),
        "fe_crank": {
            "wall_s": fe_wall,
            "cpu_s": fe_cpu,
            "peak_gb": fe_mem,
            "what": "whole cycle (720 angles) + one field",
        },
        "calculix": {"wall_s": cx_wall, "cpu_s": cx_cpu, "peak_gb": cx_mem, "what": "one angle"},
        "bearing_force_n": {"fe_crank": f_fe.tolist(), "calculix": f_cx.tolist()},
        "bearing_force_diff_rel": float(np.abs(f_fe - f_cx).max() / np.abs(f_fe).max()),
        "fillet_von_mises_peak_pa": {"fe_crank": float(vm_fe.max()), "calculix": float(vm_cx.max())},
        "fillet_von_mises_diff_rel": float(np.abs(vm_fe - vm_cx).max() / vm_fe.max()),
        "fillet_peak_diff_rel": float(vm_cx.max() / vm_fe.max() - 1.0),
    }
    print(json.dumps(rec, indent=2))
    if args.json:
        Path(args.json).write_text(json.dumps(rec, indent=2))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
