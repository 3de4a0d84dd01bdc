"""Load vectors: centrifugal body force, crankpin bearing pressure, end-face torque.

All return full interleaved load vectors (3 per P2 node) on a scalar P2 ``Basis``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from skfem import Basis, ElementTetP2, FacetBasis

from fe_crank.errors import InputError, MeshError
from fe_crank.fe.core.assembly import assemble_body_load, assemble_surface_load
from fe_crank.fe.core.supports import boundary_facets, facet_basis

SURFACE_INTORDER = 4


def centrifugal_load(
    basis, density: float, omega: float, *, axis_point=(0.0, 0.0, 0.0), axis=(0.0, 0.0, 1.0)
) -> np.ndarray:
    """Centrifugal body force f = rho omega^2 r_perp (d'Alembert, rotating frame).

    r_perp: the position's component perpendicular to the axis through ``axis_point``.
    Gravity is left out: the weight of a throw (a few kg, tens of N) is below 1e-3 of
    the crankpin loads (tens of kN) and of the centrifugal load at running speed
    (omega^2 r / g ~ 100 at 1000 rpm and r = 0.1 m), and it turns in the throw frame,
    so it would need two more unit cases for no measurable stress.
    """
    if not density > 0:
        raise InputError(f"density must be > 0, got {density!r}", key="material.density")
    if not omega > 0:
        raise InputError(f"a centrifugal load needs a speed > 0, got omega = {omega!r} rad/s", key="operating.speed")
    a = np.asarray(axis, float) / np.linalg.norm(axis)
    p = np.asarray(axis_point, float)

    def f(x):
        d = x - p[:, None, None]
        r = d - a[:, None, None] * np.einsum("i...,i->...", d, a)[None]
        return density * omega**2 * r

    return assemble_body_load(basis, f)


@dataclass(frozen=True)
class PinPressure:
    """What :func:`pin_pressure_load` applied: peak pressure per newton and arc centre."""

    peak_pressure: float  # Pa for the given force
    arc_centre: float  # rad, angle of the arc centre from +y towards +x
    half_angle: float  # rad
    centre: tuple[float, float]  # pin axis (x, y)
    resultant: np.ndarray  # (3,) integral of the traction


@dataclass(frozen=True)
class PinSurface:
    """The crankpin surface's facet quadrature, built once for every pin direction.

    ``fb``: the facet basis (its isoparametric inverse map is the expensive part);
    ``centre`` (2,) the pin axis; ``x`` (3, nf, nq) quadrature points; ``n_r`` (3, nf, nq)
    the unit radial normals (axial part removed; zero on facets normal to the axis); ``angle`` (nf, nq) the angle of each
    point about the pin axis, from +y towards +x.
    """

    fb: FacetBasis
    centre: np.ndarray
    x: np.ndarray
    n_r: np.ndarray
    angle: np.ndarray


def pin_surface(basis, boundary: str = "crankpin", centre=None) -> PinSurface:
    """Build the :class:`PinSurface` of ``boundary`` on the mesh of ``basis`` once; pass it
    to :func:`pin_pressure_load` for each direction (``centre`` None: the area centroid)."""
    mesh = basis.mesh
    facets = boundary_facets(mesh, boundary, "the crankpin load")
    fb = facet_basis(mesh, basis.elem, facets, SURFACE_INTORDER, "the crankpin load")
    x = np.asarray(fb.global_coordinates())
    c = np.asarray(centre, float) if centre is not None else _centroid_xy(fb, x)
    n = np.array(fb.normals)
    n[2] = 0.0
    nr = np.sqrt(n[0] ** 2 + n[1] ** 2)
    # a facet normal to the axis has only round-off radial parts: no radial pressure there
    # (normalising them would press a flat face in random directions)
    n = np.where(nr > 1e-6, n / np.maximum(nr, 1e-300), 0.0)
    ang = np.arctan2(x[0] - c[0], x[1] - c[1])
    return PinSurface(fb=fb, centre=c, x=x, n_r=n, angle=ang)


def _centroid_xy(fb, x) -> np.ndarray:
    return np.einsum("ieq,eq->i", x[:2], fb.dx) / fb.dx.sum()


def pin_centre(mesh, boundary: str = "crankpin") -> np.ndarray:
    """Pin axis (x, y) as the area centroid of the pin surface (a full cylinder)."""
    fb = facet_basis(
        mesh,
        ElementTetP2(),
        boundary_facets(mesh, boundary, "the crankpin load"),
        SURFACE_INTORDER,
        "the crankpin load",
    )
    return _centroid_xy(fb, np.asarray(fb.global_coordinates()))


def pin_pressure_load(
    basis,
    force,
    *,
    boundary: str = "crankpin",
    centre=None,
    half_angle: float = np.deg2rad(60.0),
    surface: PinSurface | None = None,
    band: tuple[float, float] | None = None,
) -> tuple[np.ndarray, PinPressure]:
    """Crankpin bearing load: a cosine pressure over +-half_angle that integrates to ``force``.

    p(psi) = p0 cos(pi psi / (2 psi_0)) for |psi| < psi_0, psi measured about the pin axis
    from the arc centre; the traction is t = -p n_r (n_r: outward normal without its axial
    part), i.e. the shell presses on the side facing away from the force direction.
    p0 and the arc centre are solved so that the integral of t over the discretised
    surface equals ``force`` (Fx, Fy) to round-off (the arc centre moves by the mesh's
    asymmetry only, typically < 1e-3 rad).  The cosine vanishes at the arc ends, which
    avoids the spurious peak of a uniform pressure that stops abruptly.
    ``surface``: a :func:`pin_surface` built once for several directions (then
    ``boundary`` and ``centre`` are those it was built with).  ``band`` (z_lo, z_hi): the
    pressure acts only where z lies in it (one rod's place on the pin, ``fe.throw.pin_patches``);
    its resultant is still ``force``, acting at the band's middle (a band of the whole pin
    length is the whole-pin load).
    """
    F = np.asarray(force, float)
    if F.shape != (2,) or not np.all(np.isfinite(F)) or np.linalg.norm(F) == 0:
        raise InputError(f"pin force must be a non-zero finite (Fx, Fy), got {force!r}")
    if surface is None:
        surface = pin_surface(basis, boundary, centre)
    fb, c, n, ang = surface.fb, surface.centre, surface.n_r, surface.angle
    fdir = np.arctan2(F[0], F[1])
    inside = np.ones(ang.shape, bool) if band is None else (surface.x[2] >= band[0]) & (surface.x[2] <= band[1])

    def shape(centre_angle):
        psi = np.angle(np.exp(1j * (ang - centre_angle)))
        return np.where(inside & (np.abs(psi) < half_angle), np.cos(0.5 * np.pi * psi / half_angle), 0.0)

    def resultant(centre_angle):
        t = -shape(centre_angle)[None] * n
        return np.einsum("ieq,eq->i", t[:2], fb.dx)

    def misfit(a):
        g = resultant(a)
        return np.angle(np.exp(1j * (np.arctan2(g[0], g[1]) - fdir)))

    a0 = fdir + np.pi
    a1 = a0 + 1e-3
    m0, m1 = misfit(a0), misfit(a1)
    for _ in range(20):
        if abs(m1) < 1e-15 or m1 == m0:
            break
        a0, a1, m0 = a1, a1 - m1 * (a1 - a0) / (m1 - m0), m1
        m1 = misfit(a1)
    g = resultant(a1)
    along = g @ (F / np.linalg.norm(F))
    if not along > 0:
        raise MeshError(f"boundary {boundary!r}: cosine pressure does not produce a force (not a pin surface?)")
    p0 = np.linalg.norm(F) / along
    sh = shape(a1)

    def traction(xq, nq):
        return -p0 * sh[None] * n

    f = assemble_surface_load(fb, traction)
    res = f.reshape(-1, 3).sum(axis=0)
    return f, PinPressure(
        peak_pressure=float(p0),
        arc_centre=float(a1),
        half_angle=float(half_angle),
        centre=(float(c[0]), float(c[1])),
        resultant=res,
    )


def angular_acceleration_load(basis, density: float, alpha: float = 1.0) -> np.ndarray:
    """D'Alembert body force of an angular acceleration ``alpha`` (rad/s^2) about the crank
    axis in the positive sense of rotation (about -z, ``fe_crank/model.py``):
    a = alpha_vec x r = alpha (y, -x, 0), f = -rho a = rho alpha (-y, x, 0).  Its moment
    about z is +alpha int rho (x^2 + y^2) dV = +alpha J_z: the throw's own inertia torque,
    against the sense of rotation (torsional vibration, docs/torsion.md)."""
    if not density > 0:
        raise InputError(f"density must be > 0, got {density!r}", key="material.density")

    def f(x):
        return density * alpha * np.stack([-x[1], x[0], np.zeros_like(x[0])])

    return assemble_body_load(basis, f)


#: the counterweight bodies' subdomains of a throw mesh (web 1 front, web 2 rear)
COUNTERWEIGHT_BODIES = ("counterweight_1", "counterweight_2")


def element_basis(basis, elements: np.ndarray) -> Basis:
    """``basis`` restricted to ``elements`` (same DOFs, quadrature and mapping): its
    assembled vectors are the whole basis's terms of those elements."""
    return Basis(
        basis.mesh, basis.elem, mapping=basis.mapping, quadrature=(basis.X, basis.W), dofs=basis.dofs, elements=elements
    )


def counterweight_elements(mesh, name: str | None = None) -> np.ndarray:
    """The elements of the counterweight body ``name`` (a ``COUNTERWEIGHT_BODIES`` name),
    of both with None; empty where the mesh has none."""
    sub = mesh.subdomains or {}
    parts = [np.asarray(sub[n]) for n in COUNTERWEIGHT_BODIES if n in sub and (name is None or n == name)]
    return np.unique(np.concatenate(parts)).astype(np.int64) if parts else np.zeros(0, np.int64)


def centrifugal_part(basis, density: float, *, counterweight: str | None = None, own: bool = False) -> np.ndarray:
    """The centrifugal load at omega = 1 rad/s (``centrifugal_load``) of part of a throw
    mesh: ``own``: every element but the counterweight bodies' (the throw's own);
    otherwise the counterweight body ``counterweight`` alone (zero where the mesh has
    none).  The throw's own part and each body's sum to the whole throw's load (each
    element's terms are the same, only the summation's order differs: round-off)."""
    mesh = basis.mesh
    cw = counterweight_elements(mesh, None if own else counterweight)
    elements = np.setdiff1d(np.arange(mesh.nelements), cw) if own else cw
    if not elements.size:
        return np.zeros(3 * basis.N)
    return centrifugal_load(element_basis(basis, elements), density, 1.0)


def _body_part(name: str) -> Callable[[Any, float], np.ndarray]:
    def make(basis, rho: float) -> np.ndarray:
        return centrifugal_part(basis, rho, counterweight=name)

    return make


#: the parts of ``centrifugal`` (``BODY_CASES``)
CENTRIFUGAL_PARTS = ("centrifugal_throw", *(f"centrifugal_cw_{n[-1]}" for n in COUNTERWEIGHT_BODIES))

#: body-force unit cases: name -> (load vector of (basis, density), description).
#: ``centrifugal`` is the whole throw's; ``centrifugal_throw`` and ``centrifugal_cw_<web>``
#: split it into the throw's own and each counterweight body's (their sum is
#: ``centrifugal`` to round-off), so that a counterweight of fixed shape scaled in mass
#: by k is k times its own case (the counterweight study).
BODY_CASES = {
    "centrifugal": (
        lambda basis, rho: centrifugal_load(basis, rho, 1.0),
        "centrifugal body force rho omega^2 r about z, omega = 1 rad/s",
    ),
    "centrifugal_throw": (
        lambda basis, rho: centrifugal_part(basis, rho, own=True),
        "centrifugal body force rho omega^2 r about z, omega = 1 rad/s, on the throw without its counterweights",
    ),
    **{
        f"centrifugal_cw_{name[-1]}": (
            _body_part(name),
            f"centrifugal body force rho omega^2 r about z, omega = 1 rad/s, on {name} alone",
        )
        for name in COUNTERWEIGHT_BODIES
    },
    "angular_acceleration": (
        lambda basis, rho: angular_acceleration_load(basis, rho, 1.0),
        "inertia body force of 1 rad/s^2 in the sense of rotation, -rho alpha x r",
    ),
}


def face_torque_load(basis, torque: float, *, boundary: str, centre=None) -> np.ndarray:
    """Torque about z on a face as the shear flow of a round shaft, t = T r e_theta / J.

    J = int r^2 dA over the discretised face (Saint-Venant torsion of a circular shaft,
    Timoshenko & Goodier ch. 10), so the nodal forces' moment about the axis is T exactly.
    """
    mesh = basis.mesh
    facets = boundary_facets(mesh, boundary, "the torque load")
    fb = facet_basis(mesh, basis.elem, facets, SURFACE_INTORDER, f"the torque on {boundary}")
    x = np.asarray(fb.global_coordinates())
    c = np.zeros(2) if centre is None else np.asarray(centre, float)
    dx, dy = x[0] - c[0], x[1] - c[1]
    J = np.sum((dx**2 + dy**2) * fb.dx)

    def traction(xq, nq):
        # e_theta * r = (-dy, dx); positive T turns about +z
        return (torque / J) * np.stack([-dy, dx, np.zeros_like(dx)])

    return assemble_surface_load(fb, traction)
