"""The loads on a bolted counterweight's joint, per bolt, for its VDI 2230 check
(``assess.cw_joint``): the counterweight's own inertia over the working cycle and at the
overspeed, the web's deformation under the pin force, and the joint's eccentricity.

Loads (per bolt, ``joint_loads``).  By the counterweight's equilibrium as a free body, the
force and moment its joint carries are those of its own inertia: the centrifugal force
F_c = m r_c omega^2 and the tangential inertia F_t = m r_c alpha at its centre of mass (m its
mass, r_c the radius of its centre of mass, alpha the shaft's angular acceleration), with
their levers to the joint plane.  Over the working cycle the speed varies by the
coefficient delta (omega (1 -+ delta/2)) and alpha = (T - T_mean)/J with the dynamics stage's
torque and flywheel inertia; each start and stop cycles the loads between 0 and their
working values; at the overspeed omega_os the centrifugal force (an event, not a cycle).

The web's deformation under the pin force (the joint face opening and closing each cycle).
The joint lies beyond the journal, outside the load path pin - web - journal - bearing: the
pin force reaches it only through the web's deformation, which adds no resultant (above) but
strains the interface.  A radial joint takes it from the FE unit solutions
(``fe_section_loads``): the normal stress across the joint plane in the fused model (as stiff
as the solid, so stiffer than the bolted joint: it gives the joint more of the web's
deformation than the joint takes) from the pin and journal-torque unit cases over the
cycle, each bolt's prism taking its moment and normal force.  Where that section cannot be
fitted, and for axial joints, the lever model (``web_moments``): the web's bending moment at
its mid-plane M_w = R (L_j + t/2), R the main bearing's reaction to the pin force on the web's
side (the statically determinate throw on its two main bearings, the journal's end face the
bearing centre as in the FE supports and UR M53; each rod at its place on the pin), taken
whole onto the joint as M_B = M_w / n: as if the joint lay in the web's load path, an upper
bound.

The joint's geometry (``JointGeometry``, from the geometry file) and its eccentricity
(VDI 2230 5.1.2, ``vdi2230.Eccentric``, one plane per bolt):
* ``direction = "radial"``: the bolts parallel to the counterweight's symmetry line, screwed
  through it into the web's end face opposite the pin (a counterweight turned by its
  ``offset``: its frame turned with it, the joint plane normal to its symmetry line); the
  joint plane at the web's end radius r_J (``seat_radius``).  The bolts lie on the pitch circle r_b at angles spread
  evenly over the counterweight's angle, x_i = r_b sin(phi_i) across the joint.  F_A = F_c/n
  axial; the tangential inertia pries with the lever r_c - r_J (the prying lever), carried
  by the bolt row as axial forces +-F_t (r_c - r_J) x_i / sum x_j^2 (one bolt: as a moment);
  F_Q = F_t/n.  The eccentricity plane is the web's thickness (the plane the radial pin
  force bends the web in): interface c_T = min(t, b) (web and counterweight thickness, flush
  on the web's outer face), b_T = D_A, the bolt at its middle (s_sym = 0), the centrifugal
  force at the counterweight's mid-thickness, a = (b - c_T)/2.
* ``direction = "axial"``: the bolts parallel to the crank axis on the pitch circle r_b, the
  counterweight against the web's face.  F_A = 0, F_Q = sqrt(F_c^2 + F_t^2)/n, and the
  centrifugal force at the counterweight's mid-thickness b/2 above the face pries the joint
  open at its inner edge: M_B = F_c b/(2 n) + |M_w|/n in the radial plane through the bolt,
  interface c_T = r_1 - r_2 (the counterweight's radial extent), b_T = D_A, s_sym = r_T - r_b
  (r_T = (r_1 + r_2)/2, xi positive towards the axis).
Without a ``JointGeometry`` (a joint built by hand) the joint is centric and carries no
moment: VDI 2230's centric case.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from fe_crank.assess.counterweight import BoltedCounterweight, JointGeometry
from fe_crank.assess.superpose import UnitStresses
from fe_crank.fe.core.loads import CENTRIFUGAL_PARTS
from fe_crank.geometry.spec import BoltedJoint
from fe_crank.mechanism.results import DynamicsResult
from fe_crank.rules import vdi2230 as v
from fe_crank.rules.m53.calculation import RodLoads


def stated(value: float | None, name: str, key: str) -> float:
    """A joint datum the VDI 2230 check cannot do without (``BoltedJoint.vdi_missing``):
    ``value``, or a ValueError naming the joint ``name`` and the missing ``key``."""
    if value is None:
        raise ValueError(f"{name}: the VDI 2230 bolt check needs {key}")
    return value


@dataclass(frozen=True)
class JointLoads:
    """Per bolt, N and N m: the axial load's range over the working cycle, its overspeed
    value, the largest transverse load (working cycle and overspeed); the working moment
    M_B's range over the cycle and its largest magnitude at the overspeed (positive opening
    the interface's edge at +c_T/2); the joint's eccentricity (None: centric); the web's
    largest bending moment over the cycle (the whole joint's, for the report)."""

    axial_max: float
    axial_min: float
    axial_overspeed: float
    transverse_max: float
    moment_max: float = 0.0
    moment_min: float = 0.0
    moment_overspeed: float = 0.0
    eccentric: v.Eccentric | None = None
    web_moment: float = 0.0
    web_model: str = ""  # how the web's deformation was taken onto the joint ("" none)


def counterweight_loads(
    mass: float,
    radius: float,
    count: int,
    direction: str,
    *,
    omega: float,
    overspeed: float | None,
    speed_fluctuation: float = 0.0,
    angular_acceleration: float = 0.0,
) -> JointLoads:
    """Per-bolt loads of a counterweight as a centric joint (no joint geometry: no prying,
    no web moment).  ``angular_acceleration``: the largest |alpha| over the working cycle,
    rad/s^2; ``speed_fluctuation``: delta."""
    mr = mass * radius
    f_hi = mr * (omega * (1.0 + 0.5 * speed_fluctuation)) ** 2
    f_lo = mr * (omega * (1.0 - 0.5 * speed_fluctuation)) ** 2
    f_os = mr * (overspeed if overspeed is not None else omega) ** 2
    f_t = mr * abs(angular_acceleration)
    if direction == "radial":
        return JointLoads(f_hi / count, f_lo / count, max(f_os, f_hi) / count, f_t / count)
    if direction == "axial":
        return JointLoads(0.0, 0.0, 0.0, math.hypot(max(f_os, f_hi), f_t) / count)
    raise ValueError(f"bolt direction must be 'radial' or 'axial', not {direction!r}")


@dataclass(frozen=True)
class WebMoments:
    """The web's bending moment at its mid-plane from the pin force (``web_moments``), N m:
    about x (the radial pin force's, bending the web through its thickness) over the working
    cycle, and the largest |M| (both components) over the cycle and at the overspeed."""

    about_x: np.ndarray
    largest: float
    overspeed: float


@dataclass(frozen=True)
class SectionLoads:
    """Per bolt, from the FE unit solutions (``fe_section_loads``): the joint plane's share of
    the web's deformation under the pin force and the journal torque over the working cycle
    (the moment M_B (n,), N m, positive opening the interface's edge towards the crank
    throw's middle; the normal force (n,), N, positive pulling the joint apart, the worst
    bolt's), their largest magnitudes at the overspeed, and the nodes the section was fitted on."""

    moment: np.ndarray
    force: np.ndarray  # (n, bolts)
    moment_overspeed: float
    force_overspeed: float
    nodes: int


#: the unit cases whose stresses are the web's deformation under the pin force and torque
#: (not the throw's own inertia: the counterweight's is the joint's resultant, ``joint_loads``)
def _pin_cases(cases: tuple[str, ...]) -> np.ndarray:
    return np.array([c not in ("centrifugal", *CENTRIFUGAL_PARTS, "angular_acceleration") for c in cases])


def fe_section_loads(
    unit: UnitStresses,
    group: str,
    geo: JointGeometry,
    joint: BoltedJoint,
    coeffs: np.ndarray,
    coeffs_os: np.ndarray | None = None,
) -> SectionLoads | None:
    """The normal stress sigma_yy across the radial joint's plane y = -r_J in the FE model
    (in the counterweight's own frame, turned by its offset: its mid-line on -y)
    (the counterweight fused to the web: the joint bonded, as stiff as the solid), from the
    pin and torque unit cases over the cycle: fitted over the counterweight's nodes in a thin
    slab about the plane, sigma = c_0 + c_1 zeta + c_2 x + c_3 (y + r_J) (least squares; zeta
    across the interface from its middle, positive towards the throw's middle), each bolt's
    prism (D_A across, c_T through the thickness) carrying M_B = c_1 D_A c_T^3/12 and
    F = (c_0 + c_2 x_i) D_A c_T.  None where the slab holds too few nodes to fit (the lever
    model then, ``web_moments``).  ``unit``: ``superpose.UnitStresses``; ``coeffs`` (n,
    n_cases) of the working cycle, ``coeffs_os`` of the overspeed cycles."""
    idx = unit.groups.get(group)
    if idx is None or not len(idx):
        return None
    pts = np.asarray(unit.points)[:, idx]
    stress = np.asarray(unit.stress)[:, :, idx]
    if geo.offset != 0.0:  # a turned counterweight: its own frame (mid-line on -y), points and stresses
        c, s = math.cos(geo.offset), math.sin(geo.offset)
        pts = np.stack([c * pts[0] + s * pts[1], -s * pts[0] + c * pts[1], pts[2]])
        # sigma_y'y' = e_y'^T sigma e_y', e_y' = (-sin, cos): Voigt (xx, yy, zz, xy, yz, zx)
        stress = stress.copy()
        stress[:, 1] = s * s * stress[:, 0] + c * c * stress[:, 1] - 2.0 * s * c * stress[:, 3]
    c_t = min(geo.web_thickness, geo.thickness)
    lever_j = geo.bearing_lever - 0.5 * geo.web_thickness  # L_j
    z_out = 0.5 * geo.bearing_span - lever_j  # the web's outer face, |z|
    side = -1.0 if geo.web == 1 else 1.0
    z_t = side * (z_out - 0.5 * c_t)
    zeta = -side * (pts[2] - z_t)  # positive towards the throw's middle
    eta = pts[1] + geo.seat_radius
    for half in (1.0e-3, 2.0e-3, 3.0e-3, 4.0e-3, 6.0e-3):
        sel = (np.abs(eta) <= half) & (np.abs(zeta) <= 0.5 * c_t + 1e-9)
        zs = zeta[sel]
        if sel.sum() >= 12 and zs.size and zs.max() - zs.min() >= 0.6 * c_t:
            break
    else:
        return None
    a = np.column_stack([np.ones(int(sel.sum())), zeta[sel], pts[0][sel], eta[sel]])
    fit = np.linalg.pinv(a)  # (4, m)
    mask = _pin_cases(tuple(unit.cases))
    syy = stress[:, 1, :][:, sel]  # (n_cases, m)
    per_case = syy @ fit.T  # (n_cases, 4)
    per_case[~mask] = 0.0
    d_a = stated(joint.clamped_diameter, group, "clamped_diameter")
    area, inertia = d_a * c_t, d_a * c_t**3 / 12.0
    x = bolt_offsets(joint, geo)

    def loads(c: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
        cyc = np.asarray(c, float) @ per_case  # (n, 4)
        force = (cyc[:, :1] + cyc[:, 2:3] * x[None, :]) * area
        return cyc[:, 1] * inertia, force

    m, f = loads(coeffs)
    m_os = f_os = 0.0
    if coeffs_os is not None and len(coeffs_os):
        mo, fo = loads(coeffs_os)
        m_os, f_os = float(np.max(np.abs(mo))), float(np.max(fo))
    return SectionLoads(m, f, m_os, f_os, int(sel.sum()))


def bearing_reaction(pin_force: ArrayLike, rod_loads: RodLoads | None, geo: JointGeometry) -> np.ndarray:
    """(n, 2) reaction of the main bearing on the side of the web ``geo.web`` to the pin
    force (statically determinate throw, bearings at the journals' end faces): each rod's
    force at its place e on the pin (``rod_loads``: (force (n, 2), e)), else the summed
    ``pin_force`` at mid-pin: R_1 = F (L/2 - e)/L, R_2 = F (L/2 + e)/L."""
    span = geo.bearing_span
    loads = rod_loads if rod_loads else ((pin_force, 0.0),)
    sign = -1.0 if geo.web == 1 else 1.0
    reaction: np.ndarray = np.sum([np.asarray(f, float) * (0.5 * span + sign * e) / span for f, e in loads], axis=0)
    return reaction


def web_moments(
    geo: JointGeometry,
    pin_force: ArrayLike,
    rod_loads: RodLoads | None = None,
    overspeed_loads: Sequence[tuple[Any, ...]] = (),
) -> WebMoments:
    """The web's bending moment at its mid-plane, M_w = R (L_j + t/2) (module docstring), over
    the working cycle and the overspeed cycles (``overspeed_loads``: (pin force, torque[,
    rod loads]) each)."""
    m = bearing_reaction(pin_force, rod_loads, geo) * geo.bearing_lever
    largest_os = 0.0
    for c in overspeed_loads or ():
        rods = c[2] if len(c) > 2 else None
        m_os = bearing_reaction(c[0], rods, geo) * geo.bearing_lever
        largest_os = max(largest_os, float(np.max(np.hypot(m_os[:, 0], m_os[:, 1]))))
    # the radial force (y) bends the web about x; the tangential one (x) about y
    return WebMoments(m[:, 1].copy(), float(np.max(np.hypot(m[:, 0], m[:, 1]))), largest_os)


def bolt_offsets(joint: BoltedJoint, geo: JointGeometry) -> np.ndarray:
    """x_i (m) of the bolts across the joint: on the pitch circle at angles spread evenly
    over the counterweight's angle, phi_i = -A/2 + (i + 1/2) A/n."""
    n = joint.count
    phi = -0.5 * geo.angle + (np.arange(n) + 0.5) * geo.angle / n
    x: np.ndarray = joint.pitch_radius * np.sin(phi)
    return x


LEVER_MODEL = "lever: the web's moment R (L_j + t/2) whole onto the joint (upper bound)"


def joint_loads(
    b: BoltedCounterweight,
    *,
    omega: float,
    overspeed: float | None,
    speed_fluctuation: float = 0.0,
    angular_acceleration: float = 0.0,
    web: WebMoments | None = None,
    section: SectionLoads | None = None,
) -> JointLoads:
    """Per-bolt loads of the bolted counterweight ``b`` (``BoltedCounterweight``) with its
    eccentricity (module docstring); without a joint geometry the centric
    ``counterweight_loads``.  The web's deformation: ``section`` (the FE model's, radial
    joints, ``fe_section_loads``), else ``web`` (the lever model, ``web_moments``), else none."""
    joint, geo = b.joint, b.geometry
    base = counterweight_loads(
        b.mass,
        b.radius,
        joint.count,
        joint.direction,
        omega=omega,
        overspeed=overspeed,
        speed_fluctuation=speed_fluctuation,
        angular_acceleration=angular_acceleration,
    )
    if geo is None:
        return base
    n = joint.count
    d_a = stated(joint.clamped_diameter, b.name, "clamped_diameter")
    mr = b.mass * b.radius
    f_t = mr * abs(angular_acceleration)  # the tangential inertia, whole counterweight
    if joint.direction == "radial":
        c_t = min(geo.web_thickness, geo.thickness)
        ecc = v.Eccentric(width=c_t, length=d_a, s_sym=0.0, a=0.5 * (geo.thickness - c_t))
        x = bolt_offsets(joint, geo)
        lever = max(b.radius - geo.seat_radius, 0.0)  # prying lever of the tangential inertia
        pry_force = pry_moment = 0.0
        if n > 1 and float(np.sum(x**2)) > 0:
            pry_force = f_t * lever * float(np.max(np.abs(x))) / float(np.sum(x**2))
        else:
            pry_moment = f_t * lever  # one bolt: the prying as a moment (its plane taken as the joint's)
        f_hi = f_lo = f_os = 0.0
        model = ""
        if section is not None:
            m_hi, m_lo, m_os = float(np.max(section.moment)), float(np.min(section.moment)), section.moment_overspeed
            f_hi, f_lo, f_os = float(np.max(section.force)), float(np.min(section.force)), section.force_overspeed
            model = f"FE: sigma_yy across the joint plane, the pin and torque cases ({section.nodes} nodes)"
        elif web is not None:
            m_hi, m_lo, m_os = float(np.max(web.about_x)) / n, float(np.min(web.about_x)) / n, web.overspeed / n
            model = LEVER_MODEL
        else:
            m_hi = m_lo = m_os = 0.0
        web_moment = max(abs(m_hi), abs(m_lo))
        m_hi, m_lo = m_hi + pry_moment, m_lo - pry_moment
        return JointLoads(
            axial_max=base.axial_max + pry_force + max(f_hi, 0.0),
            axial_min=base.axial_min - pry_force + min(f_lo, 0.0),
            axial_overspeed=base.axial_overspeed + max(f_os, 0.0),
            transverse_max=base.transverse_max,
            moment_max=m_hi,
            moment_min=m_lo,
            moment_overspeed=max(m_os, abs(m_hi), abs(m_lo)) if overspeed is None else m_os,
            eccentric=ecc,
            web_moment=web_moment,
            web_model=model,
        )
    # axial bolts: xi positive towards the crank axis, the centrifugal force prying the inner edge open
    r_t = 0.5 * (geo.outer_radius + geo.inner_radius)
    ecc = v.Eccentric(
        width=geo.outer_radius - geo.inner_radius,
        length=d_a,
        s_sym=r_t - joint.pitch_radius,
        a=0.0,
    )
    h = 0.5 * geo.thickness
    w_all = web.largest / n if web is not None else 0.0
    w_os = web.overspeed / n if web is not None else 0.0
    f_c_hi = mr * (omega * (1.0 + 0.5 * speed_fluctuation)) ** 2
    f_c_lo = mr * (omega * (1.0 - 0.5 * speed_fluctuation)) ** 2
    f_c_os = mr * (overspeed if overspeed is not None else omega) ** 2
    return JointLoads(
        axial_max=0.0,
        axial_min=0.0,
        axial_overspeed=0.0,
        transverse_max=base.transverse_max,
        moment_max=f_c_hi * h / n + w_all,
        moment_min=f_c_lo * h / n - w_all,
        moment_overspeed=max(f_c_os, f_c_hi) * h / n + max(w_os, w_all),
        eccentric=ecc,
        web_moment=w_all,
        web_model=LEVER_MODEL if web is not None else "",
    )


def cycle_speed_data(dynamics: DynamicsResult, flywheel_inertia: float | None = None) -> tuple[float, float]:
    """(delta, max |alpha|) of a cycle from the dynamics stage, the largest angular
    acceleration alpha = (T - T_mean) / J (torque reduced to the reference shaft).

    Without ``flywheel_inertia``: the operating cycle, J its flywheel inertia sized for the
    coefficient of speed fluctuation delta.  With it (the operating cycle's J: the one
    flywheel), a cycle at another speed of the full-load curve or a misfire case: that
    cycle's delta = dE / (J omega^2) with dE its excess energy (the same flywheel at another
    speed and torque)."""
    if flywheel_inertia is None:
        j, delta = float(dynamics.flywheel_inertia), float(dynamics.speed_fluctuation)
    else:
        j = float(flywheel_inertia)
        delta = float(dynamics.excess_energy) / (j * float(dynamics.speed) ** 2) if j > 0 else 0.0
    if not j > 0:
        return delta, 0.0
    return delta, float(max(abs(dynamics.torque - dynamics.mean_torque))) / j


__all__ = [
    "stated",
    "JointLoads",
    "counterweight_loads",
    "WebMoments",
    "SectionLoads",
    "fe_section_loads",
    "LEVER_MODEL",
    "bearing_reaction",
    "web_moments",
    "bolt_offsets",
    "joint_loads",
    "cycle_speed_data",
]
