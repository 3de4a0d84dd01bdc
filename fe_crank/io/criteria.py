"""The load case's ``[criteria]`` section -> frozen ``Criteria``.

Each limit is a key ``min_<quantity>`` or ``max_<quantity>``; the quantity must be one
of ``QUANTITIES`` (a misspelt or unknown quantity is an error naming the key)::

    [criteria]
    min_static_safety = 1.5
    min_fatigue_safety = 1.3            # von Mises equivalent + Goodman
    min_gough_pollard_safety = 1.3      # bending/torsion ellipse quadrant + Goodman
    min_m53_acceptability = 1.15        # IACS UR M53 Q
    max_counterweight_stress = "150 MPa"
    max_unbalance_error = 0.05          # |built m r vector - required m r vector| / required
    m53_additional_bending = "20 MPa"   # option: UR M53 sigma_add, not below section 4's value
                                        # (10 MPa trunk piston, 30 MPa crosshead: the engine's construction)
    m53_quasi_static_torque = true      # option: accept the quasi-static journal torque (below)

A criterion that needs a material property the load case's material does not give
(e.g. the M53 factor K of a cast iron) is an error naming the criterion and the
property.

UR M53 2.2 takes the nominal torsional stress from a forced-vibration calculation of the
shaft system, of every engine (a single-cylinder engine's train, with its flywheel,
gearing and driven machine, has torsional modes like any other).  ``min_m53_acceptability``
needs the load case's ``[torsion]`` section, unless ``m53_quasi_static_torque = true``
says that the quasi-static journal torque is accepted instead (the M53 verdict line then
says "not UR M53-conform (quasi-static torque)"); ``check_m53_torque``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from fe_crank.errors import InputError
from fe_crank.io.base import read_toml
from fe_crank.io.units import to_si
from fe_crank.results import SENSES, Sense


@dataclass(frozen=True)
class Quantity:
    """A quantity a criterion may limit: its sense, unit kind (None: pure number), the
    material properties it needs and what it means."""

    sense: Sense
    unit_kind: str | None
    needs: tuple[str, ...]
    meaning: str


QUANTITIES: dict[str, Quantity] = {
    "static_safety": Quantity("min", None, ("yield_strength",), "yield strength / max von Mises over the cycle"),
    "overspeed_safety": Quantity(
        "min",
        None,
        ("yield_strength",),
        "yield strength / max von Mises over the cycle at overspeed (inertia and body force at omega_os^2)",
    ),
    "fatigue_safety": Quantity(
        "min",
        None,
        ("fatigue_limit_bending", "tensile_strength"),
        "equivalent (von Mises) amplitude and signed mean, modified Goodman",
    ),
    "gough_pollard_safety": Quantity(
        "min",
        None,
        ("fatigue_limit_bending", "fatigue_limit_torsion", "tensile_strength"),
        "Gough-Pollard ellipse quadrant of bending and torsion amplitudes, Goodman-corrected limits",
    ),
    "m53_acceptability": Quantity(
        "min", None, ("tensile_strength", "m53_k"), "IACS UR M53 acceptability factor Q = sigma_DW / sigma_V"
    ),
    "counterweight_stress": Quantity(
        "max", "pressure", (), "max von Mises in a counterweight and its junction over the cycle"
    ),
    "counterweight_overspeed_stress": Quantity("max", "pressure", (), "max von Mises in a counterweight at overspeed"),
    "unbalance_error": Quantity(
        "max", None, (), "|built m r vector - required m r vector| / required m r per counterweight plane"
    ),
    "bolt_utilisation": Quantity("max", None, (), "counterweight bolt load m r omega^2 at overspeed / bolt capacity"),
    # VDI 2230 Part 1 (2015) of the bolted counterweight (fe_crank/assess/cw_joint.py)
    "main_bearing_load": Quantity(
        "max", "force", (), "peak main-bearing load over the cycle, whole-shaft model, counterweights as built"
    ),
    "main_bearing_specific_load": Quantity(
        "max",
        "pressure",
        (),
        "peak main-bearing load / (journal diameter x bearing width), whole-shaft model, counterweights as built",
    ),
    "oil_film_thickness": Quantity(
        "min",
        "length",
        (),
        "minimum oil film thickness over the cycle, hydrodynamic main bearings (finite bearing), counterweights as built",
    ),
    "oil_film_pressure": Quantity(
        "max",
        "pressure",
        (),
        "peak oil film pressure over the cycle, hydrodynamic main bearings (finite bearing), counterweights as built",
    ),
    "bolt_assembly_utilisation": Quantity(
        "max", None, (), "VDI 2230 R7: equivalent assembly stress / R_p0.2 at the largest preload (<= 0.9)"
    ),
    "bolt_working_safety": Quantity(
        "min", None, (), "VDI 2230 R8: R_p0.2 / equivalent bolt stress at the overspeed (>= 1.0)"
    ),
    "bolt_fatigue_safety": Quantity(
        "min",
        None,
        (),
        "VDI 2230 R9: thread endurance limit / bolt stress amplitude with the eccentric loading's bending, starts "
        "and stops included (>= 1.2)",
    ),
    "bolt_separation_safety": Quantity(
        "min",
        None,
        (),
        "VDI 2230 R2/R5: smallest clamp load after embedding / (clamp load the loads take off + opening limit "
        "F_Kab), over the cycle and at the overspeed (>= 1: no opening)",
    ),
    "bolt_slip_safety": Quantity(
        "min",
        None,
        (),
        "VDI 2230 R12: residual clamp load x friction / transverse load per bolt (>= 1.2, 1.8 alternating)",
    ),
}

#: option key -> unit kind ("bool": true or false)
OPTIONS: dict[str, str] = {"m53_additional_bending": "pressure", "m53_quasi_static_torque": "bool"}


@dataclass(frozen=True)
class Limit:
    quantity: str
    sense: Sense
    value: float  # SI or pure number
    key: str  # the key in the file, for messages


@dataclass(frozen=True)
class Criteria:
    limits: tuple[Limit, ...]
    m53_additional_bending: float | None = None  # Pa; None: UR M53 4 by the engine's construction
    m53_quasi_static_torque: bool = False  # UR M53 route accepted with the quasi-static journal torque

    def limit(self, quantity: str) -> Limit | None:
        return next((lim for lim in self.limits if lim.quantity == quantity), None)

    def needed_properties(self) -> dict[str, tuple[str, ...]]:
        """Criterion key -> material properties it needs."""
        return {lim.key: QUANTITIES[lim.quantity].needs for lim in self.limits}


def _number(value: object, file, key: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise InputError(f"must be a pure number (got a {type(value).__name__})", file=str(file), key=key)
    v = float(value)
    if not math.isfinite(v):
        raise InputError("must be a finite number (inf and nan are not accepted)", file=str(file), key=key)
    if not v >= 0:
        raise InputError(f"must not be negative (got {v:g})", file=str(file), key=key)
    return v


def build_criteria(value: object, file: str | Path, key: str = "criteria") -> Criteria:
    """Validate a ``[criteria]`` table (without the cross-check against the material)."""
    if not isinstance(value, dict):
        raise InputError("must be a table of min_<quantity>/max_<quantity> keys", file=str(file), key=key)
    limits = []
    options: dict[str, Any] = {}
    for k, v in value.items():
        full = f"{key}.{k}"
        if OPTIONS.get(k) == "bool":
            if not isinstance(v, bool):
                raise InputError("must be true or false", file=str(file), key=full)
            options[k] = v
            continue
        if k in OPTIONS:
            try:
                options[k] = to_si(v, OPTIONS[k])
            except ValueError as exc:
                raise InputError(str(exc), file=str(file), key=full) from None
            continue
        word, _, quantity = k.partition("_")
        sense = SENSES.get(word)
        if sense is None or not quantity:
            raise InputError(
                f"not a criterion: write min_<quantity> or max_<quantity> (quantities: {sorted(QUANTITIES)}) "
                f"or an option ({sorted(OPTIONS)})",
                file=str(file),
                key=full,
            )
        q = QUANTITIES.get(quantity)
        if q is None:
            raise InputError(
                f"unknown quantity {quantity!r}; known quantities are {sorted(QUANTITIES)}", file=str(file), key=full
            )
        if q.sense != sense:
            raise InputError(
                f"{quantity} takes a {q.sense}imum, not a {word}imum: write {q.sense}_{quantity}",
                file=str(file),
                key=full,
            )
        if q.unit_kind is None:
            val = _number(v, file, full)
        else:
            try:
                val = to_si(v, q.unit_kind)
            except ValueError as exc:
                raise InputError(str(exc), file=str(file), key=full) from None
            if not val > 0:
                raise InputError(f"must be positive (got {v!r})", file=str(file), key=full)
        limits.append(Limit(quantity, sense, val, full))
    return Criteria(tuple(limits), **options)


def check_material(criteria: Criteria, material, file: str | Path) -> None:
    """Every criterion's material properties must be given.  Raises InputError."""
    for ckey, needs in criteria.needed_properties().items():
        if not needs:
            continue
        if material is None:
            raise InputError(f"needs a [material] section (properties {list(needs)})", file=str(file), key=ckey)
        missing = material.missing(needs)
        if missing:
            raise InputError(
                f"needs material property {', '.join(missing)}, which material {material.name!r} does not give; "
                f"set material.{missing[0]} in the load case or drop the criterion",
                file=str(file),
                key=ckey,
            )


