"""Stress-tensor helpers on stacked 6-component arrays.

Component order along axis -2 (or 0 for a single state): ``COMPONENTS =
(xx, yy, zz, xy, yz, xz)``.  Arrays may carry leading axes (time) and a trailing node
axis: shape ``(..., 6, n)``.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from fe_crank.fe.core.stress import principal as _principal
from fe_crank.fe.core.stress import von_mises as _von_mises

COMPONENTS = ("xx", "yy", "zz", "xy", "yz", "xz")


def von_mises(s: np.ndarray) -> np.ndarray:
    """von Mises stress of ``s`` in this module's layout ``(..., 6, n)``.

    The formula (von Mises 1913; e.g. Shigley eq. 5-13) is implemented once, in
    ``fe_crank.fe.core.stress.von_mises`` (components on axis 0); this moves the component
    axis there.
    """
    return _von_mises(np.moveaxis(s, -2, 0))


def von_mises_path(history: np.ndarray, centre: np.ndarray | None = None) -> np.ndarray:
    """vM(S(t) - c) of a stress path ``history`` (n_t, 6, n) about ``centre`` (6, n)
    (None: about zero), shape (n_t, n).

    The formula of ``von_mises``, sqrt(((d_xx-d_yy)^2 + (d_yy-d_zz)^2 + (d_zz-d_xx)^2)/2
    + 3 (d_xy^2 + d_yz^2 + d_zx^2)), evaluated term by term in the same order: the same
    floating-point result as ``von_mises(history - centre)`` (``von_mises_planes``, on the
    component planes of ``history``; fastest when each component's (n_t, n) plane is
    contiguous, i.e. ``history`` is a transposed view of a (6, n_t, n) array).
    """
    return von_mises_planes(history.transpose(1, 0, 2), centre)


def von_mises_planes(
    planes: np.ndarray, centre: np.ndarray | None = None, buf: np.ndarray | None = None, out: np.ndarray | None = None
) -> np.ndarray:
    """vM(S(t) - c) of a stress path given as component planes ``planes`` (6, n_t, n),
    about ``centre`` (6, n) (None: about zero); shape (n_t, n).

    Whole-block operations only (the six differences in one subtraction, the three
    shear squares in one multiplication), each term in the order of ``von_mises``:
    ((d_xx-d_yy)^2 + (d_yy-d_zz)^2) + (d_zz-d_xx)^2, times 1/2, plus 3 ((d_xy^2 +
    d_yz^2) + d_zx^2), square root -- so the same floating-point result.  ``buf``: a
    (6, n_t, n) scratch array to reuse, ``out``: the (n_t, n) result array.
    """
    if centre is not None:
        d = np.subtract(planes, centre[:, None, :], out=buf)
        tmp = d[1]  # d_yy is not needed after d_yy - d_zz
        shear = d[3:]
    else:  # about zero: the planes themselves
        d = planes
        tmp = np.empty(planes.shape[1:])
        shear = np.empty((3,) + planes.shape[1:]) if buf is None else buf[3:]
    acc = np.subtract(d[0], d[1], out=out)
    np.subtract(d[1], d[2], out=tmp)
    np.multiply(acc, acc, out=acc)
    np.multiply(tmp, tmp, out=tmp)
    acc += tmp
    np.subtract(d[2], d[0], out=tmp)
    np.multiply(tmp, tmp, out=tmp)
    acc += tmp
    acc *= 0.5
    np.multiply(d[3:], d[3:], out=shear)
    sq = shear[0]
    sq += shear[1]
    sq += shear[2]
    sq *= 3.0
    acc += sq
    vm: np.ndarray = np.sqrt(acc, out=acc)
    return vm


def to_matrix(s: np.ndarray) -> np.ndarray:
    """(..., 6, n) -> (..., n, 3, 3) symmetric tensors."""
    xx, yy, zz, xy, yz, xz = (s[..., i, :] for i in range(6))
    m = np.stack([np.stack([xx, xy, xz], -1), np.stack([xy, yy, yz], -1), np.stack([xz, yz, zz], -1)], -2)
    return m


def principal(s: np.ndarray) -> np.ndarray:
    """Principal stresses in this module's layout, shape (..., 3, n), descending
    sigma_1 >= sigma_2 >= sigma_3: implemented once, in ``fe_crank.fe.core.stress.principal``
    (components on axis 0); this moves the component axis there and back."""
    return np.moveaxis(_principal(np.moveaxis(s, -2, 0)), 0, -2)


def cylindrical(
    s: np.ndarray,
    points: np.ndarray,
    axis_point: tuple[float, float],
    which: tuple[str, ...] = ("rr", "tt", "zz", "rt", "tz", "rz"),
) -> dict[str, np.ndarray]:
    """Components in the cylindrical frame (r, theta, z) of an axis parallel to z.

    ``points`` (3, n) are the node coordinates; ``axis_point`` (x, y) a point of the
    axis.  Returns ``rr, tt, zz, rt, tz, rz`` (those named in ``which``) each of shape
    (..., n).  Rotation sigma' = Q sigma Q^T with e_r = (cos a, sin a, 0),
    e_t = (-sin a, cos a, 0).
    """
    dx = points[0] - axis_point[0]
    dy = points[1] - axis_point[1]
    rad = np.hypot(dx, dy)
    c = np.where(rad > 0, dx / np.where(rad > 0, rad, 1.0), 1.0)
    sn = np.where(rad > 0, dy / np.where(rad > 0, rad, 1.0), 0.0)
    xx, yy, zz, xy, yz, xz = (s[..., i, :] for i in range(6))
    formulas: dict[str, Callable[[], np.ndarray]] = {
        "rr": lambda: c * c * xx + sn * sn * yy + 2 * c * sn * xy,
        "tt": lambda: sn * sn * xx + c * c * yy - 2 * c * sn * xy,
        "zz": lambda: zz,
        "rt": lambda: (yy - xx) * c * sn + xy * (c * c - sn * sn),
        "tz": lambda: -sn * xz + c * yz,
        "rz": lambda: c * xz + sn * yz,
    }
    return {k: formulas[k]() for k in ("rr", "tt", "zz", "rt", "tz", "rz") if k in which}
