"""Bores of a throw: oil bores and axial bores (hollow pins and journals).

* oil bores: concave cylinders (holes) narrower than half the pin (journal) that meet the
  crankpin (a journal of the throw); every face on the same line with the same radius
  within the throw belongs to the bore (``[cad.faces] oil_bore`` names them outright, or
  ``[]``: none);
* axial bores: the widest hole along the pin's (journal's) axis.
"""

from __future__ import annotations

from fe_crank.cad.axis import Line, line_of
from fe_crank.cad.chains import cylinder_groups, extent
from fe_crank.cad.survey import Face
from fe_crank.errors import InputError


def oil_bores(ctx, name: str, near: list[tuple[list[Face], float]], span: tuple[float, float]):
    """The faces of each oil bore of throw ``name``: holes meeting a host of ``near``
    ((faces, radius) of the pin and the journals), within the shaft positions ``span``."""
    given = ctx.cad.override("oil_bore", name)
    ax, tol = ctx.axis, ctx.tol
    holes = [f for f in ctx.faces.values() if f.kind == "cylinder" and not f.convex]
    if given is not None:
        bad = [t for t in given.faces if t not in ctx.faces or ctx.faces[t] not in holes]
        if bad:
            raise InputError(f"faces {bad} are not holes of the model", file=str(ctx.cad.file), key=given.key)
        groups = cylinder_groups([ctx.faces[t] for t in given.faces], tol)
    else:
        starts = []
        for host, r in near:
            tags = {t for f in host for t in ctx.nbrs[f.tag]}
            starts += [f for f in holes if f.tag in tags and f.radius < r / 2]
        groups = cylinder_groups(starts, tol)
    out = []
    for g in groups:
        line = line_of(g[0])
        members = [
            f
            for f in holes
            if abs(f.radius - g[0].radius) <= tol
            and line_of(f).same(line, tol)
            and span[0] - tol <= extent([f], ax)[0]
            and extent([f], ax)[1] <= span[1] + tol
        ]
        out.append(tuple(sorted(members, key=lambda f: f.tag)))
    return tuple(out)


def axial_bore(ctx, line: Line, lo: float, hi: float) -> float:
    """Diameter of the widest hole along ``line`` within [lo, hi] (a hollow pin or journal)."""
    ax, tol = ctx.axis, ctx.tol
    found = [
        f.radius
        for f in ctx.faces.values()
        if f.kind == "cylinder"
        and not f.convex
        and line_of(f).same(line, tol)
        and extent([f], ax)[0] < hi - tol
        and extent([f], ax)[1] > lo + tol
    ]
    return 2.0 * max(found, default=0.0)
