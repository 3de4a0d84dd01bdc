"""Full-cycle benchmark: unit-load superposition vs solving every crank angle.

Builds a P2 crank throw, solves the FE stage's unit cases on one factorisation, then
assesses the whole cycle (720 angles at 1 deg) by superposition, and times a few direct
solves (load vector + solve with the factorisation + stress recovery) to extrapolate the
cost of solving all 720 angles.  Also reports how far the superposed fillet stress is
from a direct solve with a single cosine arc centred on the actual pin-force resultant
(the FE stage builds it from the two pin directions that bracket it; docs/performance.md).

    .venv/bin/python benchmarks/cycle_bench.py --size 4.0 [--angles 5] [--json out.json]
    .venv/bin/python benchmarks/cycle_bench.py --geometry geometry/single_cylinder_seed001.toml --preset medium

Without ``--geometry`` the throw is built here with gmsh OCC (journals d 50, pin d 45 at
R 40, webs 15 mm, counterweights on -y; no fillet radii, the groups named *_fillet_* are
the pin and journal surfaces next to the webs), uniform element size ``--size`` (mm).
With ``--geometry`` the real filleted throw of that file is meshed by ``mesh_throw`` at
``--preset`` (the fillet groups are then real fillets).
"""

from __future__ import annotations

import argparse
import json
import resource
import sys
import time

import numpy as np


def build_throw(size_mm: float):
    """A simple crank throw as a P2 scikit-fem mesh with the contract's group names."""
    from fe_crank.gmsh_io import gmsh_session, model_to_skfem

    mm = 1e-3
    R, rj, rp, lj, w, lp = 40 * mm, 25 * mm, 22.5 * mm, 30 * mm, 15 * mm, 40 * mm
    with gmsh_session() as gmsh:
        occ = gmsh.model.occ
        z = 0.0
        j1 = occ.addCylinder(0, 0, z, 0, 0, lj, rj)
        z += lj
        w1 = occ.addBox(-40 * mm, -35 * mm, z, 80 * mm, R + 35 * mm + 25 * mm, w)
        c1 = occ.addCylinder(0, 0, z, 0, 0, w, 75 * mm)
        cw1 = occ.intersect([(3, c1)], [(3, occ.addBox(-80 * mm, -80 * mm, z, 160 * mm, 45 * mm, w))])[0]
        z += w
        pin = occ.addCylinder(0, R, z, 0, 0, lp, rp)
        z += lp
        w2 = occ.addBox(-40 * mm, -35 * mm, z, 80 * mm, R + 35 * mm + 25 * mm, w)
        c2 = occ.addCylinder(0, 0, z, 0, 0, w, 75 * mm)
        cw2 = occ.intersect([(3, c2)], [(3, occ.addBox(-80 * mm, -80 * mm, z, 160 * mm, 45 * mm, w))])[0]
        z += w
        j2 = occ.addCylinder(0, 0, z, 0, 0, lj, rj)
        z += lj
        parts = [(3, j1), (3, w1), (3, pin), (3, w2), (3, j2)] + cw1 + cw2
        occ.fragment(parts, [])
        occ.synchronize()
        vols = gmsh.model.getEntities(3)
        zc = {v[1]: occ.getCenterOfMass(3, v[1]) for v in vols}
        names = {}
        for tag, (_cx, cy, cz) in zc.items():
            if cz < lj:
                names[tag] = "journal_1"
            elif cz < lj + w:
                names[tag] = "counterweight_1" if cy < -36 * mm else "web_1"
            elif cz < lj + w + lp:
                names[tag] = "crankpin"
            elif cz < lj + 2 * w + lp:
                names[tag] = "counterweight_2" if cy < -36 * mm else "web_2"
            else:
                names[tag] = "journal_2"
        for name in sorted(set(names.values())):
            gmsh.model.addPhysicalGroup(3, [t for t, n in names.items() if n == name], name=name)
        faces = {}
        for _, s in gmsh.model.getEntities(2):
            cx, cy, cz = occ.getCenterOfMass(2, s)
            bb = gmsh.model.getBoundingBox(2, s)
            ztop, zbot = bb[5], bb[2]
            flat = abs(ztop - zbot) < 1e-6
            if flat and abs(cz) < 1e-9:
                faces.setdefault("end_1", []).append(s)
            elif flat and abs(cz - z) < 1e-9:
                faces.setdefault("end_2", []).append(s)
            elif not flat and np.hypot(cx, cy - R) < 1e-3 and zbot >= lj + w - 1e-6 and ztop <= lj + w + lp + 1e-6:
                faces.setdefault("crankpin", []).append(s)
            elif not flat and np.hypot(cx, cy) < 1e-3 and ztop <= lj + 1e-6:
                faces.setdefault("journal_1", []).append(s)
            elif not flat and np.hypot(cx, cy) < 1e-3 and zbot >= z - lj - 1e-6:
                faces.setdefault("journal_2", []).append(s)
        for name, tags in faces.items():
            gmsh.model.addPhysicalGroup(2, tags, name=name)
        # "fillet" groups: the pin and journal surfaces next to each web (stand-ins, no radii)
        gmsh.option.setNumber("Mesh.MeshSizeMax", size_mm * mm)
        gmsh.option.setNumber("Mesh.MeshSizeMin", 0.25 * size_mm * mm)
        gmsh.option.setNumber("Mesh.ElementOrder", 2)
        gmsh.option.setNumber("Mesh.HighOrderOptimize", 0)
        gmsh.model.mesh.generate(3)
        mesh = model_to_skfem()
    fill = {}
    f = mesh.facets
    mid = mesh.p[:, f].mean(axis=1)
    pin_f = mesh.boundaries["crankpin"]
    jz = mid[2]
    fill["crankpin_fillet_1"] = pin_f[jz[pin_f] < lj + w + 5 * mm]
    fill["crankpin_fillet_2"] = pin_f[jz[pin_f] > lj + w + lp - 5 * mm]
    fill["journal_fillet_1"] = mesh.boundaries["journal_1"][jz[mesh.boundaries["journal_1"]] > lj - 5 * mm]
    fill["journal_fillet_2"] = mesh.boundaries["journal_2"][jz[mesh.boundaries["journal_2"]] < z - lj + 5 * mm]
    return mesh.with_boundaries({**mesh.boundaries, **fill})


