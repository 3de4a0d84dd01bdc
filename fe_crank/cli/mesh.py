"""``fe-crank mesh GEOMETRY.toml [-o DIR]``: build, mesh (cached) and picture crank throws.

``GEOMETRY.toml``: a parametric geometry file, a TOML holding a ``[cad]`` section (a CAD
file, ``fe_crank.io.cad``), or a load case (its geometry, either kind).  Prints the mass
properties of each throw (from the OCC solid; for a CAD file every recognised feature
first) and the mesh statistics, the cached ``.msh``/``.vtu`` paths, copies them into
``DIR`` and writes an offscreen pyvista picture ``DIR/<geometry>_throw<name>.png``.
"""

from __future__ import annotations

import argparse
import math
import shutil
from pathlib import Path

from fe_crank.mesh import DEFAULT_CACHE_DIR, PRESETS


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("geometry", help="geometry file (geometry/*.toml), a TOML file with a [cad] section, or a load case")
    p.add_argument(
        "-o",
        "--output",
        default="reports",
        metavar="DIR",
        help="folder for the picture and mesh copies (default: reports/)",
    )
    p.add_argument("--throw", default=None, help="throw name to mesh, or 'all' (default: the first throw)")
    p.add_argument(
        "--mesh-size",
        default="coarse",
        choices=sorted(PRESETS),
        help="mesh preset (default coarse: fillet elements <= r/4; test is for quick trials only)",
    )
    p.add_argument(
        "--cache-dir",
        default=str(DEFAULT_CACHE_DIR),
        metavar="DIR",
        help=f"mesh cache folder (default: {DEFAULT_CACHE_DIR}, relative to the working directory)",
    )
    p.add_argument("--no-render", action="store_true", help="do not render the PNG")
    p.add_argument(
        "--max-elements",
        type=int,
        default=None,
        metavar="N",
        help="raise the limit on the estimated element count (docs/limits.md)",
    )


def render_png(vtu_path: Path, png_path: Path, title: str = "") -> None:
    """Offscreen pyvista picture of a meshed throw coloured by subdomain (lazy import)."""
    import pyvista as pv

    grid = pv.read(str(vtu_path))
    surf = grid.extract_surface(nonlinear_subdivision=1, algorithm="dataset_surface")
    pl = pv.Plotter(off_screen=True, window_size=(1200, 900))
    pl.add_mesh(
        surf,
        scalars="subdomain",
        show_edges=True,
        edge_color="black",
        line_width=0.3,
        cmap="tab10",
        show_scalar_bar=False,
    )
    if title:
        pl.add_text(title, font_size=10)
    pl.view_vector((1.0, 0.6, -1.3), viewup=(0.0, 1.0, 0.0))  # front-right, from above; crankpin up
    tmp = png_path.with_name("." + png_path.name + ".tmp.png")
    pl.screenshot(str(tmp))
    pl.close()
    tmp.replace(png_path)


def _source(path: str):
    """The geometry a file gives: parametric, a CAD file's ``CadInput``, or a load case's."""
    from fe_crank.errors import InputError
    from fe_crank.io.base import read_toml
    from fe_crank.io.cad import load_cad
    from fe_crank.io.geometry import load_geometry
    from fe_crank.io.loadcase import load_loadcase

    data = read_toml(path, record=False)
    if "operating" in data:
        lc = load_loadcase(path)
        if lc.geometry is None:
            raise InputError("the load case gives no geometry", file=path, key="geometry")
        return lc.geometry
    if "cad" in data:
        return load_cad(path)
    return load_geometry(path)


def _keep(tm, out: Path, stem: str, name: str, title: str, no_render: bool) -> None:
    """Copy the cached mesh into ``out`` and picture it."""
    print(f"  cached: {tm.msh_path}")
    base = out / f"{stem}_throw{name}"
    shutil.copyfile(tm.msh_path, base.with_suffix(".msh"))
    shutil.copyfile(tm.vtu_path, base.with_suffix(".vtu"))
    if not no_render:
        png = base.with_suffix(".png")
        render_png(tm.vtu_path, png, title)
        print(f"  picture: {png}")


