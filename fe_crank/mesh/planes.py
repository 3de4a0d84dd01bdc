"""The mirror planes of a throw: across which planes through the origin the solid of one
throw (``fe_crank.geometry.throw.add_throw``) is exactly its own mirror image.

Throw frame (``fe_crank.geometry.spec``): ``z`` the crank axis, crankpin centre on ``+y``.

* ``z = 0`` (axis 2), the mid-plane through the crankpin's centre: journals, webs,
  fillets and undercuts are built from one specification for both sides and the oil bore
  lies in ``z = 0``, so the throw is symmetric exactly when its counterweights are: none,
  or one on each web with equal outer/inner radius, angle, thickness, transition fillet radius
  and offset (the mirror image across ``z = 0`` keeps ``x`` and ``y``).  Bolt data are
  not part of the solid (they feed the bolt check only) and are ignored.
* ``x = 0`` (axis 0), the crank plane: the web outline (hull of two circles centred on
  the ``y`` axis), the pin, the journals and the counterweight sectors centred on ``-y``
  are symmetric about it; a counterweight turned from ``-y`` (``offset`` not 0) is not, and
  leaves the plane out (its mirror image is turned the other way); the oil bore, a through-bore in ``z = 0`` along
  ``(sin a, cos a)``, is symmetric only when it runs along ``y`` or along ``x``
  (``a`` a multiple of 90 deg, to within ``ANGLE_TOL``); an oblique bore breaks it.

Anything else (a counterweight on one web only, two different counterweights, two
counterweights on one web) leaves the plane out: a plane is used only when the
specification makes the solid symmetric by construction.
"""

from __future__ import annotations

import math

from fe_crank.geometry.spec import CounterweightSpec, CrankGeometry, ThrowSpec

#: rad: an oil-bore angle this close to a multiple of 90 deg counts as along x or y
#: (a parsed "90 deg" is pi/2 to within 1 ulp; 1e-12 rad moves the bore's far end by < 1e-13 m)
ANGLE_TOL = 1e-12

#: the planes a mesh is mirrored across, of those the solid has: the mid-plane z = 0 only.
#: The crank plane x = 0 runs through the fillets' hot spots (bending in the crank plane
#: peaks there), and a mesh cut along it has poorly shaped elements where the plane meets
#: a fillet: measured on tests/data/geometry_small.toml at fillet elements of r/2, the
#: journal fillet's peak node on x = 0 has element values 73 % apart (UR M53 App. III 2.3.2
#: asks < 5 %) and a principal ratio of 0.13 (< 0.03), where the whole mesh and the mesh
#: mirrored across z = 0 alone give 1.7 % / 0.011.
MESH_PLANES = (2,)


def _same_sector(a: CounterweightSpec, b: CounterweightSpec) -> bool:
    return (a.outer_radius, a.inner_radius, a.angle, a.thickness, a.fillet_radius, a.offset) == (
        b.outer_radius,
        b.inner_radius,
        b.angle,
        b.thickness,
        b.fillet_radius,
        b.offset,
    )


def z_symmetric(spec: ThrowSpec) -> bool:
    """Counterweights on neither web, or one on each web with equal sectors (exact equality)."""
    cws = spec.counterweights
    if not cws:
        return True
    if len(cws) != 2 or sorted(cw.web for cw in cws) != [1, 2]:
        return False
    return _same_sector(cws[0], cws[1])


def bore_axis_aligned(angle: float) -> int | None:
    """0 when the bore direction ``(sin a, cos a)`` is along ``y``, 1 along ``x``, None when oblique."""
    k = angle / (math.pi / 2)
    n = round(k)
    if abs(k - n) * (math.pi / 2) > ANGLE_TOL:
        return None
    return n % 2


def x_symmetric(geometry: CrankGeometry, spec: ThrowSpec | None = None) -> bool:
    """No oil bore, or one along ``x`` or ``y``, and no counterweight of ``spec`` turned
    from ``-y`` (every other part is symmetric by construction)."""
    if spec is not None and any(cw.offset != 0.0 for cw in spec.counterweights):
        return False
    return geometry.oil_bore is None or bore_axis_aligned(geometry.oil_bore.angle) is not None


def symmetry_planes(geometry: CrankGeometry, throw: ThrowSpec | str | int | None = None) -> tuple[int, ...]:
    """Axes normal to the throw's exact mirror planes through the origin, ascending:
    0 for ``x = 0``, 2 for ``z = 0``; ``()`` when there is none."""
    spec = throw if isinstance(throw, ThrowSpec) else geometry.throw(throw)
    out = []
    if x_symmetric(geometry, spec):
        out.append(0)
    if z_symmetric(spec):
        out.append(2)
    return tuple(out)


def mesh_planes(geometry: CrankGeometry, throw: ThrowSpec | str | int | None = None) -> tuple[int, ...]:
    """The mirror planes ``mesh_throw`` meshes across: the throw's exact planes
    (``symmetry_planes``) that are also in ``MESH_PLANES``."""
    return tuple(a for a in symmetry_planes(geometry, throw) if a in MESH_PLANES)
