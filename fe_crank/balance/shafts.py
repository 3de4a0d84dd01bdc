"""Balance shafts for one free component (Lanchester-type balancers).

Rules (after "Concluding remarks on the use of balance shafts for balancing IC engines",
a Russian engine-design text): shafts for first-order forces or couples turn at
``+-omega``, for second order at ``+-2 omega``.  A force needs two shafts turning in opposite senses,
parallel to the crank axis and symmetric about it, their counterweights in the plane of
the force (for a straight-line force both unbalances are equal).  A first-order couple
needs one shaft carrying a pair of opposed unbalances, the other pair sitting on the
crankshaft; a second-order couple needs two shafts, anywhere in the crankcase.

The component of order ``k`` is split (``fe_crank.balance.hodograph``) into a vector
``P`` turning in the positive engine sense and ``Q`` turning in the negative sense.
A rotating unbalance ``U`` at ``psi0`` turning at ``k omega`` gives ``U (k omega)^2
u(psi0 +- k theta)``; it cancels ``P`` (or ``Q``) with ``U = |P| / (k omega)^2``
and ``psi0 = arg(-P)``.  For a couple, a pair ``+U`` at ``z1``, ``-U`` at ``z2``
(``L = z1 - z2``) gives the moment ``L (-Fy, Fx)``, i.e. ``w_M = -i L w_F`` with
``w = y + i x`` components, so the pair that cancels ``P_M`` has
``U e^{i psi0} = -i P_M / (L (k omega)^2)``.

Free placement: ``positions`` puts each shaft's axis anywhere in the cross-section
(that text allows the second-order pair at different heights).  The force of a shaft is
a free vector, so any placement cancels the force; what placement adds is the moment
about the crank axis of forces acting on offset lines, ``M_z = sum (x_i F_y,i - y_i F_x,i)``.
For a straight-line force along ``y`` the two shafts' ``x`` components cancel as forces
but act at heights ``h_1, h_2``: a roll moment of amplitude ``U (k omega)^2 |h_1 - h_2|``
(one shaft's force times the height offset), reported as ``roll_moment`` and carried
in the residual's ``M_z``.  A placement is refused when it cannot cancel the component:
a position count that differs from the number of shafts the component needs, a
balance shaft on the crank axis (only the crankshaft's own counterweights sit there),
or a crankshaft counterweight pair placed off the crank axis.
"""

from __future__ import annotations

import cmath
import math
from dataclasses import dataclass

from fe_crank.balance.forces import FreeForces, OrderTerm, point_term, rotating_force
from fe_crank.balance.hodograph import rotating_parts
from fe_crank.errors import InputError

COMPONENTS = ("force", "couple")


@dataclass(frozen=True)
class BalanceShaft:
    """One balance shaft (or the crankshaft's share of a first-order couple).

    ``speed_ratio`` is signed relative to the reference crankshaft: ``+1`` turns with it
    at its speed, ``-2`` against it at twice its speed.  ``angle`` is the direction of the
    (first) unbalance at ``theta = 0`` (engine convention).  ``z`` lists the planes of the
    unbalances (two opposed ones for a couple), ``position`` the (x, y) of its axis.
    """

    name: str
    speed_ratio: int
    unbalance: float  # kg m, per unbalance
    angle: float
    z: tuple[float, ...]
    position: tuple[float, float]
    on_crankshaft: bool
    constraint: str


@dataclass(frozen=True)
class BalanceShaftDesign:
    component: str
    order: int
    shafts: tuple[BalanceShaft, ...]
    residual: FreeForces
    roll_moment: float = 0.0  # N m: amplitude of M_z (about the crank axis) of these shafts' forces


def _terms_for(shaft: BalanceShaft, sense: int, order: int, speed: float, ref_z: float) -> list[OrderTerm]:
    mag = shaft.unbalance * (order * speed) ** 2
    out = []
    for j, z in enumerate(shaft.z):
        psi = shaft.angle + (math.pi if j == 1 else 0.0)
        force = rotating_force(mag, psi, sense)
        out.append(point_term("balance_shafts", order, force, (shaft.position[0], shaft.position[1], z - ref_z)))
    return out