def check_m53_torque(criteria: Criteria, engine, has_torsion: bool, file: str | Path, key: str = "criteria") -> None:
    """UR M53 needs its torque (module docstring).  Raises InputError naming the key."""
    m53 = criteria.limit("m53_acceptability")
    if criteria.m53_quasi_static_torque and has_torsion:
        raise InputError(
            "the load case has a [torsion] section, whose vibratory torque UR M53 takes; "
            "m53_quasi_static_torque applies only without one",
            file=str(file),
            key=f"{key}.m53_quasi_static_torque",
        )
    if m53 is None or has_torsion or criteria.m53_quasi_static_torque:
        return
    n = len(engine.cylinders)
    raise InputError(
        f"UR M53 2.2 takes the torsional stress of every engine (this one has {n} cylinder{'' if n == 1 else 's'}) "
        "from a forced-vibration calculation: give the [torsion] section (docs/torsion.md), or set "
        f"{key}.m53_quasi_static_torque = true to accept the quasi-static journal torque (the M53 verdict is "
        "then not UR M53-conform (quasi-static torque))",
        file=str(file),
        key=m53.key,
    )


def parse_criteria(value: object, file: str | Path, key: str = "criteria") -> Criteria:
    """Section parser of the load case's ``[criteria]`` section (``fe_crank.io.sections``): builds the criteria and
    checks them against the same file's ``[material]`` section."""
    crit = build_criteria(value, file, key)
    if any(crit.needed_properties().values()):
        from fe_crank.io.material import parse_material

        data = read_toml(file) if Path(file).is_file() else {}
        mat = parse_material(data["material"], file, "material") if "material" in data else None
        check_material(crit, mat, file)
    return crit


__all__ = [
    "Criteria",
    "Limit",
    "Quantity",
    "QUANTITIES",
    "OPTIONS",
    "build_criteria",
    "check_m53_torque",
    "check_material",
    "parse_criteria",
]
