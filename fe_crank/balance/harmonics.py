"""Harmonic content of piston motion: closed-form series and exact spectral coefficients.

The reciprocating inertia force of one slider crank is ``m_j * s''``; for the central
mechanism (no pin offset) its Fourier series in the crank angle is (e.g. Taylor, *The
Internal-Combustion Engine in Theory and Practice* vol. 2, ch. 8; Heywood, App. B)::

    s'' = r omega^2 (cos phi + A2 cos 2 phi + A4 cos 4 phi + A6 cos 6 phi + ...)
    A2 = lam + lam^3/4 + 15 lam^5/128
    A4 = -(lam^3/4 + 3 lam^5/16)
    A6 = 9 lam^5/128

(``lam = r / l``), truncated after ``lam^5`` (``series_coefficients``, implemented in
``fe_crank.mechanism.kinematics``).  For the balance sums fe-crank does not use
the truncated series: ``spectral_coefficients`` takes the exact piston position of any
mechanism (offset pins, articulated rods) at ``N`` equally spaced crank angles, and its
discrete Fourier transform (``fe_crank.mechanism.kinematics.fourier_coefficients``, the one used
for the exact ``harmonic_coefficients`` too) gives the coefficients of ``x(tau)``; twice differentiating
term by term, order ``k`` of the acceleration is ``-k^2`` times order ``k`` of the
position.  For a smooth periodic ``x`` the error decays exponentially with ``N``.
"""

from __future__ import annotations

import numpy as np

from fe_crank.mechanism.kinematics import fourier_coefficients, series_coefficients
from fe_crank.mechanism.kinematics import sample_angles as _sample_angles

__all__ = ["SAMPLES", "acceleration_coefficients", "fourier_coefficients", "sample_angles", "series_coefficients"]

#: samples per shaft revolution for the spectral coefficients (orders up to N/2)
SAMPLES = 256


def sample_angles(n: int = SAMPLES) -> np.ndarray:
    """``n`` equally spaced angles over one revolution (``fe_crank.mechanism.kinematics.sample_angles``)."""
    return _sample_angles(n)


def acceleration_coefficients(position: np.ndarray, kmax: int) -> np.ndarray:
    """Fourier coefficients of ``d^2 x / d tau^2`` from samples of ``x(tau)``.

    Shape as ``fourier_coefficients``; order 0 is zero.
    """
    c = fourier_coefficients(position, kmax)
    k = np.arange(kmax + 1)  # integer orders: k^2 is exact, the product with c is float
    return -(k**2)[:, None] * c