def balance_shafts(
    forces: FreeForces,
    component: str,
    order: int,
    *,
    reference_sense: int = 1,
    offset: float = 0.1,
    span: float = 0.2,
    sources=None,
    positions=None,
) -> BalanceShaftDesign:
    """Design balance shafts that cancel one component of ``forces``.

    Parameters
    ----------
    forces : FreeForces
        Usually the residual after counterweights.
    component : {"force", "couple"}
    order : {1, 2}
    reference_sense : int
        Sense of the reference crankshaft (+1/-1), to express speeds relative to it.
    offset : float
        Distance (m) of each shaft axis from the crank axis (force shafts sit at
        ``+-offset`` across the force line; couple shafts at ``+-offset`` too).
    span : float
        Axial distance (m) between the two opposed unbalances of a couple shaft,
        centred on the reference point.
    sources : iterable of str, optional
        Sources included in the target (default: all present).
    positions : sequence of (x, y), optional
        Axis of each shaft (m, engine frame), in the order of the design's shafts
        (the one turning with the crank first); default the symmetric placement above.
    """
    if component not in COMPONENTS:
        raise InputError(f"{component!r} is not one of {COMPONENTS}", key="balance.shafts.component")
    if order not in (1, 2):
        raise InputError(f"balance shafts are for orders 1 and 2 (got {order})", key="balance.shafts.order")
    if not (offset >= 0.0 and span > 0.0):
        raise InputError("offset must be >= 0 and span > 0", key="balance.shafts")
    w = forces.speed
    term = forces.total(order, sources)
    zr = forces.reference_z
    if component == "force":
        (a, b), (c, d) = term.force
    else:
        (a, b), (c, d) = term.moment[:2]
    p, q = rotating_parts(a, b, c, d)
    scale = max(abs(p) + abs(q), 1e-300)
    designs: list[tuple[BalanceShaft, int]] = []
    z: tuple[float, ...]  # axial positions of a shaft's unbalances: one (force) or a pair (couple)
    if abs(p) + abs(q) == 0.0:
        return BalanceShaftDesign(component, order, (), forces)
    # direction of the major axis (engine convention): where the two vectors line up
    psi_major = 0.5 * (cmath.phase(p) + cmath.phase(q)) if abs(p) and abs(q) else cmath.phase(p or q)
    across = (math.sin(psi_major + math.pi / 2), math.cos(psi_major + math.pi / 2))
    for part, sense, side in ((p, 1, 1.0), (q, -1, -1.0)):
        if abs(part) <= 1e-12 * scale:
            continue
        rel = sense * reference_sense * order  # signed speed relative to the crankshaft
        pos = (side * offset * across[0], side * offset * across[1])
        if component == "force":
            u = -part / (order * w) ** 2  # w = y + i x encoding, cancels the part
            z = (zr,)
            constraint = (
                "axes parallel to the crank axis and symmetric about it, in the plane across the "
                "force line; unbalance in the plane of the force resultant"
            )
        else:
            # pair +U at zr + span/2, -U at zr - span/2: w_M = -i span w_F  ->  w_F = i w_M / span
            u = 1j * (-part) / span / (order * w) ** 2
            z = (zr + span / 2.0, zr - span / 2.0)
            constraint = "axis parallel to the crank axis, anywhere in the crankcase; two opposed unbalances"
        on_crank = component == "couple" and order == 1 and rel == 1
        if on_crank:
            pos = (0.0, 0.0)
            constraint = "counterweight pair on the crankshaft (one balance shaft plus a crank pair)"
        name = f"{component}{order}_{'crank' if on_crank else ('plus' if rel > 0 else 'minus')}"
        designs.append((BalanceShaft(name, rel, abs(u), cmath.phase(u), z, pos, on_crank, constraint), sense))
    if positions is not None:
        designs = _place(designs, positions, component, order)
    terms = []
    for sh, sense in designs:
        terms += _terms_for(sh, sense, order, w, zr)
    mz = sum((t.moment[2] for t in terms), start=[0.0, 0.0])
    return BalanceShaftDesign(
        component, order, tuple(s for s, _ in designs), forces.with_terms(terms), float(math.hypot(mz[0], mz[1]))
    )


def _place(designs, positions, component: str, order: int):
    """Put the designed shafts at the user's ``positions`` (module docstring: refusals)."""
    import dataclasses

    key = "balance.shafts.positions"
    positions = [tuple(float(v) for v in p) for p in positions]
    if len(positions) != len(designs):
        raise InputError(
            f"the order-{order} {component} needs {len(designs)} shaft(s) "
            f"({', '.join(s.name for s, _ in designs)}); give one position each",
            key=key,
        )
    out = []
    for (sh, sense), (x, y) in zip(designs, positions):
        if not (math.isfinite(x) and math.isfinite(y)):
            raise InputError("positions must be finite", key=key)
        on_axis = math.hypot(x, y) < 1e-9
        if sh.on_crankshaft and not on_axis:
            raise InputError(
                f"{sh.name} is a counterweight pair on the crankshaft: its position is the crank axis (0, 0)", key=key
            )
        if not sh.on_crankshaft and on_axis:
            raise InputError(f"balance shaft {sh.name} cannot sit on the crank axis", key=key)
        out.append((dataclasses.replace(sh, position=(x, y), constraint=sh.constraint + "; placed as given"), sense))
    return out
