"""Counterweight hot spot under local refinement (not in CI).

Meshes one throw of a geometry file at a mesh preset, with an extra size field of
element edge ``--corner-size`` within ``--corner-radius`` of the vertical lines where a
counterweight sector's radial sides cross the web's journal-end circle (the corners of
the web-plus-counterweight outline), solves the centrifugal unit case, and prints the
largest von Mises stress at the counterweight and junction nodes at ``--speed`` with
where it is.  A stress that keeps growing as ``--corner-size`` shrinks is a singular
(sharp re-entrant) edge; one that settles is a resolvable concentration.

    python benchmarks/studies/counterweight_hotspot.py geometry/single_cylinder.toml \
        --preset test --corner-size 1 --speed "3360 rpm"
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import resource
import time

import numpy as np


def corner_points(g, spec):
    """(x, y) of the points where each counterweight's radial sides cross the web's
    journal-end circle (radius r_a about the axis), throw frame."""
    ra = g.web.journal_end_radius
    out = []
    for cw in spec.counterweights:
        if cw.inner_radius < ra < cw.outer_radius:
            for s in (-1.0, 1.0):
                a = math.pi + s * cw.angle / 2  # from +y towards +x
                out.append((ra * math.sin(a), ra * math.cos(a)))
    return out


def main(argv=None):
    from fe_crank.assess.group.nodes import assessed_groups
    from fe_crank.fe import FeOptions, solve_unit_cases
    from fe_crank.fe.core.stress import stress_at_selected_nodes, von_mises
    from fe_crank.geometry.throw import add_throw
    from fe_crank.gmsh_io import gmsh_session, model_to_skfem
    from fe_crank.io.geometry import load_geometry
    from fe_crank.io.material import load_material
    from fe_crank.io.units import to_si
    from fe_crank.mesh.fields import surface_field
    from fe_crank.mesh.options import FILLET_SAFETY, resolve_options
    from fe_crank.mesh.quality import straighten_poor
    from fe_crank.mesh.sizing import counterweight_fillet_radius, set_size_fields
    from fe_crank.mesh.types import MeshStats, ThrowMesh

    ap = argparse.ArgumentParser()
    ap.add_argument("geometry")
    ap.add_argument("--preset", default="test")
    ap.add_argument("--corner-size", type=float, default=0.0, help="mm; 0: no extra refinement")
    ap.add_argument("--corner-radius", type=float, default=4.0, help="mm, radius of the refined zone")
    ap.add_argument("--speed", default="3360 rpm")
    ap.add_argument("--material", default="C45")
    ap.add_argument("--cw-fillet", type=float, default=None, help="mm: override the counterweight fillet radius")
    ap.add_argument(
        "--cw-divisions",
        type=float,
        default=None,
        help="counterweight fillet elements r/N (default: the preset's fillet_divisions)",
    )
    a = ap.parse_args(argv)

    g = load_geometry(a.geometry)
    if a.cw_fillet is not None:
        t = g.throws[0]
        cws = tuple(dataclasses.replace(c, fillet_radius=a.cw_fillet * 1e-3) for c in t.counterweights)
        g = dataclasses.replace(g, throws=(dataclasses.replace(t, counterweights=cws),) + g.throws[1:])
    spec = g.throws[0]
    opt = resolve_options(a.preset)
    omega = to_si(a.speed, "speed")
    t0 = time.process_time()
    with gmsh_session() as gmsh:
        model = add_throw(g, spec)
        size_max = set_size_fields(gmsh, g, model.surfaces, model.fillet_radii, opt)
        fld = gmsh.model.mesh.field
        if a.cw_divisions:
            bg = max(fld.list())
            extra = [bg]
            for name, tags in model.surfaces.items():
                if name.startswith("counterweight_fillet_"):
                    r = counterweight_fillet_radius(g, int(name[-1]))
                    extra.append(surface_field(gmsh, tags, FILLET_SAFETY * r / a.cw_divisions, size_max, opt.grading))
            mn = fld.add("Min")
            fld.setNumbers(mn, "FieldsList", extra)
            fld.setAsBackgroundMesh(mn)
        if a.corner_size > 0:
            bg = max(fld.list())
            h, rz = a.corner_size * 1e-3, a.corner_radius * 1e-3
            ths = [bg]
            for x, y in corner_points(g, spec):
                d = fld.add("MathEval")
                fld.setString(d, "F", f"Sqrt((x - ({x!r}))*(x - ({x!r})) + (y - ({y!r}))*(y - ({y!r})))")
                th = fld.add("Threshold")
                fld.setNumber(th, "InField", d)
                fld.setNumber(th, "SizeMin", h)
                fld.setNumber(th, "SizeMax", size_max)
                fld.setNumber(th, "DistMin", rz)
                fld.setNumber(th, "DistMax", rz + max(size_max - h, 0.0) / opt.grading)
                ths.append(th)
            mn = fld.add("Min")
            fld.setNumbers(mn, "FieldsList", ths)
            fld.setAsBackgroundMesh(mn)
        gmsh.option.setNumber("Mesh.Algorithm3D", 1)
        gmsh.option.setNumber("Mesh.Optimize", 1)
        gmsh.option.setNumber("Mesh.OptimizeNetgen", 1)
        gmsh.model.mesh.generate(3)
        gmsh.model.mesh.setOrder(2)
        straighten_poor(gmsh, spec.name)
        mesh = model_to_skfem()
    t_mesh = time.process_time() - t0
    stats = MeshStats(mesh.doflocs.shape[1], mesh.nelements, 3 * mesh.doflocs.shape[1], 1.0, 0, 1.0, {}, {}, 0.0)
    tm = ThrowMesh(mesh, stats, dict(model.fillet_radii), None, None, spec.name, "bench", opt)
    mat = load_material(a.material)
    units = solve_unit_cases(tm, mat, FeOptions(cases=("centrifugal",)))
    groups = {k: v for k, v in assessed_groups(units).items() if k.startswith(("counterweight", "junction"))}
    ids = np.unique(np.concatenate(list(groups.values())))
    u = omega**2 * units.displacement("centrifugal")
    s = stress_at_selected_nodes(
        units.mesh, [u], mat.youngs_modulus, mat.poisson_ratio, ids, dofs=units.system.basis.dofs
    )[0]
    vm = von_mises(s)
    i = int(np.argmax(vm))
    p = np.asarray(units.points)[:, ids[i]] * 1e3
    owners = [k for k, v in groups.items() if ids[i] in v]
    ru = resource.getrusage(resource.RUSAGE_SELF)
    rc = [c.fillet_radius for c in spec.counterweights if c.fillet_radius]
    print(
        f"preset={a.preset} cw_fillet={rc[0] * 1e3 if rc else 0:g} mm cw_divisions={a.cw_divisions or opt.fillet_divisions:g} "
        f"corner_size={a.corner_size:g} mm dof={units.n_dof} "
        f"max_vm={vm[i] / 1e6:.2f} MPa at ({p[0]:.1f}, {p[1]:.1f}, {p[2]:.1f}) mm r={math.hypot(p[0], p[1]):.2f} mm "
        f"groups={'+'.join(owners)} cpu_mesh={t_mesh:.1f}s cpu={ru.ru_utime + ru.ru_stime:.1f}s "
        f"peak_rss={ru.ru_maxrss / 1e6:.2f} GB"
    )


if __name__ == "__main__":
    main()
