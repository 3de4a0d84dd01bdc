"""The hot-spot convergence study's factors on the FE stress criteria, and its own criterion.

When the study ran (``fe_crank.fe.refinement.convergence``), the assessment does not keep the
assessed mesh's hot-spot values: on every surface the study follows -- the shaft fillets,
the counterweights' transition fillets, the oil-bore outlet -- the FE stress criteria are
evaluated over the groups (``assess.criteria.finders.over_groups``) with each group's stresses taken
at the study's best estimate of the converged peak,

    sigma_criterion = k sigma_assessed,   k = max(1, sigma_est / sigma_assessed),

with sigma_est and sigma_assessed the study's peaks on that surface (the throw's model, the
load set with the largest k) at its best estimate (``fe.refinement.convergence.estimate``: the finest
level or the Richardson extrapolation) and on the assessed mesh (the study's first level).
No credit is taken when the peak falls with refinement (k >= 1): the study's load sets are
the peak pin force and the peak torque, not every state of the cycle.  A safety factor
(static, overspeed, fatigue, Gough-Pollard) is divided by k -- exact for the static ones,
conservative for Goodman (UR M53's sigma_add does not grow) -- and a stress limit
(counterweight stresses) multiplied by it; groups the study does not follow (the
counterweight bodies, their junctions) keep k = 1.  The worst group may then be another
than the assessed mesh's; the criterion's remarks name the factor (``Refinement``).  Over
a full-load curve the factors apply at every speed and load state and in both models (a
group's k is the same at every speed: the study measures the mesh, whose refinement ratio
a load's magnitude does not change; the whole shaft's throws are meshed as the per-throw
model's, and a throw mesh's study holds both models' load sets -- the whole shaft's own
states of the largest crankpin force and journal torque, ``fe.shaft.refinement`` -- so k
is the largest over both).

The study's own criterion, ``mesh_convergence`` (``criterion``): the assessed mesh and the
finest level must agree within the tolerance (5 %) for every load set, else the sign-off
fails as not converged.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from fe_crank.fe.refinement.convergence import estimate
from fe_crank.fe.refinement.levels import COUNTERWEIGHT_PREFIX, OIL_BORE_PREFIX, ConvergenceStudy
from fe_crank.results import CriterionResult, Location
from fe_crank.throw_scope import ALL_THROWS

#: quantity -> True when the value is a safety factor (divided by k), False a stress (times k)
SCALED = {
    "static_safety": True,
    "overspeed_safety": True,
    "fatigue_safety": True,
    "gough_pollard_safety": True,
    "counterweight_stress": False,
    "counterweight_overspeed_stress": False,
}
SURFACES = {"": "shaft fillets", COUNTERWEIGHT_PREFIX: "counterweight fillets", OIL_BORE_PREFIX: "oil-bore outlet"}


@dataclass(frozen=True)
class Refinement:
    """The factor k a criterion is taken at, and on what it rests."""

    criterion: str
    factor: float
    surface: str  # "shaft fillets", "counterweight fillets", "oil-bore outlet"
    basis: str  # the estimate in words, e.g. "finest level r/8" or "Richardson extrapolation ..."
    load_set: str
    ratio: float  # sigma_est / sigma_assessed before the floor at 1

    @property
    def words(self) -> str:
        fall = "; the peak falls with refinement: no credit taken" if self.ratio < 1.0 else ""
        return f"x{self.factor:.3f} by the convergence study ({self.surface}: {self.basis}, {self.load_set}{fall})"


def _surface(group: str) -> str | None:
    if group.startswith(("crankpin_fillet", "journal_fillet")):
        return ""
    if group.startswith("counterweight_fillet"):
        return COUNTERWEIGHT_PREFIX
    if group == "oil_bore":
        return OIL_BORE_PREFIX
    return None


def _in_surface(name: str, prefix: str) -> bool:
    if prefix:
        return name.startswith(prefix)
    return not name.startswith((COUNTERWEIGHT_PREFIX, OIL_BORE_PREFIX))


def surface_factor(
    studies: dict[str, ConvergenceStudy], throw: str, group: str
) -> tuple[float, str, str, float] | None:
    """(k, the estimate in words, load set, sigma_est / sigma_assessed) of a group of a
    throw, or None when the study does not follow its surface (module docstring): the load
    set with the largest ratio."""
    prefix = _surface(group)
    study = studies.get(throw, studies.get(ALL_THROWS))
    if prefix is None or study is None:
        return None
    found = [(estimate(study, n), n) for n in study.changes if _in_surface(n, prefix)]
    if not found:
        return None
    (ratio, basis), load_set = max(found, key=lambda x: x[0][0])
    return max(1.0, ratio), basis, load_set.removeprefix(prefix), ratio


@dataclass
class StudyFactors:
    """The study's factor of each (throw, group), each found once (``surface_factor``)."""

    studies: dict[str, ConvergenceStudy]
    _found: dict[tuple[str, str], tuple[float, str, str, float] | None] = field(default_factory=dict)

    def found(self, throw: str, group: str) -> tuple[float, str, str, float] | None:
        if (throw, group) not in self._found:
            self._found[throw, group] = surface_factor(self.studies, throw, group)
        return self._found[throw, group]

    def factor(self, throw: str, group: str) -> float:
        """k of a group of a throw (1 where the study does not follow its surface)."""
        f = self.found(throw, group)
        return 1.0 if f is None else f[0]

    def refinement(self, criterion: str, where: Location | None) -> Refinement | None:
        """The factor the criterion ``criterion`` is taken at, at its governing group ``where``
        (None: the study does not follow that group's surface)."""
        if where is None or where.kind != "group":
            return None
        f = self.found(where.throw, where.group)
        if f is None:
            return None
        return Refinement(criterion, f[0], SURFACES[_surface(where.group) or ""], f[1], f[2], f[3])


def criterion(studies: dict[str, ConvergenceStudy]) -> CriterionResult:
    """The ``mesh_convergence`` criterion: the largest difference of a hot-spot peak between
    the assessed mesh and the finest level, over the load sets and throws, must not exceed
    the tolerance (a "max" criterion; failing it: not converged)."""
    key, st = max(studies.items(), key=lambda kv: kv[1].assessed_change)
    name = max(st.assessed_changes, key=lambda n: st.assessed_changes[n])
    a, b = st.levels[0], st.levels[-1]
    tol = st.tolerance
    return CriterionResult(
        name="mesh_convergence.max_peak_change",
        passed=st.converged,
        value=st.assessed_change,
        limit=tol,
        margin=1.0 - st.assessed_change / tol if tol > 0 else -math.inf,
        unit="",
        quantity="mesh_convergence",
        sense="max",
        where=Location("hot_spot", key, b.where[name], detail=name, levels=(a.fillet_divisions, b.fillet_divisions)),
        remarks=() if st.converged else ("NOT CONVERGED",),
        description="relative difference of the peak von Mises stress on the hot-spot surfaces (shaft and "
        "counterweight fillets, oil-bore outlet) between the assessed mesh and the finest level of the "
        "convergence study (docs/fe.md)",
    )


__all__ = ["SCALED", "Refinement", "StudyFactors", "criterion", "surface_factor"]
