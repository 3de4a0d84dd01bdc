"""Lumped-mass torsional model of a crank train: a chain of inertias and shaft segments.

Equation of motion of the chain (Den Hartog, *Mechanical Vibrations*, 4th ed., ch. 5;
Ker Wilson, *Practical Solution of Torsional Vibration Problems*, vol. 1)::

    J theta'' + C theta' + K theta = T(t)

``J`` diagonal (kg m^2), ``K`` the tridiagonal stiffness of the segments (N m/rad),
``C`` = absolute dampers to ground (``absolute_damping``, e.g. the cylinders' piston and
bearing friction) + relative viscous dampers across segments (``segment_damping``, a
viscous damper or a coupling).  The shaft material's hysteresis enters as a loss factor
``eta`` per segment: complex stiffness ``k (1 + i eta)`` in the frequency domain, i.e. a
modal damping ratio ``zeta = eta / 2`` at resonance.

Masses are numbered from the free end (front, smaller z) to the driven end; segment ``i``
joins mass ``i`` and ``i + 1``.  A segment may have no stiffness when it has a viscous
damping: the ring of an untuned viscous (Houdaille) damper, coupled to its hub by the
silicone film alone (Den Hartog sec. 3.9; Ker Wilson vol. 4).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np

from fe_crank import model
from fe_crank.errors import InputError
from fe_crank.geometry.spec import CrankGeometry
from fe_crank.io.material import Material
from fe_crank.io.torsion import TorsionSettings


class TorsionCase(Protocol):
    """What the torsional stage reads of a load case (``fe_crank.io.loadcase.LoadCase``
    has it): the engine, the operating point, the crank geometry and material (throw
    inertias and stiffnesses) and the ``[torsion]`` section."""

    @property
    def source_file(self) -> str: ...
    @property
    def engine(self) -> model.Engine: ...
    @property
    def operating(self) -> model.OperatingPoint: ...
    @property
    def geometry(self) -> CrankGeometry | None: ...
    @property
    def material(self) -> Material | None: ...
    @property
    def torsion(self) -> TorsionSettings | None: ...


@dataclass(frozen=True)
class TorsionModel:
    """A chain of ``n`` inertias and ``n - 1`` segments (SI).

    ``throw_mass[name]`` is the index of the mass that carries throw ``name``;
    ``segment_names[i]`` names the shaft between mass ``i`` and ``i + 1`` (e.g. the
    journal ``"1-2"`` between throws 1 and 2).
    """

    names: tuple[str, ...]
    inertia: np.ndarray  # (n,) kg m^2
    stiffness: np.ndarray  # (n-1,) N m/rad
    loss_factor: np.ndarray  # (n-1,) shaft hysteresis eta (complex stiffness k (1 + i eta))
    segment_damping: np.ndarray  # (n-1,) N m s/rad, viscous across the segment
    absolute_damping: np.ndarray  # (n,) N m s/rad, viscous to ground
    segment_names: tuple[str, ...]
    throw_mass: dict

    def __post_init__(self):
        n = len(self.names)
        for key, arr, size in (
            ("inertia", self.inertia, n),
            ("stiffness", self.stiffness, n - 1),
            ("loss_factor", self.loss_factor, n - 1),
            ("segment_damping", self.segment_damping, n - 1),
            ("absolute_damping", self.absolute_damping, n),
        ):
            a = np.asarray(arr, float)
            if a.shape != (size,) or not np.all(np.isfinite(a)):
                raise InputError(f"needs {size} finite values (got shape {a.shape})", key=f"torsion.{key}")
        if n < 2:
            raise InputError("a torsional model needs at least two masses", key="torsion")
        if np.any(self.inertia <= 0):
            raise InputError("every inertia must be positive", key="torsion.inertia")
        if np.any(self.loss_factor < 0) or np.any(self.segment_damping < 0) or np.any(self.absolute_damping < 0):
            raise InputError("damping must not be negative", key="torsion.damping")
        if np.any(self.stiffness < 0):
            raise InputError("a segment stiffness must not be negative", key="torsion.stiffness")
        if np.any((self.stiffness == 0) & (self.segment_damping <= 0)):
            raise InputError(
                "a segment without stiffness needs a viscous damping (an untuned viscous damper), "
                "else the chain falls apart",
                key="torsion.stiffness",
            )

    @property
    def size(self) -> int:
        return len(self.names)

    def components(self) -> list[slice]:
        """The elastically connected parts of the chain (split at the segments without
        stiffness), as slices of the masses: one part without a viscous-only segment."""
        cuts = [i + 1 for i, k in enumerate(self.stiffness) if k == 0]
        edges = [0, *cuts, self.size]
        return [slice(a, b) for a, b in zip(edges[:-1], edges[1:], strict=True)]

    @staticmethod
    def _chain(values: np.ndarray, n: int) -> np.ndarray:
        """Tridiagonal matrix of springs/dampers ``values`` (n-1,) joining i and i+1."""
        out = np.zeros((n, n), dtype=np.result_type(values, float))
        for i, v in enumerate(values):
            out[i, i] += v
            out[i + 1, i + 1] += v
            out[i, i + 1] -= v
            out[i + 1, i] -= v
        return out

    def mass_matrix(self) -> np.ndarray:
        return np.diag(np.asarray(self.inertia, float))

    def stiffness_matrix(self, *, hysteretic: bool = False) -> np.ndarray:
        """``K`` (real), or ``K (1 + i eta)`` segment by segment when ``hysteretic``."""
        k = np.asarray(self.stiffness, float)
        if hysteretic:
            k = k * (1.0 + 1j * np.asarray(self.loss_factor, float))
        return self._chain(k, self.size)

    def damping_matrix(self) -> np.ndarray:
        return self._chain(np.asarray(self.segment_damping, float), self.size) + np.diag(
            np.asarray(self.absolute_damping, float)
        )

    def segment_torque(self, angles: np.ndarray, omega: float | None = None) -> np.ndarray:
        """Torque in each segment from the mass angles ``angles`` (n, ...) (complex
        amplitudes when ``omega`` is given): ``T_i = k_i (1 + i eta_i) (theta_i - theta_{i+1})
        + i omega c_i (theta_i - theta_{i+1})``; positive when mass ``i`` leads."""
        a = np.asarray(angles)
        twist = a[:-1] - a[1:]
        k = np.asarray(self.stiffness, float).reshape((-1,) + (1,) * (a.ndim - 1))
        if omega is None:
            return k * twist
        eta = np.asarray(self.loss_factor, float).reshape(k.shape)
        c = np.asarray(self.segment_damping, float).reshape(k.shape)
        return (k * (1 + 1j * eta) + 1j * omega * c) * twist
