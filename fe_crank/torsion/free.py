"""Free torsional vibration: natural frequencies and mode shapes, and a Holzer table.

Undamped eigenproblem ``K x = omega^2 J x`` (generalised, symmetric; scipy ``eigh``);
mode shapes normalised to a unit largest amplitude, sign so that the free-end mass
(index 0) is positive.

Holzer's method (Den Hartog, *Mechanical Vibrations*, 4th ed., sec. 5.5; Ker Wilson
vol. 1): for a trial ``omega`` set ``theta_0 = 1``; going along the chain the torque
in segment ``i`` is the sum of the inertia torques ``omega^2 J_j theta_j`` of the masses
before it, and ``theta_{i+1} = theta_i - T_i / k_i``.  ``omega`` is natural when the
residual torque after the last mass is zero (a free-free chain).  It is an independent
check of the eigen-solution (no matrices).

A segment without stiffness (the ring of an untuned viscous damper, coupled by its
silicone film alone) separates the undamped chain into parts that turn freely against
each other: each part has its own rigid-body mode at 0 Hz (``Modes.rigid`` of them, all
dropped from the reports), and Holzer's table runs on each part.  These are the
natural frequencies with the damper's film free (c -> 0); the forced response always
uses the film's damping.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.linalg import eigh
from scipy.optimize import brentq

from fe_crank.torsion.model import TorsionModel


@dataclass(frozen=True)
class Modes:
    omega: np.ndarray  # (m,) rad/s, ascending, the rigid-body modes (0) included
    shapes: np.ndarray  # (n, m) columns normalised to max |x| = 1
    rigid: int = 1  # number of rigid-body modes (one per freely turning part of the chain)

    @property
    def frequencies_hz(self) -> np.ndarray:
        return self.omega / (2 * np.pi)

    @property
    def elastic_omega(self) -> np.ndarray:
        """Natural angular frequencies of the elastic modes (rad/s)."""
        return self.omega[self.rigid :]

    @property
    def elastic_hz(self) -> np.ndarray:
        return self.elastic_omega / (2 * np.pi)


def natural_modes(model: TorsionModel) -> Modes:
    """Undamped natural frequencies and mode shapes of the chain (rigid mode first)."""
    lam, vec = eigh(model.stiffness_matrix(), model.mass_matrix())
    rigid = len(model.components())
    lam = np.clip(lam, 0.0, None)
    lam[:rigid] = 0.0  # round-off of the rigid-body modes
    omega = np.sqrt(lam)
    shapes = vec / np.max(np.abs(vec), axis=0)
    lead = shapes[np.argmax(np.abs(shapes) > 1e-9, axis=0), np.arange(shapes.shape[1])]
    shapes = shapes * np.where(lead < 0, -1.0, 1.0)
    return Modes(omega, shapes, rigid)


def holzer_table(model: TorsionModel, omega: float) -> dict[str, np.ndarray]:
    """Holzer table at ``omega``: columns ``theta`` (n,), ``inertia_torque``
    ``omega^2 J theta`` (n,), ``cumulative`` torque after each mass (n,), ``twist``
    of each segment (n-1,).  ``cumulative[-1]`` is the residual torque."""
    n = model.size
    theta = np.zeros(n)
    inertia_torque = np.zeros(n)
    cumulative = np.zeros(n)
    twist = np.zeros(n - 1)
    theta[0] = 1.0
    total = 0.0
    for i in range(n):
        inertia_torque[i] = omega**2 * model.inertia[i] * theta[i]
        total += inertia_torque[i]
        cumulative[i] = total
        if i < n - 1:
            twist[i] = total / model.stiffness[i]
            theta[i + 1] = theta[i] - twist[i]
    return {"theta": theta, "inertia_torque": inertia_torque, "cumulative": cumulative, "twist": twist}


def holzer_residual(model: TorsionModel, omega: float) -> float:
    return float(holzer_table(model, omega)["cumulative"][-1])


def holzer_frequencies(model: TorsionModel, omega_max: float, *, samples: int = 4000) -> np.ndarray:
    """Natural frequencies (rad/s, > 0) below ``omega_max`` as the roots of the Holzer
    residual: sign changes on a fine grid, then Brent's method to 1e-12 relative; on
    each elastically connected part of the chain (module docstring)."""
    parts = model.components()
    if len(parts) > 1:
        roots = [
            holzer_frequencies(part_of(model, p), omega_max, samples=samples) for p in parts if p.stop - p.start > 1
        ]
        return np.sort(np.concatenate([np.zeros(0), *roots]))
    w = np.linspace(omega_max * 1e-6, omega_max, samples)
    r = np.array([holzer_residual(model, x) for x in w])
    roots = []
    for i in np.nonzero(np.sign(r[:-1]) * np.sign(r[1:]) < 0)[0]:
        roots.append(brentq(lambda x: holzer_residual(model, x), w[i], w[i + 1], xtol=1e-14, rtol=1e-13))
    return np.array(roots)


def part_of(model: TorsionModel, part: slice) -> TorsionModel:
    """The masses ``part`` of the chain and the segments between them."""
    seg = slice(part.start, part.stop - 1)
    return TorsionModel(
        model.names[part],
        np.asarray(model.inertia)[part],
        np.asarray(model.stiffness)[seg],
        np.asarray(model.loss_factor)[seg],
        np.asarray(model.segment_damping)[seg],
        np.asarray(model.absolute_damping)[part],
        model.segment_names[seg],
        {},
    )
