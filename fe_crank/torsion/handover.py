"""The journal torques the torsional stage hands to the assessment: one consistent
synthesis per journal, at one speed, the largest of the speed range.

IACS UR M53 Rev.1 2.2.2 takes the nominal alternating torque of a shaft section as
``M_TN = (M_Tmax - M_Tmin) / 2`` of the harmonic synthesis of the forced vibration
(orders 0.5 .. 12 four-stroke, 1 .. 15 two-stroke), the highest value over the speed
range.  At a crank speed ``omega`` two histories of a segment are available:

* the UR M53 synthesis ``S(theta; omega)`` (mean + the response of those orders,
  ``ForcedResponse.synthesis``), and
* the same with the quasi-static torque of every order: ``Q_all(omega) + V(omega)``,
  where ``V = S - Q_M53`` is the vibratory part and ``Q`` the rigid-shaft cumulative
  cylinder torque (of all harmonics of the cycle grid, ``Q_all``, or of the UR M53
  orders, ``Q_M53``); the orders above the synthesis are not amplified.

Both are one synthesis at one speed (gas and inertia torque, quasi-static and
vibratory, at the same ``omega``).  The journal's history handed over is, of all speeds
of the grid and both forms, the one with the largest half range; so its half range is
never below the largest ``M_TN`` of the segment (the higher orders can lower the half
range by a fraction of a per cent: the inline-4 genset's segments 0.1-1.3 % at some
speeds).  ``assess_speed = "operating"``: the all-orders form at the operating speed.
(Earlier the quasi-static torque at the operating speed was added to the vibratory part
at the governing speed: 4.7 % below ``M_TN`` on an inline-6 generating set.)
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

ALL_ORDERS = "quasi-static of all orders + vibratory of the UR M53 orders"
M53_ORDERS = "UR M53 synthesis (mean + orders of UR M53 2.2.2)"


@dataclass(frozen=True)
class JournalTorque:
    """The torque history handed over for one shaft segment (journal)."""

    segment: str
    speed: float  # rad/s at which the history is synthesised
    form: str  # ALL_ORDERS or M53_ORDERS
    history: np.ndarray  # N m over the cycle grid of the synthesis, positive driving
    max_m_tn: float  # N m: the largest UR M53 M_TN of the segment over the speed range
    case: str = "all cylinders firing"  # or "cylinder 3 misfiring" (fe_crank.torsion.misfire)

    @property
    def half_range(self) -> float:
        return float(0.5 * np.ptp(self.history))


def quasi_static_all_orders(result) -> tuple[np.ndarray, np.ndarray]:
    """Rigid-shaft segment torques of every harmonic of the cycle grid: the gas part
    (n_gas_parts, n_seg, n_theta), one per diagram of a full-load curve, and the inertia
    part (n_seg, n_theta) at ``harmonics.reference_speed`` (their synthesis is the
    dynamics stage's cumulative journal torque to round-off)."""
    h, m, theta = result.harmonics, result.model, result.theta
    phase = np.exp(1j * np.outer(theta, h.orders))
    out = []
    for part in (*h.gas_parts(), h.inertia):
        per_mass = np.zeros((m.size, theta.size))
        for cyl, throw in h.throw_of.items():
            per_mass[m.throw_mass[throw]] += np.real(phase @ part[cyl])
        out.append(np.cumsum(per_mass, axis=0)[:-1])
    return np.stack(out[:-1]), out[-1]


def segment_histories(result, s: int, qs_all=None) -> tuple[np.ndarray, np.ndarray]:
    """(UR M53 synthesis, all-orders form) of every segment (n_seg, n_theta) at speed
    index ``s`` (module docstring)."""
    gas, inertia = quasi_static_all_orders(result) if qs_all is None else qs_all
    w = result.response.speeds[s]
    ratio = (w / result.harmonics.reference_speed) ** 2
    syn = result.response.synthesis(s, result.theta)
    quasi = np.tensordot(result.harmonics.gas_weights(w), gas, axes=1) + ratio * inertia
    return syn, syn - result.quasi_static(s) + quasi


def journal_torques(result) -> dict[str, JournalTorque]:
    """Segment name -> the history handed over (module docstring)."""
    qs_all = quasi_static_all_orders(result)
    speeds = result.response.speeds
    lo, hi = result.speed_range
    inside = np.nonzero((speeds >= lo - 1e-9) & (speeds <= hi + 1e-9))[0]
    if result.assess_speed == "operating":
        inside = np.array([result.index(result.operating_speed)])
    best: dict[int, tuple[float, int, str, np.ndarray]] = {}
    for s in inside:
        forms = segment_histories(result, int(s), qs_all)
        names = (M53_ORDERS, ALL_ORDERS) if result.assess_speed != "operating" else (ALL_ORDERS,)
        for form, hist in zip(names, forms[-len(names) :], strict=True):
            half = 0.5 * np.ptp(hist, axis=1)
            for i, h in enumerate(half):
                if i not in best or h > best[i][0]:
                    best[i] = (float(h), int(s), form, hist[i].copy())
    m_tn = result.half_range[inside].max(axis=0)
    return {
        name: JournalTorque(name, float(speeds[best[i][1]]), best[i][2], best[i][3], float(m_tn[i]))
        for i, name in enumerate(result.model.segment_names)
    }


__all__ = ["JournalTorque", "journal_torques", "quasi_static_all_orders", "segment_histories"]
