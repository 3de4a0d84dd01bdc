"""Mass properties of a built throw, from the OpenCASCADE solid (exact B-rep integrals).

For each named part and for the whole throw: volume ``V``, mass ``m = rho V``,
centroid ``c``, unbalance about the crank axis ``U = m sqrt(c_x^2 + c_y^2)`` (kg m)
with its vector ``(m c_x, m c_y)``, the inertia tensor about the centroid and the
moment of inertia about the crank axis ``J_z = I_zz,c + m (c_x^2 + c_y^2)``
(parallel-axis theorem).
"""

from __future__ import annotations

import dataclasses
import functools
from dataclasses import dataclass

import numpy as np

from fe_crank.geometry.spec import CrankGeometry, ThrowSpec


@dataclass(frozen=True)
class PartProperties:
    volume: float  # m^3
    mass: float  # kg
    centroid: tuple[float, float, float]  # m, throw frame
    unbalance: float  # kg m about the crank axis
    unbalance_vector: tuple[float, float]  # kg m, (m c_x, m c_y)
    inertia: tuple[tuple[float, float, float], ...]  # kg m^2 about the centroid
    inertia_axis: float  # kg m^2 about the crank axis (z)


@dataclass(frozen=True)
class MassProperties:
    """Mass properties of one throw: the whole solid and each named part."""

    throw: str
    density: float
    total: PartProperties
    parts: dict[str, PartProperties]

    def counterweight_unbalance(self, web: int) -> float:
        """m r of the counterweight on ``web`` (1 or 2), kg m; 0 when there is none."""
        p = self.parts.get(f"counterweight_{web}")
        return 0.0 if p is None else p.unbalance


def combine_volumes(items: list[tuple[float, np.ndarray, np.ndarray]], rho: float) -> PartProperties:
    """Sum volumes (V, centroid, inertia about own centroid per unit density)."""
    V = sum(v for v, _, _ in items)
    c: np.ndarray = sum((v * cc for v, cc, _ in items), np.zeros(3)) / V
    J = np.zeros((3, 3))
    for v, cc, Jc in items:
        d = cc - c
        J += Jc + v * (np.dot(d, d) * np.eye(3) - np.outer(d, d))
    m = rho * V
    J *= rho
    r2 = c[0] ** 2 + c[1] ** 2
    return PartProperties(
        volume=float(V),
        mass=float(m),
        centroid=(float(c[0]), float(c[1]), float(c[2])),
        unbalance=float(m * np.sqrt(r2)),
        unbalance_vector=(float(m * c[0]), float(m * c[1])),
        inertia=tuple((float(row[0]), float(row[1]), float(row[2])) for row in J),
        inertia_axis=float(J[2, 2] + m * r2),
    )


def model_mass_properties(volumes: dict[str, list[int]], density: float, throw: str = "") -> MassProperties:
    """Mass properties of the named volumes of the current gmsh OCC model."""
    import gmsh

    occ = gmsh.model.occ
    per_volume = {}
    for tags in volumes.values():
        for v in tags:
            per_volume[v] = (
                occ.getMass(3, v),
                np.array(occ.getCenterOfMass(3, v)),
                np.array(occ.getMatrixOfInertia(3, v)).reshape(3, 3),
            )
    parts = {name: combine_volumes([per_volume[v] for v in tags], density) for name, tags in volumes.items()}
    total = combine_volumes(list(per_volume.values()), density)
    return MassProperties(throw=throw, density=density, total=total, parts=parts)


def mass_properties(geometry: CrankGeometry, throw: ThrowSpec | str | int | None = None) -> MassProperties:
    """Build the throw in a fresh gmsh session and return its mass properties.

    Uses ``geometry.density``; fillets and the oil bore are included exactly.  The
    properties are a function of the (frozen) geometry and throw alone: a throw asked for
    again in the same process is not built again (``_built``)."""
    spec = throw if isinstance(throw, ThrowSpec) else geometry.throw(throw)
    # the throw's name and angle do not enter its solid (built in its own frame): throws
    # that differ in those alone share one build
    mp = _built(geometry, dataclasses.replace(spec, name="", angle=0.0))
    return dataclasses.replace(mp, throw=spec.name, parts=dict(mp.parts))  # the caller's own dict


@functools.lru_cache(maxsize=64)
def _built(geometry: CrankGeometry, spec: ThrowSpec) -> MassProperties:
    """``mass_properties`` of one throw (its name left empty), built once per process for
    equal inputs."""
    from fe_crank.geometry.throw import add_throw
    from fe_crank.gmsh_io import gmsh_session

    with gmsh_session():
        model = add_throw(geometry, spec)
        return model_mass_properties(model.volumes, geometry.density, spec.name)


@dataclass(frozen=True)
class ThrowSolids:
    """Mass properties of the throws of one geometry, by geometry throw name.  Throws that
    differ only in name and angle are one solid (the properties are in the throw's own
    frame): it is built once and shared."""

    by_throw: dict[str, MassProperties]

    def of(self, throw: str) -> MassProperties:
        return self.by_throw[throw]


def throw_solids(geometry: CrankGeometry, throws: tuple[str, ...] | None = None) -> ThrowSolids:
    """``mass_properties`` of the named geometry throws (all by default), each distinct
    solid built once."""
    built: list[tuple[ThrowSpec, MassProperties]] = []
    out = {}
    for name in throws if throws is not None else tuple(t.name for t in geometry.throws):
        spec = geometry.throw(name)
        solid = dataclasses.replace(spec, name="", angle=0.0)
        props = next((p for s, p in built if s == solid), None)
        if props is None:
            props = mass_properties(geometry, spec)
            built.append((solid, props))
        out[name] = props
    return ThrowSolids(out)
