"""Peak von Mises stresses by brute force, the references the study's screened stresses
are compared with: the counterweights' peak of a check's per-throw model (every
counterweight node, crank angle and load state, its stress histories superposed from the
FE stage's unit solutions with the coefficients a test names), and the peak of a
whole-shaft history over every node of the chosen group kinds."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from fe_crank.assess.group.assessment import of_counterweight
from fe_crank.assess.group.nodes import assessed_groups, unit_stresses
from fe_crank.fe.core.stress import von_mises
from fe_crank.fe.throw.pin_patches import rod_positions
from fe_crank.io.loadcase import LoadCase
from fe_crank.throw_scope import throws_of


def counterweight_peak(lc: LoadCase, solved: dict, speeds, coefficients: Callable) -> float:
    """The largest von Mises (Pa) over the counterweight groups' nodes of every unit solution
    of ``solved`` (key -> the FE stage's unit solutions), each throw the key stands for,
    and every state of ``speeds`` (``torsion.loads``' per-speed states);
    ``coefficients(unit, tc, state, sense, places)`` gives the cycle's coefficient matrix."""
    assert lc.geometry is not None
    names = [t.name for t in lc.engine.throws]
    ref = 0.0
    for key, us in solved.items():
        unit = unit_stresses(us, {g: n for g, n in assessed_groups(us).items() if of_counterweight(g)})
        nodes = np.unique(np.concatenate([np.asarray(v) for v in unit.groups.values()]))
        for t in throws_of(key, names):
            sense = lc.engine.shaft(lc.engine.throw(t).shaft).sense
            places = rod_positions(lc.engine, t, lc.geometry.crankpin_length)
            for states in speeds:
                for state in states:
                    C = coefficients(unit, state.throws[t], state, sense, places)
                    s = np.einsum("ac,cjn->ajn", C, unit.stress[:, :, nodes])
                    ref = max(ref, float(von_mises(np.moveaxis(s, 1, 0)).max()))
    return ref


def brute_peak(units, weights: np.ndarray, kinds=None) -> float:
    """The largest von Mises stress (Pa) of the history sum_c W_c(theta) S_c at every node of
    the group kinds ``kinds`` (None: every assessed group) of every throw's unit stresses
    ``units``, every angle (``weights``: angles x unit cases)."""
    from fe_crank.fe.throw.node_groups import group_kind

    peak = 0.0
    for unit in units:
        ids = np.unique(
            np.concatenate([v for g, v in unit.groups.items() if len(v) and (kinds is None or group_kind(g) in kinds)])
        )
        s = unit.stress[:, :, ids]
        hist = (weights @ s.reshape(s.shape[0], -1)).reshape(weights.shape[0], 6, ids.size)
        peak = max(peak, float(von_mises(hist.transpose(1, 0, 2)).max()))
    return peak