def _stats(tm, size: str) -> None:
    s = tm.stats
    print(
        f"  mesh ({size}{', cached' if s.from_cache else ''}): {s.nodes} nodes, {s.elements} quadratic tets, "
        f"{s.p2_dofs} P2 DOFs, min quality {s.min_quality:.3g}, {s.straightened} elements straightened, "
        f"built in {s.build_seconds:.1f} s"
    )
    if s.symmetry:  # exact mirror image across these planes (docs/geometry.md)
        print("  mirrored across " + ", ".join({0: "x = 0", 2: "z = 0"}[a] for a in s.symmetry))
    for name, h in s.fillet_max_edge.items():
        r = s.fillet_radii[name]
        print(f"  {name}: r {r * 1e3:g} mm, largest edge {h * 1e3:.3g} mm (r/{r / h:.2f})")


def _cad(cad, args: argparse.Namespace, out: Path) -> int:
    """A CAD file: its recognised features, then the throws asked for meshed."""
    from fe_crank.cad import feature_lines, recognise
    from fe_crank.cad.source import mesh_source_throw
    from fe_crank.errors import InputError

    features = recognise(cad)
    print("\n".join(feature_lines(features)))
    names = [t.name for t in features.throws]
    if args.throw in (None, ""):
        names = names[:1]
    elif args.throw != "all":
        if args.throw not in names:
            raise InputError(f"no throw named {args.throw!r}; throws are {names}", file=args.geometry, key="--throw")
        names = [args.throw]
    for name in names:
        tm = mesh_source_throw(cad, name, size=args.mesh_size, cache_dir=args.cache_dir, max_elements=args.max_elements)
        print(f"throw {name} (CAD):")
        _stats(tm, args.mesh_size)
        _keep(tm, out, cad.file.stem, name, f"{cad.file.name}, throw {name}", args.no_render)
    return 0


def run(args: argparse.Namespace) -> int:
    from fe_crank.cad.config import CadInput
    from fe_crank.cad.source import mesh_source_throw
    from fe_crank.geometry.mass import mass_properties

    g = _source(args.geometry)
    out = Path(args.output)
    out.mkdir(parents=True, exist_ok=True)
    if isinstance(g, CadInput):
        return _cad(g, args, out)
    if args.throw in (None, ""):
        throws = [g.throws[0]]
    elif args.throw == "all":
        throws = list(g.throws)
    else:
        try:
            throws = [g.throw(args.throw)]
        except KeyError as exc:
            from fe_crank.errors import InputError

            raise InputError(str(exc.args[0]), file=args.geometry, key="--throw") from None
    stem = Path(args.geometry).stem
    print(
        f"{g.name}  ({len(g.throws)} throw(s), R = {g.crank_radius * 1e3:g} mm, pin/journal overlap {g.pin_overlap * 1e3:.3g} mm)"
    )
    for spec in throws:
        mp = mass_properties(g, spec)
        tot = mp.total
        print(
            f"throw {spec.name} (angle {spec.angle * 57.29577951308232:g} deg): mass {tot.mass:.4g} kg, "
            f"centroid y {tot.centroid[1] * 1e3:.4g} mm, unbalance m r {tot.unbalance * 1e3:.4g} kg mm, "
            f"J_z {tot.inertia_axis:.4g} kg m^2"
        )
        for web in (1, 2):
            part = mp.parts.get(f"counterweight_{web}")
            if part is not None:
                ux, uy = part.unbalance_vector
                turn = (
                    f", turned {math.degrees(math.atan2(ux, -uy)):.4g} deg"
                    if ux != 0.0 and abs(ux) > 1e-9 * abs(uy)
                    else ""
                )
                print(
                    f"  counterweight_{web}: mass {part.mass:.4g} kg at r_c {math.hypot(*part.centroid[:2]) * 1e3:.4g} mm"
                    f"{turn}, m r {part.unbalance * 1e3:.4g} kg mm"
                )
        tm = mesh_source_throw(
            g, spec.name, size=args.mesh_size, cache_dir=args.cache_dir, max_elements=args.max_elements
        )
        _stats(tm, args.mesh_size)
        _keep(tm, out, stem, spec.name, f"{g.name}, throw {spec.name}", args.no_render)
    return 0
