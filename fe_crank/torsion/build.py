"""Build the lumped-mass chain of a load case (``[torsion]`` + engine + geometry + material).

Masses, from the free end: [damper ring], [pulley hub], one per throw (in axial order),
flywheel, driven machines.  A throw's inertia about the crank axis is

* the CAD value of the meshed throw (webs, pin, half journals either side, counterweights:
  ``fe_crank.geometry.mass_properties(...).total.inertia_axis``, exact B-rep integrals), plus
* for each cylinder on it, the rod's rotating share ``m_rod (l - c)/l R^2`` and the
  mean inertia of the reciprocating mass ``m_j mean((ds/dphi)^2)`` over a revolution
  (exact slider-crank; ``R^2 (1/2 + lambda^2/8)`` to second order, Ker Wilson vol. 1,
  Den Hartog sec. 5.2), ``m_j = m_piston + m_rod c / l`` (two-mass split).

Segment between two throws: one pitch (throw centre to throw centre), stiffness from
Carter's equivalent length with the journal length of the pitch
``L_j = pitch - L_p - 2 h`` (``throw_stiffness = "carter"``), or from the FE throw model
with the plain journal the FE span leaves out in series
(``1/k = 1/k_FE + (pitch - span) 32 / (G pi D_j^4)``, ``throw_stiffness = "fe"``).
``G = E / (2 (1 + nu))`` of the load case's material.  Relative damping: the shaft loss
factor on every crank segment (pulley-throw 1 .. last throw-flywheel); each throw has
``cylinder_damping`` to ground.
"""

from __future__ import annotations

import numpy as np

from fe_crank.errors import InputError
from fe_crank.geometry.mass import ThrowSolids, throw_solids
from fe_crank.io.material import Material
from fe_crank.io.torsion import TorsionSettings
from fe_crank.mechanism.kinematics import piston_motion
from fe_crank.torsion.lumped import lumped_model
from fe_crank.torsion.model import TorsionCase, TorsionModel
from fe_crank.torsion.stiffness import carter_throw_stiffness, shaft_stiffness, throw_span


def crank_throws(engine):
    """The throws of a single-shaft engine in axial order (refuses geared multi-shaft engines)."""
    if len(engine.shafts) != 1 or engine.shafts[0].speed_ratio != 1.0:
        raise InputError(
            "torsional analysis is for one crankshaft turning at the reference speed; "
            f"the engine has {len(engine.shafts)} shaft(s)",
            key="torsion",
        )
    return sorted(engine.throws, key=lambda t: t.axial_position)


def reciprocating_inertia(cylinder, crank_radius: float, samples: int = 3600) -> float:
    """Rotating + mean reciprocating inertia (kg m^2) of one cylinder's rod and piston."""
    rod = cylinder.rod
    c = rod.cg_from_big_end
    m_rot = rod.mass * (rod.length - c) / rod.length
    m_j = cylinder.piston_mass + rod.mass * c / rod.length
    phi = 2 * np.pi * np.arange(samples) / samples
    v = piston_motion(phi, crank_radius, rod.length, 1.0, offset=cylinder.pin_offset).v  # ds/dphi at omega = 1
    return float(m_rot * crank_radius**2 + m_j * np.mean(v**2))


def shear_modulus(material: Material | None) -> float:
    if material is None:
        raise InputError("torsional analysis needs the material's Young's modulus and Poisson ratio", key="material")
    return material.youngs_modulus / (2.0 * (1.0 + material.poisson_ratio))


def throw_inertias(loadcase: TorsionCase, solids: ThrowSolids | None = None) -> dict[str, float]:
    """CAD inertia of every throw's geometry (kg m^2) + its cylinders' (module docstring).
    ``solids``: the geometry's mass properties when the caller has them (else built here,
    each distinct throw solid once)."""
    g = loadcase.geometry
    if g is None:
        raise InputError("torsional analysis needs the crank geometry (key 'geometry')", key="geometry")
    engine = loadcase.engine
    names = {t.name for t in g.throws}
    throws = crank_throws(engine)
    geometry_throw = {t.name: g.throw(t.name if t.name in names else None).name for t in throws}
    if solids is None:
        solids = throw_solids(g, tuple(sorted(set(geometry_throw.values()))))
    # J_z does not depend on the throw's angle
    return with_cylinders(engine, {t.name: solids.of(geometry_throw[t.name]).total.inertia_axis for t in throws})


