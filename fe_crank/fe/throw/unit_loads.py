"""The load vectors of the FE stage's unit cases, by case name (``solve_unit_cases``).

* the body-force cases of ``loads.BODY_CASES``: ``centrifugal`` (rho omega^2 r about z at
  omega = 1 rad/s), or split into ``centrifugal_throw`` (the throw without its
  counterweights) and ``centrifugal_cw_1``, ``centrifugal_cw_2`` (each web's counterweight
  body alone), and ``angular_acceleration`` (-rho alpha x r at 1 rad/s^2);
* ``torque``: 1 N m in the positive sense of rotation (M_z = -1 N m) on the torque face;
* pin cases by direction (``pin_directions``): 1 N on the crankpin as a cosine pressure;
  with rod places on the pin (``FeOptions.pin_patches``, ``fe.throw.pin_patches``) the patch
  cases ``<pin case>@<k>`` put that pressure on band k only.
"""

from __future__ import annotations

import numpy as np

from fe_crank.errors import InputError
from fe_crank.fe.core.loads import BODY_CASES, face_torque_load, pin_pressure_load, pin_surface
from fe_crank.fe.throw.pin_directions import patch_case, pin_direction, unit_force


def check_case_names(options) -> None:
    """Refuse a case name that is none of the above (or a patch beyond the bands given)."""
    n = len(options.pin_patches)
    unknown = [
        c
        for c in options.cases
        if c not in (*BODY_CASES, "torque") and pin_direction(c) is None and (patch_case(c) or (n + 1, 0))[0] > n
    ]
    split = [c for c in options.cases if c in BODY_CASES and c.startswith("centrifugal_")]
    if split and "centrifugal" in options.cases:
        raise InputError(
            f"centrifugal is the sum of {', '.join(split)}: give the whole throw's case or its parts, not both",
            key="fe.cases",
        )
    if unknown:
        raise InputError(
            f"unknown unit cases {sorted(unknown)}; pick from centrifugal (or centrifugal_throw, centrifugal_cw_1, "
            "centrifugal_cw_2), angular_acceleration, torque and pin cases "
            f"by direction (pin_x, pin_y, pin_-x, pin_-y, pin_<deg> as pin_030; pin_030@k on rod "
            f"place k of {n})",
            key="fe.cases",
        )


def unit_loads(basis, material, options) -> tuple[dict, dict, dict]:
    """(load vector, description, ``PinPressure``) by case name, in ``options.cases``' order."""
    loads, desc, pins, surface = {}, {}, {}, None
    for name in options.cases:
        if name in BODY_CASES:
            make, desc[name] = BODY_CASES[name]
            loads[name] = make(basis, material.density)
        elif name == "torque":
            # +1 N m in the positive sense of rotation (from +y towards +x), i.e. M_z = -1 N m
            loads[name] = face_torque_load(basis, -1.0, boundary=options.torque_face)
            desc[name] = (
                f"1 N m in the sense of rotation (M_z = -1 N m) on {options.torque_face}, "
                f"reacted at {options.reaction_face}"
            )
        else:
            if surface is None:  # the pin surface's facet basis, built once for all directions
                surface = pin_surface(basis, options.pin_boundary, options.pin_centre)
            patch = patch_case(name)
            band = options.pin_patches[patch[0] - 1] if patch is not None else None
            loads[name], pins[name] = pin_pressure_load(
                basis,
                unit_force(name),
                boundary=options.pin_boundary,
                half_angle=options.pin_half_angle,
                surface=surface,
                band=band,
            )
            where = "" if band is None else f" over z = {band[0] * 1e3:.2f}..{band[1] * 1e3:.2f} mm"
            deg = pin_direction(name) if patch is None else patch[1]
            desc[name] = (
                f"1 N on {options.pin_boundary}{where} at {deg} deg from +x, cosine pressure +-"
                f"{np.rad2deg(options.pin_half_angle):.0f} deg"
            )
    return loads, desc, pins


__all__ = ["check_case_names", "unit_loads"]
