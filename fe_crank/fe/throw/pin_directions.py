"""Crankpin unit cases by direction, and the weights that build any pin force from them.

The crankpin load is a cosine pressure over +-60 deg centred on the force direction
(``loads.pin_pressure_load``): not linear in the force vector.  A force is therefore
built from the unit cases of the two neighbouring directions that bracket it,
F = a e_k + b e_(k+1) with a, b >= 0 (sine rule), which is exact for the resultant and,
with directions 30 deg apart, close to one arc centred on F.  With the four axis
directions only (the first design) the two arcs are 90 deg apart and the von Mises
stress at the crankpin fillets of the shipped single-cylinder throw differed from one arc
on the resultant by up to 10 %; with 12 directions the difference is given in
docs/performance.md (``benchmarks/perf/run.py``, stage ``cycle``).  The superposed cycle is exact for this
load model (piecewise linear in F), and a direct solve of the same model agrees with it
to round-off.

Names: ``pin_x``, ``pin_y``, ``pin_-x``, ``pin_-y`` are the directions 0, 90, 180 and
270 deg (x tangential, y radial outward in the throw frame, angles from +x towards +y);
any other direction is ``pin_<deg>`` with three digits (``pin_030``).  With several rod
places on the pin (``fe.throw.pin_patches``) each place's band has its own cases, ``<name>@<k>``.
"""

from __future__ import annotations

import re

import numpy as np

AXIS_NAMES = {"pin_x": 0, "pin_y": 90, "pin_-x": 180, "pin_-y": 270}
_BY_ANGLE = {v: k for k, v in AXIS_NAMES.items()}
#: default spacing of the pin unit cases, deg
STEP_DEG = 30


def pin_direction(name: str) -> int | None:
    """Direction in whole degrees [0, 360) of a pin unit case name, or None if not one."""
    if name in AXIS_NAMES:
        return AXIS_NAMES[name]
    m = re.fullmatch(r"pin_(\d{3})", name)
    if m and int(m.group(1)) < 360:
        return int(m.group(1))
    return None


def pin_name(deg: int) -> str:
    deg = int(deg) % 360
    return _BY_ANGLE.get(deg, f"pin_{deg:03d}")


def pin_cases(step: int = STEP_DEG) -> tuple[str, ...]:
    if step <= 0 or 360 % step:
        raise ValueError(f"pin direction step must divide 360 deg, got {step}")
    return tuple(pin_name(d) for d in range(0, 360, step))


def patch_case(name: str) -> tuple[int, int] | None:
    """(patch number k >= 1, direction in degrees) of a patch unit case ``<pin case>@<k>``
    (``pin_030@2``: 1 N at 30 deg on the second rod place's band, ``fe.throw.pin_patches``), else None."""
    base, sep, k = name.partition("@")
    d = pin_direction(base)
    if not sep or d is None or not k.isdigit() or int(k) < 1:
        return None
    return int(k), d


def patch_cases(n_patches: int, step: int = STEP_DEG) -> tuple[str, ...]:
    """The pin cases of every patch: ``pin_x@1``, ``pin_030@1``, ..., ``pin_330@<n>``."""
    return tuple(f"{c}@{k}" for k in range(1, n_patches + 1) for c in pin_cases(step))


def unit_force(name: str) -> tuple[float, float]:
    """The unit force (Fx, Fy) of a pin case (exact on the axes)."""
    d = pin_direction(name)
    patch = patch_case(name) if d is None else None
    if patch is not None:
        d = patch[1]
    if d is None:
        raise ValueError(f"{name!r} is not a pin unit case")
    exact = {0: (1.0, 0.0), 90: (0.0, 1.0), 180: (-1.0, 0.0), 270: (0.0, -1.0)}
    if d in exact:
        return exact[d]
    a = np.deg2rad(d)
    return float(np.cos(a)), float(np.sin(a))


def pin_case_weights(force: np.ndarray, names) -> np.ndarray:
    """Weights (n, len(names)) of the pin unit cases ``names`` for forces (n, 2), N.

    One direction: forces along its line only (signed).  Three or more directions: each force goes to the two directions that bracket it
    (non-negative weights; every gap between neighbouring directions must be below
    180 deg).  Two directions: the signed decomposition F = a e_1 + b e_2 (the two arcs
    then also carry negative, i.e. pulling, pressure; kept for models solved with two
    cases only).
    """
    F = np.atleast_2d(np.asarray(force, float))
    names = list(names)
    n = F.shape[0]
    W = np.zeros((n, len(names)))
    if not names:
        if np.any(F):
            raise ValueError("a pin force but no pin unit case")
        return W
    deg = np.array([pin_direction(s) for s in names], dtype=object)
    if any(d is None for d in deg):
        raise ValueError(f"not pin unit cases: {[s for s, d in zip(names, deg) if d is None]}")
    deg = deg.astype(float)
    if len(set(deg)) != len(deg):
        raise ValueError(f"pin unit cases with the same direction: {names}")
    if len(names) == 1:  # only forces along that line (signed): e.g. a model solved for pin_y alone
        e = np.array([np.cos(np.deg2rad(deg[0])), np.sin(np.deg2rad(deg[0]))])
        along = F @ e
        across = F[:, 0] * e[1] - F[:, 1] * e[0]
        if np.any(np.abs(across) > 1e-9 * np.maximum(np.abs(along), 1e-300)):
            raise ValueError(f"one pin direction ({names[0]}) carries only forces along it")
        W[:, 0] = along
        return W
    if len(names) == 2:
        E = np.array([[np.cos(np.deg2rad(d)), np.sin(np.deg2rad(d))] for d in deg]).T  # columns e_1, e_2
        if abs(np.linalg.det(E)) < 1e-9:
            raise ValueError(f"pin unit cases {names} are parallel: they cannot carry an arbitrary force")
        return np.linalg.solve(E, F.T).T
    order = np.argsort(deg)
    sd = deg[order]
    gaps = np.diff(np.append(sd, sd[0] + 360.0))
    if gaps.max() >= 180.0:
        raise ValueError(f"pin unit cases {names} leave a gap of {gaps.max():g} deg: every gap must be < 180 deg")
    mag = np.hypot(F[:, 0], F[:, 1])
    psi = np.mod(np.rad2deg(np.arctan2(F[:, 1], F[:, 0])), 360.0)
    k = np.searchsorted(sd, psi, side="right") - 1  # -1: below the first direction
    lo = np.where(k < 0, sd[-1] - 360.0, sd[np.maximum(k, 0)])
    kn = np.where(k < 0, 0, (k + 1) % len(sd))
    hi = sd[kn] + np.where((k >= 0) & (kn == 0), 360.0, 0.0)
    dl = np.deg2rad(hi - lo)
    a = mag * np.sin(np.deg2rad(hi - psi)) / np.sin(dl)
    b = mag * np.sin(np.deg2rad(psi - lo)) / np.sin(dl)
    ilo = order[np.where(k < 0, len(sd) - 1, k)]
    ihi = order[kn]
    rows = np.arange(n)
    np.add.at(W, (rows, ilo), a)
    np.add.at(W, (rows, ihi), b)
    return W