def with_cylinders(engine, geometry_inertia: dict[str, float]) -> dict[str, float]:
    """Each throw's inertia in the chain (kg m^2): its geometry's about the crank axis
    (``geometry_inertia``: engine throw -> the meshed throw's CAD J_z) plus its cylinders'
    rotating and mean reciprocating inertia (module docstring)."""
    out = {}
    for t in crank_throws(engine):
        j = geometry_inertia[t.name]
        for c in engine.cylinders:
            if c.throw == t.name:
                j += reciprocating_inertia(c, t.crank_radius)
        out[t.name] = j
    return out


def pitch_stiffness(
    geometry, shear: float, pitch: float, *, method: str = "carter", fe_stiffness: float | None = None
) -> float:
    """Stiffness (N m/rad) of one pitch between adjacent throw centres."""
    lj = pitch - geometry.crankpin_length - 2 * geometry.web_thickness
    if lj <= 0:
        raise InputError(f"throw pitch {pitch * 1e3:.4g} mm leaves no journal between the webs", key="engine.throws")
    if method == "carter":
        return carter_throw_stiffness(geometry, shear, journal_length=lj)
    if fe_stiffness is None:
        raise InputError("throw_stiffness = 'fe' needs the FE throw model", key="torsion.throw_stiffness")
    extra = pitch - throw_span(geometry)
    if extra < -1e-9:
        raise InputError(
            f"throw pitch {pitch * 1e3:.4g} mm is shorter than the FE throw {throw_span(geometry) * 1e3:.4g} mm",
            key="torsion.throw_stiffness",
        )
    flex = 1.0 / fe_stiffness + (max(extra, 0.0) / shaft_stiffness(shear, geometry.journal_diameter, 1.0))
    return 1.0 / flex


def build_model(
    loadcase: TorsionCase,
    settings: TorsionSettings,
    *,
    inertias: dict[str, float] | None = None,
    fe_stiffness: float | None = None,
) -> TorsionModel:
    """The chain of a load case (module docstring; ``model = "lumped"``: the stated
    stations, ``fe_crank.torsion.lumped``).  ``inertias`` overrides the throw inertias
    (tests, or a caller that has them); ``fe_stiffness`` the FE throw stiffness."""
    engine = loadcase.engine
    throws = crank_throws(engine)
    if settings.model == "lumped":
        return lumped_model(engine, settings, file=loadcase.source_file)
    inertias = throw_inertias(loadcase) if inertias is None else inertias
    g = loadcase.geometry
    G = shear_modulus(loadcase.material)
    eta = settings.shaft_loss_factor
    names, J, k, lf, cseg, cabs, seg_names = [], [], [], [], [], [], []

    def add(name, inertia, absolute=0.0):
        names.append(name)
        J.append(inertia)
        cabs.append(absolute)

    def join(name, stiffness, loss, damping=0.0):
        seg_names.append(name)
        k.append(stiffness)
        lf.append(loss)
        cseg.append(damping)

    if settings.damper is not None:
        d = settings.damper
        add("damper", d.inertia)
        join("damper-pulley", d.stiffness, d.loss_factor or 0.0, d.damping)
    if settings.pulley is not None:
        add("pulley", settings.pulley.inertia)
        join(f"pulley-{throws[0].name}", settings.pulley.stiffness, eta)
    throw_mass = {}
    for i, t in enumerate(throws):
        throw_mass[t.name] = len(names)
        add(t.name, inertias[t.name], settings.cylinder_damping)
        if i + 1 < len(throws):
            pitch = throws[i + 1].axial_position - t.axial_position
            join(
                f"{t.name}-{throws[i + 1].name}",
                pitch_stiffness(g, G, pitch, method=settings.throw_stiffness, fe_stiffness=fe_stiffness),
                eta,
            )
    flywheel = settings.flywheel
    if flywheel is None:
        raise ValueError("the torsional model needs its flywheel")
    join(f"{throws[-1].name}-flywheel", flywheel.stiffness, eta)
    add("flywheel", flywheel.inertia)
    prev = "flywheel"
    for m in settings.driven:
        join(f"{prev}-{m.name}", m.stiffness, m.loss_factor if m.loss_factor is not None else eta, m.damping)
        add(m.name, m.inertia, m.absolute_damping)
        prev = m.name
    return TorsionModel(
        tuple(names),
        np.array(J),
        np.array(k),
        np.array(lf),
        np.array(cseg),
        np.array(cabs),
        tuple(seg_names),
        throw_mass,
    )