def loads_for(units, basis, mat):
    from fe_crank.fe.loads import centrifugal_load, face_torque_load, pin_pressure_load
    from fe_crank.fe.unit_cases import PIN_FORCES

    return {
        "centrifugal": lambda: centrifugal_load(basis, mat.density, 1.0),
        "torque": lambda: face_torque_load(basis, units.cases["torque"].applied[5], boundary="end_1"),
        **{k: (lambda f=f: pin_pressure_load(basis, f)[0]) for k, f in PIN_FORCES.items()},
    }


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--size", type=float, default=5.0, help="element size, mm")
    ap.add_argument("--angles", type=int, default=4, help="direct solves to time")
    ap.add_argument("--solver", default="auto")
    ap.add_argument("--geometry", default=None, help="geometry file: mesh its first throw with mesh_throw")
    ap.add_argument("--preset", default="coarse", help="mesh preset with --geometry")
    ap.add_argument("--json", default=None)
    args = ap.parse_args(argv)

    from fe_crank.assess import unit_stresses
    from fe_crank.assess.stress import von_mises
    from fe_crank.assess.superpose import combine, load_coefficients, stress_history
    from fe_crank.assess.throw import assess_throw
    from fe_crank.fe.loads import pin_pressure_load
    from fe_crank.fe.unit_cases import FeOptions, solve_unit_cases
    from fe_crank.io.loadcase import load_loadcase
    from fe_crank.io.material import load_material
    from fe_crank.mechanism.dynamics import analyse

    out = {}
    t0 = time.perf_counter()
    crank_radius = 0.04
    if args.geometry:
        from fe_crank.io.geometry import load_geometry
        from fe_crank.mesh import mesh_throw

        g = load_geometry(args.geometry)
        mesh = mesh_throw(g, size=args.preset, cache_dir=".cache/meshes").mesh
        crank_radius = g.crank_radius
        out["model"] = f"{args.geometry} ({args.preset})"
    else:
        mesh = build_throw(args.size)
        out["model"] = f"build_throw({args.size} mm)"
    out["mesh_s"] = time.perf_counter() - t0
    mat = load_material("42CrMo4")
    units = solve_unit_cases(mesh, mat, FeOptions(solver=args.solver))
    tm = units.timings
    out.update(
        nodes=int(units.points.shape[1]),
        elements=int(mesh.t.shape[1]),
        dof=int(units.n_dof),
        solver=units.solver,
        assembly_s=tm.get("assembly"),
        constraints_s=tm.get("constraints"),
        factorisation_s=tm.get("factorisation"),
        unit_loads_s=tm.get("loads"),
        unit_solves_s=tm.get("solve"),
        n_unit_cases=len(units.cases),
    )
    # a real cycle: seed-001 single cylinder at its speed (pin forces scaled to this throw only by use)
    lc = load_loadcase("loadcases/single_cylinder_seed001.toml")
    dyn = analyse(lc.engine, lc.operating)
    tl = next(iter(dyn.throws.values()))
    theta = dyn.theta
    t0 = time.perf_counter()
    unit = unit_stresses(units)
    out["unit_stress_recovery_s"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    ta = assess_throw(
        "1",
        unit,
        theta,
        tl.pin_force,
        tl.torque_front,
        omega=lc.operating.speed,
        overspeed=lc.operating.overspeed,
        material=mat,
        crank_radius=crank_radius,
    )
    out["superposition_and_assessment_s"] = time.perf_counter() - t0
    out["n_angles"] = int(theta.size)
    out["assessed_nodes"] = int(unit.n_nodes)
    coeffs = load_coefficients(
        tl.pin_force, tl.torque_front, lc.operating.speed, cases=unit.cases, torque_mz=unit.torque_mz
    )
    basis = units.system.basis
    makers = loads_for(units, basis, mat)
    t0 = time.perf_counter()
    unit_f = np.stack([makers[c]() for c in unit.cases])
    out["unit_load_vectors_s"] = time.perf_counter() - t0
    fillet = np.concatenate([unit.groups[g] for g in unit.groups if "fillet" in g])
    sup = stress_history(unit, coeffs)
    picks = np.linspace(0, theta.size - 1, args.angles).astype(int)
    direct_t, lin_err, phys_dev = [], [], []
    for k in picks:
        t0 = time.perf_counter()
        # per-angle direct solve as one would do without superposition: build the load
        # (a cosine arc centred on the actual resultant), solve, recover stress
        f = combine(
            unit_f[[i for i, c in enumerate(unit.cases) if not c.startswith("pin")]],
            coeffs[k, [i for i, c in enumerate(unit.cases) if not c.startswith("pin")]],
        )[0]
        f = f + pin_pressure_load(basis, tl.pin_force[k])[0]
        u = units.system.solve(f)
        s = units.stress_at_nodes(u)[:, unit.node_ids]
        direct_t.append(time.perf_counter() - t0)
        vm_phys = von_mises(s[:, fillet][None])[0]
        vm_sup = von_mises(sup[k][:, fillet][None])[0]
        phys_dev.append(float(np.max(np.abs(vm_phys - vm_sup)) / np.max(vm_phys)))
        u_lin = units.system.solve(combine(unit_f, coeffs[k])[0])
        s_lin = units.stress_at_nodes(u_lin)[:, unit.node_ids]
        lin_err.append(float(np.max(np.abs(s_lin - sup[k])) / np.max(np.abs(s_lin))))
    out["direct_per_angle_s"] = float(np.mean(direct_t))
    out["direct_720_extrapolated_s"] = float(np.mean(direct_t) * theta.size)
    out["superposition_vs_linear_direct_max_rel"] = max(lin_err)
    out["superposition_vs_single_arc_fillet_vm_max_rel"] = max(phys_dev)
    out["single_arc_deviation_by_angle"] = {
        f"{np.rad2deg(theta[k]):.0f} deg": round(d, 5) for k, d in zip(picks, phys_dev)
    }
    out["fatigue_min_safety"] = min(g.fatigue_safety.value for g in ta.groups if g.fatigue_safety)
    out["peak_rss_gb"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1e6
    total_sup = sum(
        out[k] or 0
        for k in (
            "assembly_s",
            "constraints_s",
            "factorisation_s",
            "unit_loads_s",
            "unit_solves_s",
            "unit_stress_recovery_s",
            "superposition_and_assessment_s",
        )
    )
    out["total_superposition_route_s"] = total_sup
    out["total_direct_route_s"] = (
        sum(out[k] or 0 for k in ("assembly_s", "constraints_s", "factorisation_s")) + out["direct_720_extrapolated_s"]
    )
    text = json.dumps(out, indent=2)
    print(text)
    if args.json:
        with open(args.json, "w") as fh:
            fh.write(text + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
