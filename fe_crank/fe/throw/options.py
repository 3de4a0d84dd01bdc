"""Options of the FE stage's unit load cases and the statement of their support model.

``FeOptions`` (the load case's ``[fe]`` section, ``fe_crank.fe.input``), the default unit
cases ``CASES``, the check that a support model is fully stated and its one-line text for
the report (``UnitSolutions.support_model``).  The models themselves: ``unit_cases``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal, Protocol, get_args

import numpy as np

from fe_crank.errors import InputError
from fe_crank.fe.linalg.choice import SolverMethod
from fe_crank.fe.throw.pin_directions import pin_cases, unit_force

#: default unit cases: the centrifugal load, 1 N on the crankpin in 12 directions 30 deg
#: apart (``pin_directions``: pin_x, pin_030, ..., pin_y = radial outward, ...), the torque
CASES = ("centrifugal",) + pin_cases() + ("torque",)
PIN_FORCES = {name: unit_force(name) for name in pin_cases()}

#: the support models (``unit_cases``), the end faces that can react the torque
Support = Literal["determinate", "foundation"]
TorqueEnd = Literal["end_2", "end_1"]
SUPPORTS: tuple[Support, ...] = get_args(Support)
TORQUE_ENDS: tuple[TorqueEnd, ...] = get_args(TorqueEnd)


class Material(Protocol):
    """What the FE stage reads from a material (SI)."""

    @property
    def youngs_modulus(self) -> float: ...
    @property
    def poisson_ratio(self) -> float: ...
    @property
    def density(self) -> float: ...


@dataclass(frozen=True)
class FeOptions:
    """Options of :func:`solve_unit_cases` (all SI).

    support: "determinate" (default) or "foundation", see ``fe_crank.fe.throw.unit_cases``.
    bearing_stiffness: N/m^3, the foundation's stiffness per area ("foundation" only, required there).
    torque_reaction: the end face that reacts the torque (where the power is taken off):
    "end_2" (default, rear/flywheel side) or "end_1"; the ``torque`` unit case enters at the other.
    solver: "auto" | "pardiso" | "pardiso_ooc" | "cholmod" | "amg" | "superlu" (``fe.linalg.choice``).
    cases: which unit cases to solve: "centrifugal", "torque" and pin cases by direction
    ("pin_x", "pin_y", "pin_-x", "pin_-y", "pin_<deg>"; see ``pin_directions``).
    pin_half_angle: rad, half width of the cosine pressure arc.
    symmetry: solve on the symmetry components where the mesh states mirror planes
    (``ThrowMesh.symmetry``) and the supports are the determinate ones (``fe.core.symmetric``);
    False: the full model (for comparison; same answer to round-off).
    """

    support: Support = "determinate"
    bearing_stiffness: float | None = None
    solver: SolverMethod = "auto"
    cases: tuple[str, ...] = CASES
    pin_half_angle: float = float(np.deg2rad(60.0))
    journals: tuple[str, str] = ("journal_1", "journal_2")
    torque_reaction: TorqueEnd = "end_2"
    pin_boundary: str = "crankpin"
    pin_centre: tuple[float, float] | None = None  # (x, y) of the pin axis; None: centroid of the pin surface
    intorder: int = 2
    symmetry: bool = True
    #: axial bands (z_lo, z_hi), m, of the rods' places on the pin (``fe.throw.pin_patches``): the
    #: patch cases ``pin_<deg>@<k>`` load band k; empty: the whole pin
    pin_patches: tuple[tuple[float, float], ...] = ()

    @property
    def reaction_face(self) -> TorqueEnd:
        """End face reacting the torque."""
        return self.torque_reaction

    @property
    def torque_face(self) -> TorqueEnd:
        """End face where the ``torque`` unit case enters (the other one)."""
        return "end_1" if self.torque_reaction == "end_2" else "end_2"


def check_support_options(options: FeOptions) -> None:
    """Refuse a support model that is not fully stated."""
    if options.support not in SUPPORTS:
        raise InputError(
            f"unknown support {options.support!r}; pick 'determinate' (statically determinate, "
            f"the default) or 'foundation' (with bearing_stiffness)",
            key="fe.support",
        )
    if options.torque_reaction not in TORQUE_ENDS:
        raise InputError(
            f"unknown torque_reaction {options.torque_reaction!r}; pick 'end_2' or 'end_1'", key="fe.torque_reaction"
        )
    if options.support == "foundation":
        k = options.bearing_stiffness
        if k is None or not k > 0:
            raise InputError(
                "support = 'foundation' needs bearing_stiffness > 0 (N/m^3, from the oil film and "
                "housing; docs/fe.md says how to derive it)",
                key="fe.bearing_stiffness",
            )
    elif options.bearing_stiffness is not None:
        raise InputError("bearing_stiffness applies to support = 'foundation' only", key="fe.bearing_stiffness")


def support_text(options: FeOptions, centres: dict[str, float]) -> str:
    """The support model in one line (``UnitSolutions.support_model``)."""
    j1, j2 = options.journals
    if options.support == "foundation":
        return (
            f"radial elastic foundation k = {options.bearing_stiffness:.4g} N/m^3 on {j1} and {j2} "
            f"(statically indeterminate); torque and axial force reacted at {options.reaction_face} "
            f"(rigid coupling)"
        )
    zs = ", ".join(f"{centres[j] * 1e3:.2f}" for j in options.journals)
    return (
        f"statically determinate (IACS UR M53 2.1): {j1} and {j2} on distributing (RBE3) couplings to "
        f"simple supports at the bearing centres z = {zs} mm (radial at both, axial at "
        f"{axial_journal(options)}); torque reacted at {options.reaction_face}"
    )


def axial_journal(options: FeOptions) -> str:
    return options.journals[1] if options.torque_reaction == "end_2" else options.journals[0]
