"""Slider-crank kinematics: exact (with piston-pin offset) and as a harmonic series.

Conventions (``fe_crank/model.py``):

* ``phi`` is the crank angle measured from the cylinder axis (the crank pointing at
  the cylinder head) in the direction of rotation.  Without pin offset this is TDC.
  With a pin offset ``e`` the true dead centres lie a little off the axis; ``phi``
  is still measured from the axis and ``s`` from the true TDC, so ``s >= 0``.
* ``s`` is the piston displacement from TDC towards the crank axis; ``v = ds/dt``
  and ``a = d2s/dt2`` at constant ``omega`` (so ``a`` is positive at TDC).
* ``beta`` is the rod angle from the cylinder axis, positive when the big end lies
  on the side the crankpin moves to just after TDC (``sin beta = (r sin phi - e)/l``).
* Vectors of the rod's centre of mass are given in the cylinder frame with columns
  ``(axial, lateral)``: axial from the crank axis towards the cylinder head, lateral
  towards the side the crankpin moves to just after TDC.  Positive pin offset ``e``
  (désaxé) lies on that lateral side too, as in ``model.Cylinder.pin_offset``.

Exact relations (any kinematics text, e.g. Kolchin & Demidov, *Design of automotive
engines*, ch. 2; Heywood, *Internal Combustion Engine Fundamentals*, sec. 2.2)::

    l sin(beta) = r sin(phi) - e
    x = r cos(phi) + l cos(beta)                 (piston pin from crank axis, axial)
    s = sqrt((l + r)^2 - e^2) - x
    beta' = r omega cos(phi) / (l cos(beta))
    beta'' = (l sin(beta) beta'^2 - r omega^2 sin(phi)) / (l cos(beta))
    v = r omega sin(phi) + l sin(beta) beta'
    a = r omega^2 cos(phi) + l cos(beta) beta'^2 + l sin(beta) beta''
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fe_crank.errors import GeometryError, InputError

__all__ = [
    "PistonMotion",
    "piston_motion",
    "harmonic_coefficients",
    "piston_motion_harmonic",
    "fourier_coefficients",
    "sample_angles",
]


@dataclass(frozen=True)
class PistonMotion:
    """Motion of one slider-crank over an array of crank angles (SI units).

    Attributes
    ----------
    phi : crank angle, rad
    s, v, a : piston displacement from TDC towards the crank axis (m), velocity (m/s),
        acceleration (m/s^2), positive towards the crank axis
    beta, beta_dot, beta_ddot : rod angle (rad) and its rates (rad/s, rad/s^2)
    rod_cg_velocity, rod_cg_acceleration : (n, 2) arrays, (axial, lateral) in the
        cylinder frame, of the rod's centre of mass (m/s, m/s^2); zero when no
        centre-of-mass distance was given
    crankpin_velocity, crankpin_acceleration : (n, 2) arrays, same frame, of the
        crankpin centre
    """

    phi: np.ndarray
    s: np.ndarray
    v: np.ndarray
    a: np.ndarray
    beta: np.ndarray
    beta_dot: np.ndarray
    beta_ddot: np.ndarray
    rod_cg_velocity: np.ndarray
    rod_cg_acceleration: np.ndarray
    crankpin_velocity: np.ndarray
    crankpin_acceleration: np.ndarray


def _check_mechanism(r: float, l: float, offset: float) -> None:
    if not (r > 0 and np.isfinite(r)):
        raise GeometryError(f"crank radius must be positive, got {r!r}")
    if not (l > 0 and np.isfinite(l)):
        raise GeometryError(f"rod length must be positive, got {l!r}")
    if l <= r + abs(offset):
        raise GeometryError(
            f"rod length {l} m must exceed crank radius {r} m plus |pin offset| {abs(offset)} m, "
            "otherwise the crank cannot turn fully"
        )


def piston_motion(
    phi,
    r: float,
    l: float,
    omega: float,
    *,
    offset: float = 0.0,
    rod_cg: float | None = None,
) -> PistonMotion:
    """Exact slider-crank motion at constant angular speed.

    Parameters
    ----------
    phi : array_like
        Crank angle from the cylinder axis in the sense of rotation, rad.
    r, l : float
        Crank radius and rod length (big-end to small-end centres), m.
    omega : float
        Crank angular speed, rad/s (constant).
    offset : float
        Piston-pin offset ``e`` (désaxé), m, see the module docstring.
    rod_cg : float, optional
        Distance of the rod's centre of mass from the big-end centre, m.

    Returns
    -------
    PistonMotion
        See the module docstring for the formulas.
    """
    _check_mechanism(r, l, offset)
    phi = np.asarray(phi, dtype=float)
    sphi, cphi = np.sin(phi), np.cos(phi)
    sb = (r * sphi - offset) / l
    beta = np.arcsin(sb)
    cb = np.cos(beta)
    x = r * cphi + l * cb
    s = np.sqrt((l + r) ** 2 - offset**2) - x
    bd = r * omega * cphi / (l * cb)
    bdd = (l * sb * bd**2 - r * omega**2 * sphi) / (l * cb)
    v = r * omega * sphi + l * sb * bd
    a = r * omega**2 * cphi + l * cb * bd**2 + l * sb * bdd

    # crankpin B = (r cos phi, r sin phi) in (axial, lateral)
    vb = np.stack([-r * omega * sphi, r * omega * cphi], axis=-1)
    ab = np.stack([-r * omega**2 * cphi, -r * omega**2 * sphi], axis=-1)
    # piston pin P = (x, e): velocity (-v, 0), acceleration (-a, 0)
    vp = np.stack([-v, np.zeros_like(v)], axis=-1)
    ap = np.stack([-a, np.zeros_like(a)], axis=-1)
    if rod_cg is None:
        vg = np.zeros_like(vb)
        ag = np.zeros_like(ab)
    else:
        k = rod_cg / l
        vg = vb + k * (vp - vb)
        ag = ab + k * (ap - ab)
    return PistonMotion(phi, s, v, a, beta, bd, bdd, vg, ag, vb, ab)


def sample_angles(n: int) -> np.ndarray:
    """``n`` equally spaced angles over one revolution, ``[0, 2 pi)``."""
    return 2.0 * np.pi * np.arange(n) / n


def fourier_coefficients(samples: np.ndarray, kmax: int) -> np.ndarray:
    """Coefficients ``(alpha_k, beta_k)``, ``k = 0..kmax``, of ``sum alpha cos k t + beta sin k t``.

    ``samples`` has shape ``(..., n)`` on ``sample_angles(n)``; returns shape
    ``(..., kmax + 1, 2)``; ``alpha_0`` is the mean.  By the FFT:
    ``alpha_k = 2 Re X_k / n``, ``beta_k = -2 Im X_k / n`` with ``X = rfft(samples)``
    (the trapezoidal rule of the Fourier integrals, exact for orders below ``n / 2``;
    order ``n / 2`` of an even ``n`` is the Nyquist term, whose sine is lost and whose
    cosine would be doubled, so ``kmax < n / 2`` is required).
    """
    n = samples.shape[-1]
    if 2 * kmax >= n:
        raise InputError(f"order {kmax} needs more than {n} samples per revolution", key="kmax")
    spec = np.fft.rfft(samples) / n  # along the last axis
    out = np.zeros(samples.shape[:-1] + (kmax + 1, 2))  # beta_0 stays 0
    out[..., 0, 0] = spec[..., 0].real
    out[..., 1:, 0] = 2.0 * spec[..., 1 : kmax + 1].real
    out[..., 1:, 1] = -2.0 * spec[..., 1 : kmax + 1].imag
    return out


def series_coefficients(lam: float) -> dict[int, float]:
    """Textbook power-series coefficients ``A_k`` (k = 1, 2, 4, 6; to lambda^5) of the
    acceleration harmonics of the central slider crank (see ``harmonic_coefficients``)."""
    return {
        1: 1.0,
        2: lam + lam**3 / 4.0 + 15.0 * lam**5 / 128.0,
        4: -(lam**3 / 4.0 + 3.0 * lam**5 / 16.0),
        6: 9.0 * lam**5 / 128.0,
    }


def harmonic_coefficients(lam: float, orders=(1, 2, 4, 6), *, method: str = "exact") -> dict[int, float]:
    """Coefficients ``A_k`` of ``a(phi) = r omega^2 sum_k A_k cos(k phi)`` (no pin offset).

    ``A_1 = 1`` and only even orders appear beyond it.  With ``method="series"`` the
    classical expansion of ``sqrt(1 - lam^2 sin^2 phi)`` in powers of ``lam`` (Kolchin &
    Demidov, ch. 2; Taylor, *The internal-combustion engine in theory and practice*,
    vol. 2, ch. 8) truncated after ``lam^5``::

        A_2 =   lam + lam^3/4 + 15 lam^5/128
        A_4 = -(lam^3/4 + 3 lam^5/16)
        A_6 =   9 lam^5/128

    With ``method="leading"`` only the leading power of each coefficient
    (``A_2 = lam``, ``A_4 = -lam^3/4``, ``A_6 = 9 lam^5/128``): the usual
    "first + second harmonic" engineering approximation (seed 001, eqs. 33-38).

    With ``method="exact"`` (default) the true Fourier coefficients of the exact
    acceleration, ``A_k = (1/pi) int_0^2pi a/(r omega^2) cos(k phi) dphi``, by the
    discrete Fourier transform of 512 samples (``fourier_coefficients``; the trapezoidal
    rule, exponentially convergent for this periodic analytic integrand; exact to
    round-off for lam < 0.5).  Any order >= 1 is allowed.

    Parameters
    ----------
    lam : float
        Crank ratio ``r / l``, 0 < lam < 1.
    orders : iterable of int
        Orders wanted.
    method : {"exact", "series", "leading"}

    Returns
    -------
    dict[int, float]
    """
    if not (0.0 < lam < 1.0):
        raise GeometryError(f"crank ratio lambda = r/l must lie in (0, 1), got {lam!r}")
    orders = tuple(int(k) for k in orders)
    if any(k < 1 for k in orders):
        raise ValueError(f"harmonic orders must be >= 1, got {orders}")
    if method == "series":
        ser = series_coefficients(lam)
        return {k: ser.get(k, 0.0) for k in orders}
    if method == "leading":
        lead = {1: 1.0, 2: lam, 4: -(lam**3) / 4.0, 6: 9.0 * lam**5 / 128.0}
        return {k: lead.get(k, 0.0) for k in orders}
    if method != "exact":
        raise ValueError(f"method must be 'exact', 'series' or 'leading', got {method!r}")
    n = 512
    a = piston_motion(sample_angles(n), 1.0, 1.0 / lam, 1.0).a
    c = fourier_coefficients(a, max(orders))
    return {k: float(c[k, 0]) for k in orders}


def piston_motion_harmonic(
    phi, r: float, l: float, omega: float, orders=(1, 2), *, method: str = "exact"
) -> PistonMotion:
    """Piston motion from the truncated harmonic series (no pin offset).

    With ``A_k`` from :func:`harmonic_coefficients`::

        s = r sum_k A_k / k^2 (1 - cos k phi)
        v = r omega sum_k A_k / k sin k phi
        a = r omega^2 sum_k A_k cos k phi

    (``s`` follows from ``a`` by integrating twice with ``s(0) = v(0) = 0``; with all
    orders the sum is the exact motion.)  The rod angle and the rod and crankpin
    vectors are the exact ones: only ``s, v, a`` are truncated.
    """
    exact = piston_motion(phi, r, l, omega)
    phi = np.asarray(phi, dtype=float)
    coef = harmonic_coefficients(r / l, orders, method=method)
    s = np.zeros_like(phi)
    v = np.zeros_like(phi)
    a = np.zeros_like(phi)
    for k, ak in coef.items():
        s = s + r * ak / k**2 * (1.0 - np.cos(k * phi))
        v = v + r * omega * ak / k * np.sin(k * phi)
        a = a + r * omega**2 * ak * np.cos(k * phi)
    return PistonMotion(
        phi,
        s,
        v,
        a,
        exact.beta,
        exact.beta_dot,
        exact.beta_ddot,
        exact.rod_cg_velocity,
        exact.rod_cg_acceleration,
        exact.crankpin_velocity,
        exact.crankpin_acceleration,
    )
