"""The chain of an explicit lumped model (``[torsion] model = "lumped"``): the stations
as given, no CAD and no Carter.

Station ``i`` is mass ``i`` of ``TorsionModel``; the connection stated on station
``i + 1`` is segment ``i`` (its stiffness, loss factor as complex stiffness
``k (1 + i eta)``, viscous damping across it); a station's ``absolute_damping`` is its
damper to ground.  The engine's cylinders act on the stations that name them; a
throw's mass is the station of its cylinders (``TorsionModel.throw_mass``), so the
journal segments either side of a throw are the connections either side of that station.
A throw without cylinders (none in the shipped engines) has no station and no journal
torque from this model.
"""

from __future__ import annotations

import numpy as np

from fe_crank.errors import InputError
from fe_crank.torsion.model import TorsionModel


def lumped_model(engine, settings, *, file: str | None = None) -> TorsionModel:
    """``TorsionModel`` of ``settings.stations`` with the throws of ``engine`` placed on
    the stations their cylinders name (``fe_crank.io.torsion_lumped.check_stations``
    has checked the attachment when the load case was read)."""
    st = settings.stations
    if len(st) < 2:
        raise InputError("a lumped model needs at least two stations", file=file, key="torsion.stations")
    throw_mass: dict[str, int] = {}
    for i, s in enumerate(st):
        for c in s.cylinders:
            throw_mass[engine.cylinder(c).throw] = i
    names = tuple(s.name for s in st)
    return TorsionModel(
        names,
        np.array([s.inertia for s in st]),
        np.array([s.stiffness for s in st[1:]]),
        np.array([s.loss_factor for s in st[1:]]),
        np.array([s.damping for s in st[1:]]),
        np.array([s.absolute_damping for s in st]),
        tuple(f"{a}-{b}" for a, b in zip(names[:-1], names[1:], strict=True)),
        throw_mass,
    )
