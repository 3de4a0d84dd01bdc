"""gmsh size fields shared by the parametric and the CAD throw meshes.

Every refined feature gets a ``Threshold`` field: the element edge is ``h`` on (or near)
the feature and grows linearly with the distance, by ``grading`` m per m, to
``size_max``; the background size is the minimum of all of them.

* fillets that are part of a torus (rolling-ball fillets of a circular edge, the
  undercut fillets): the exact distance to the torus (:func:`torus_distance`, a
  ``MathEval`` field), so the size is ``h`` on the whole fillet however curved;
* other refined faces (oil bores, counterweight transition fillets, blends that are no
  torus): gmsh's sampled ``Distance`` to the faces;
* the webs, when the mesh options ask for elements across the web thickness (UR M53
  App. III 2.2): a ``Constant`` field inside the web volumes (:func:`web_field`).

Call inside :func:`fe_crank.gmsh_io.gmsh_session`.
"""

from __future__ import annotations


def torus_distance(cy: float, zc: float, a: float, rf: float) -> str:
    """gmsh MathEval expression: distance from (x, y, z) to a torus about the axis
    ``x = 0, y = cy`` (parallel to z), spine circle of radius ``a`` in the plane
    ``z = zc``, tube radius ``rf``: ``| dist(x, spine) - rf |`` (exact, unlike sampled
    ``Distance`` fields)."""
    rho = f"Sqrt(x*x + (y - ({cy!r}))*(y - ({cy!r})))"
    spine = f"Sqrt(({rho} - {a!r})*({rho} - {a!r}) + (z - ({zc!r}))*(z - ({zc!r})))"
    return f"Fabs({spine} - {rf!r})"


def torus_field(gmsh, expression: str, h: float, size_max: float, grading: float) -> int:
    """Threshold on a ``MathEval`` distance: ``h`` on the torus, growing by ``grading``."""
    d = gmsh.model.mesh.field.add("MathEval")
    gmsh.model.mesh.field.setString(d, "F", expression)
    th = gmsh.model.mesh.field.add("Threshold")
    gmsh.model.mesh.field.setNumber(th, "InField", d)
    gmsh.model.mesh.field.setNumber(th, "SizeMin", h)
    gmsh.model.mesh.field.setNumber(th, "SizeMax", size_max)
    gmsh.model.mesh.field.setNumber(th, "DistMin", 0.0)
    gmsh.model.mesh.field.setNumber(th, "DistMax", max(size_max - h, 0.0) / grading)
    return th


def bore_field(gmsh, tags: list[int], h: float, size_max: float, grading: float) -> int:
    """Threshold on gmsh's ``Distance`` to the faces (default sampling): ``h`` on them."""
    d = gmsh.model.mesh.field.add("Distance")
    gmsh.model.mesh.field.setNumbers(d, "SurfacesList", tags)
    th = gmsh.model.mesh.field.add("Threshold")
    gmsh.model.mesh.field.setNumber(th, "InField", d)
    gmsh.model.mesh.field.setNumber(th, "SizeMin", min(h, size_max))
    gmsh.model.mesh.field.setNumber(th, "SizeMax", size_max)
    gmsh.model.mesh.field.setNumber(th, "DistMin", 0.0)
    gmsh.model.mesh.field.setNumber(th, "DistMax", max(size_max - h, 0.0) / grading)
    return th


def surface_field(gmsh, tags: list[int], h: float, size_max: float, grading: float) -> int:
    """Threshold field: ``h`` within ``h`` of the surfaces (sampled 100 x 100 per face,
    so that the sampling gap stays below ``h``), growing by ``grading`` beyond."""
    d = gmsh.model.mesh.field.add("Distance")
    gmsh.model.mesh.field.setNumbers(d, "SurfacesList", tags)
    gmsh.model.mesh.field.setNumber(d, "Sampling", 100)
    th = gmsh.model.mesh.field.add("Threshold")
    gmsh.model.mesh.field.setNumber(th, "InField", d)
    gmsh.model.mesh.field.setNumber(th, "SizeMin", min(h, size_max))
    gmsh.model.mesh.field.setNumber(th, "SizeMax", size_max)
    gmsh.model.mesh.field.setNumber(th, "DistMin", h)
    gmsh.model.mesh.field.setNumber(th, "DistMax", h + max(size_max - h, 0.0) / grading)
    return th


#: target edge in the webs = WEB_SAFETY W / divisions: W/6 targets gave 6.75 elements
#: across (``rules.m53.web_mesh``'s measure) on the small test throw with 3.8 mm fillets
WEB_SAFETY = 0.7


def web_field(gmsh, volumes: list[int], thickness: float, divisions: float, size_max: float) -> int:
    """``Constant`` field: edges of ``WEB_SAFETY thickness / divisions`` inside the web
    ``volumes`` (IACS UR M53 App. III 2.2: at least 6 elements across the web thickness
    W in an SCF model), ``size_max`` outside."""
    h = WEB_SAFETY * thickness / divisions
    c = gmsh.model.mesh.field.add("Constant")
    gmsh.model.mesh.field.setNumbers(c, "VolumesList", volumes)
    gmsh.model.mesh.field.setNumber(c, "VIn", min(h, size_max))
    gmsh.model.mesh.field.setNumber(c, "VOut", size_max)
    return c


def apply_fields(gmsh, fields: list[int], size_max: float) -> None:
    """The minimum of ``fields`` as the background size; ``size_max`` elsewhere;
    12 elements per 2 pi on curved faces."""
    if fields:
        mn = gmsh.model.mesh.field.add("Min")
        gmsh.model.mesh.field.setNumbers(mn, "FieldsList", fields)
        gmsh.model.mesh.field.setAsBackgroundMesh(mn)
    gmsh.option.setNumber("Mesh.MeshSizeMax", size_max)
    gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 12)  # 12 elements per 2 pi on curved faces
