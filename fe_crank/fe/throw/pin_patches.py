"""Where the connecting rods bear on the crankpin: one pressure patch per rod position.

Two rods side by side on one pin (a V engine) load it at two axial places, and UR M53 2.1
superposes each rod's bending-moment triangle at its own place and phase: the web next to
the more loaded rod carries more than the summed force at mid-pin would give.

``rod_positions(engine, throw, pin_length)``: each rod's axial place on the pin, from the
pin's middle (+z to the rear, the throw frame of ``docs/contracts.md``):
* ``Cylinder.pin_position`` where the engine states it (a forked rod's blade and fork,
  whose resultants act at the pin's middle, both 0 mm);
* an articulated rod bears through its master rod's big end: the master's place;
* the other rods share the pin equally in the engine's order, the first at the front:
  n rods at -L/2 + (i + 1/2) L/n (side by side: -+L/4).

``patch_bands(positions, pin_length)``: one axial band per distinct place, of width L/n
(n the number of distinct places), centred on it and kept on the pin; the FE stage loads
each band with its own cosine-pressure unit cases (``loads.pin_pressure_load(band=)``,
cases ``pin_<deg>@<k>``, ``pin_directions.patch_cases``).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from fe_crank.errors import InputError


def rod_positions(engine, throw: str, pin_length: float) -> dict[str, float]:
    """Cylinder name -> axial place of its rod on the pin (m, from the pin's middle)."""
    cyls = [c for c in engine.cylinders if c.throw == throw]
    free = [c for c in cyls if c.pin_position is None and c.articulation is None]
    out: dict[str, float] = {}
    for i, c in enumerate(free):
        out[c.name] = -0.5 * pin_length + (i + 0.5) * pin_length / len(free)
    for c in cyls:
        if c.pin_position is not None:
            if abs(c.pin_position) > 0.5 * pin_length:
                raise InputError(
                    f"cylinder {c.name}: pin_position {c.pin_position * 1e3:g} mm lies off the "
                    f"{pin_length * 1e3:g} mm crankpin",
                    key="cylinders.pin_position",
                )
            out[c.name] = c.pin_position
    for c in cyls:
        if c.name not in out:  # articulated: its master's place (masters of masters followed)
            m, seen = c, set()
            while m.articulation is not None and m.pin_position is None and m.name not in seen:
                seen.add(m.name)
                m = engine.cylinder(m.articulation.master)
            out[c.name] = out.get(m.name, 0.0)
    return out


def patch_bands(positions, pin_length: float) -> tuple[tuple[float, float], ...]:
    """One band (z_lo, z_hi) per distinct place, width L/n, centred and kept on the pin."""
    places = sorted({round(float(e), 9) for e in positions})
    w = pin_length / len(places)
    half = 0.5 * pin_length
    out = []
    for e in places:
        lo = min(max(e - 0.5 * w, -half), half - w)
        out.append((lo, lo + w))
    return tuple(out)


def patch_of(position: float, bands) -> int:
    """Index of the band whose centre is nearest ``position``."""
    centres = np.array([0.5 * (a + b) for a, b in bands])
    return int(np.argmin(np.abs(centres - position)))


def patch_forces(rod_loads, bands) -> dict[int, np.ndarray]:
    """Patch number k (1-based) -> the summed force (n, 2) of the rods bearing there;
    ``rod_loads``: (force (n, 2), place m) per rod."""
    out: dict[int, np.ndarray] = {}
    for force, place in rod_loads:
        k = patch_of(place, bands) + 1
        out[k] = out.get(k, 0.0) + np.asarray(force, float)
    return out


def rod_loads(throw_loads, places: dict[str, float]) -> tuple | None:
    """(force (n, 2), place m) of each rod of a throw's loads (``dynamics.ThrowLoads.rods``)
    at ``places`` (``rod_positions``); None without places (the summed force at mid-pin)."""
    if not places:
        return None
    return tuple((r.pin_force, places[r.cylinder]) for r in throw_loads.rods)


def engine_positions(engine, pin_length: float, throws=None) -> dict[str, dict[str, float]]:
    """``rod_positions`` of every throw (or of ``throws``)."""
    names = [t.name for t in engine.throws] if throws is None else list(throws)
    return {t: rod_positions(engine, t, pin_length) for t in names}


def pin_patch_options(options, engine, pin_length: float | None, throws=None):
    """``options`` (``FeOptions``) with one patch per rod place when some throw of ``throws``
    (None: every throw of ``engine``) carries rods at more than one place of the
    ``pin_length`` crankpin (m, between the webs): the bands and the patch cases
    (``pin_<deg>@<k>``) in place of the whole-pin ones.  Otherwise (or without a pin
    length) ``options`` unchanged."""
    from fe_crank.fe.throw.options import FeOptions
    from fe_crank.fe.throw.pin_directions import patch_cases, pin_direction

    options = options or FeOptions()
    if pin_length is None:
        return options
    places = [e for pos in engine_positions(engine, pin_length, throws).values() for e in pos.values()]
    bands = patch_bands(places, pin_length) if places else ()
    if len(bands) < 2:
        return options
    others = tuple(c for c in options.cases if pin_direction(c) is None)
    step = 360 // max(1, sum(1 for c in options.cases if pin_direction(c) is not None))
    return dataclasses.replace(
        options, pin_patches=bands, cases=others[:1] + patch_cases(len(bands), step) + others[1:]
    )


__all__ = [
    "rod_positions",
    "patch_bands",
    "patch_of",
    "patch_forces",
    "rod_loads",
    "engine_positions",
    "pin_patch_options",
]
