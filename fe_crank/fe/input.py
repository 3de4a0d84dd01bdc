"""The load case's ``[fe]`` section -> frozen :class:`~fe_crank.fe.throw.unit_cases.FeOptions`.

::

    [fe]
    support = "determinate"             # default; or "foundation" (needs bearing_stiffness)
    bearing_stiffness = "2e12 N/m^3"    # foundation only, required there (docs/fe.md: how to derive it)
    torque_reaction = "end_2"           # end face where the power is taken off: "end_2" (default) | "end_1"
    solver = "auto"                     # "pardiso" | "pardiso_ooc" | "cholmod" | "amg" | "superlu"
    pin_half_angle = "60 deg"           # cosine pressure arc on the crankpin
    symmetry = true                     # solve mirror-symmetric meshes on their symmetry components
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from pydantic import Field, StrictBool, model_validator

from fe_crank.errors import InputError
from fe_crank.fe.linalg.choice import SolverMethod
from fe_crank.fe.throw.options import Support, TorqueEnd
from fe_crank.fe.throw.pin_directions import pin_case_weights, pin_direction
from fe_crank.fe.throw.unit_cases import CASES, FeOptions
from fe_crank.io.base import Strict, validate
from fe_crank.io.units import Angle, StiffnessPerArea

RENAMED = {
    "elastic": 'the radial foundation is now support = "foundation" with an explicit bearing_stiffness; '
    'the default "determinate" needs no stiffness',
    "rigid": 'the penalty ("rigid") bearing was removed: use the default "determinate" '
    "(simple supports at the bearing centres)",
}


class FeInput(Strict):
    support: Support = "determinate"
    bearing_stiffness: StiffnessPerArea | None = Field(default=None, gt=0)
    torque_reaction: TorqueEnd = "end_2"
    solver: SolverMethod = "auto"
    pin_half_angle: Angle = Field(default=FeOptions.pin_half_angle, gt=0, le=1.5707963267948966)
    cases: tuple[str, ...] = CASES
    symmetry: StrictBool = True  # true or false only: a string such as "no" is refused, not read

    @model_validator(mode="after")
    def _check(self):
        bad = [c for c in self.cases if c not in CASES]
        if bad:
            raise ValueError(f"unknown unit cases {bad}; pick from {', '.join(CASES)}")
        missing = [c for c in ("centrifugal", "torque") if c not in self.cases]
        if missing:
            raise ValueError(f"the cycle assessment needs the unit cases {missing}")
        pins = [c for c in self.cases if pin_direction(c) is not None]
        try:  # the pin cases must carry a force in any direction
            pin_case_weights(np.array([[np.cos(a), np.sin(a)] for a in np.deg2rad(np.arange(0, 360, 5))]), pins)
        except ValueError as exc:
            raise ValueError(
                f"the pin unit cases {pins} cannot carry a crankpin force in every direction "
                f"({exc}); list at least three directions less than 180 deg apart"
            ) from None
        if self.support == "foundation" and self.bearing_stiffness is None:
            raise ValueError(
                'support = "foundation" needs bearing_stiffness (N/m^3, from the oil film and housing: docs/fe.md)'
            )
        if self.support != "foundation" and self.bearing_stiffness is not None:
            raise ValueError('bearing_stiffness applies to support = "foundation" only')
        return self


def parse_fe(value: object, file: str | Path, key: str = "fe") -> FeOptions:
    """Section parser of the load case's ``[fe]`` section (``fe_crank.io.sections``)."""
    if not isinstance(value, dict):
        raise InputError('must be a table, e.g. [fe] support = "elastic"', file=str(file), key=key)
    support = value.get("support")
    if isinstance(support, str) and support in RENAMED:
        raise InputError(
            f"support = {support!r} is no longer offered: {RENAMED[support]}", file=str(file), key=f"{key}.support"
        )
    raw = validate(FeInput, value, file, key)
    return FeOptions(
        support=raw.support,
        bearing_stiffness=raw.bearing_stiffness,
        solver=raw.solver,
        pin_half_angle=raw.pin_half_angle,
        cases=tuple(raw.cases),
        torque_reaction=raw.torque_reaction,
        symmetry=raw.symmetry,
    )


def check_torque_reaction(
    options: FeOptions, engine, file: str | Path, key: str = "fe.torque_reaction", *, torsion: bool = False
) -> None:
    """A front power take-off (``torque_reaction = "end_1"``) with the torsional stage on
    an engine with more than one throw on a shaft is refused: the torsional chain takes
    the power off behind the last throw.  Without the torsional stage either end is
    checked: the assessment takes each throw's entering torque from the torque flow for
    that end (``fe_crank.torsion.flow.torque_flow``)."""
    if options.torque_reaction != "end_1" or not torsion:
        return
    per_shaft: dict[str, int] = {}
    for t in engine.throws:
        per_shaft[t.shaft] = per_shaft.get(t.shaft, 0) + 1
    if max(per_shaft.values()) > 1:
        raise InputError(
            f"a front power take-off on a shaft with {max(per_shaft.values())} throws contradicts the torsional "
            "chain, which takes the power off behind the last throw (flywheel, driven machines); take the power "
            "off at the rear (end_2) or check without [torsion]",
            file=str(file),
            key=key,
        )
