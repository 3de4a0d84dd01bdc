"""The hot-spot convergence study in the verdict (``decide``'s part of it, one owner).

When the study ran (``fe_crank.fe.convergence``), the verdict does not keep the assessed
mesh's hot-spot values: on every surface the study follows -- the shaft fillets, the
counterweights' transition fillets, the oil-bore outlet -- the FE stress criteria are
re-evaluated over the groups (``assess.criteria.over_groups``, the assessment's own
evaluators) with each group's stresses taken at the study's best estimate of the
converged peak,

    sigma_verdict = k sigma_assessed,   k = max(1, sigma_est / sigma_assessed),

with sigma_est and sigma_assessed the study's peaks on that surface (the throw's model, the
load set with the largest k) at the finest level and on the assessed mesh (the study's
first level).  sigma_est is the finest level's peak, or, where the three levels
h_1 > h_2 > h_3 (h = r/n) give a monotone rising sequence with shrinking steps, its
Richardson extrapolation sigma_3 + (sigma_3 - sigma_2) h_3^p / (h_2^p - h_3^p), the order p
solved from (sigma_2 - sigma_1)/(sigma_3 - sigma_2) = (h_1^p - h_2^p)/(h_2^p - h_3^p) in
[P_MIN, P_MAX].  No credit is taken when the peak falls with refinement (k >= 1): the
study's load sets are the peak pin force and the peak torque, not every state of the cycle.
A safety factor (static, overspeed, fatigue, Gough-Pollard) is divided by k -- exact for
the static ones, conservative for Goodman (UR M53's sigma_add does not grow) -- and a
stress limit (counterweight stresses) multiplied by it; groups the study does not follow
(the counterweight bodies, their junctions) keep k = 1.  The worst group after this may be
another than the assessed mesh's; the criterion's location names it and the factor.  Over a
full-load curve the factors apply at every speed and load state (a group's k is the same
at every speed: the study measures the mesh, whose refinement ratio a load's magnitude does
not change), and the criterion is the worst speed again (``assess.criteria.locate``), each
speed's value scaled in ``per_speed``.

The study's own criterion, ``mesh_convergence``: the assessed mesh and the finest level
must agree within the tolerance (5 %) for every load set, else the sign-off fails as not
converged.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

from fe_crank.assess.criteria import locate
from fe_crank.assess.qualifiers import qualified
from fe_crank.assess.shaft import PER_THROW, WHOLE_SHAFT, ShaftAssessment
from fe_crank.assess.verdict import judge
from fe_crank.fe.convergence import COUNTERWEIGHT_PREFIX, OIL_BORE_PREFIX, ConvergenceStudy
from fe_crank.results import CriterionResult
from fe_crank.throw_scope import ALL_THROWS

P_MIN, P_MAX = 0.3, 8.0
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


def richardson(h, s) -> tuple[float, float] | None:
    """(extrapolated value, order p) of three levels h_1 > h_2 > h_3 with peaks s; None when
    the sequence is not monotone with shrinking steps or p falls outside [P_MIN, P_MAX]."""
    if len(s) != 3 or len(h) != 3:
        return None
    d1, d2 = s[1] - s[0], s[2] - s[1]
    if d1 == 0 or d2 == 0 or (d1 > 0) != (d2 > 0) or abs(d2) >= abs(d1):
        return None
    target = d1 / d2

    def f(p):
        return (h[0] ** p - h[1] ** p) / (h[1] ** p - h[2] ** p) - target

    lo, hi = P_MIN, P_MAX
    if f(lo) * f(hi) > 0:
        return None
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if f(lo) * f(mid) <= 0:
            hi = mid
        else:
            lo = mid
    p = 0.5 * (lo + hi)
    return s[2] + d2 * h[2] ** p / (h[1] ** p - h[2] ** p), p


def estimate(study: ConvergenceStudy, name: str) -> tuple[float, str]:
    """(sigma_est / sigma_assessed, the estimate in words) of one load set (module doc)."""
    lv = study.levels
    s = [x.peaks[name] for x in lv]
    h = [1.0 / x.fillet_divisions for x in lv]
    sizes = ", ".join(f"r/{x.fillet_divisions:g}" for x in lv)
    ext = richardson(h, s) if s[-1] > s[0] else None
    if ext is not None:
        return ext[0] / s[0], f"Richardson extrapolation of {sizes}, order {ext[1]:.2f}"
    return s[-1] / s[0], f"finest level r/{lv[-1].fillet_divisions:g} of {sizes}"


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


def surface_factor(studies: dict, throw: str, group: str) -> tuple[float, str, str, float] | None:
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


def refine(
    criteria: tuple[CriterionResult, ...],
    throws,
    studies: dict,
    *,
    sweep: tuple = (),
    overspeed: float | None = None,
    qualifiers: dict[str, str] | None = None,
    shaft: ShaftAssessment | None = None,
) -> tuple[tuple[CriterionResult, ...], tuple[Refinement, ...]]:
    """``criteria`` with the FE stress criteria re-evaluated at the study's estimates
    (module docstring), and the factor each of them ends up at (its governing group's).
    ``throws``, ``sweep``, ``overspeed``, ``qualifiers``: the assessment's (``Assessment``:
    the operating speed's throws, every speed and load state, the overspeed, the verdict
    line's words, the whole-shaft model's results: its throws are meshed as the per-throw
    model's, so a group's k applies to them alike)."""
    cache: dict[tuple[str, str], tuple[float, str, str, float] | None] = {}

    def got(throw: str, group: str):
        if (throw, group) not in cache:
            cache[throw, group] = surface_factor(studies, throw, group)
        return cache[throw, group]

    def factor(throw: str, group: str) -> float:
        f = got(throw, group)
        return 1.0 if f is None else f[0]

    out, made = [], []
    for c in criteria:
        found = (
            locate(c.quantity, c.sense, throws, sweep=sweep, overspeed=overspeed, factor=factor, shaft=shaft)
            if c.quantity in SCALED
            else None
        )
        if found is None:
            out.append(c)
            continue
        value, where, speed_rpm, per_speed = found
        bare = next(
            (where.removeprefix(f"{m}: ") for m in (PER_THROW, WHOLE_SHAFT) if where.startswith(f"{m}: ")), where
        )
        parts = bare.split(", ")  # the throw and the group, without the model's name (with the whole shaft)
        f = got(parts[0].removeprefix("throw "), parts[1]) if len(parts) > 1 else None
        if f is not None:
            r = Refinement(c.name, f[0], SURFACES[_surface(parts[1]) or ""], f[1], f[2], f[3])
            made.append(r)
            where = f"{where}; {r.words}"
        where = qualified(where, (qualifiers or {}).get(c.quantity, ""))
        verdict = judge(
            c.name, c.quantity, c.sense, value, c.limit, unit=c.unit, location=where, description=c.description
        )
        out.append(dataclasses.replace(verdict, per_speed=per_speed, speed_rpm=speed_rpm))
    return tuple(out), tuple(made)


def refined(criteria: tuple[CriterionResult, ...], throws, studies: dict, **assessed) -> tuple[CriterionResult, ...]:
    """``criteria`` taken at the study's estimates (``refine``; ``assessed``: its keywords)."""
    return refine(criteria, throws, studies, **assessed)[0]


def refinements(criteria: tuple[CriterionResult, ...], throws, studies: dict, **assessed) -> tuple[Refinement, ...]:
    """The factor each FE stress criterion is taken at (``refine``; ``assessed``: its keywords)."""
    return refine(criteria, throws, studies, **assessed)[1]


def of_assessment(a) -> dict:
    """``refine``'s keywords from an ``assess.case.Assessment``."""
    return {"sweep": a.sweep, "overspeed": a.overspeed, "qualifiers": a.qualifiers, "shaft": a.shaft}


def criterion(studies: dict[str, ConvergenceStudy]) -> CriterionResult:
    """The verdict's ``mesh_convergence`` criterion: the largest difference of a hot-spot
    peak between the assessed mesh and the finest level, over the load sets and throws,
    must not exceed the tolerance (a "max" criterion; failing it: not converged)."""
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
        location=f"throw {key}, {b.where[name]}, {name}, r/{a.fillet_divisions:g} (assessed) -> "
        f"r/{b.fillet_divisions:g} (finest)" + ("" if st.converged else "; NOT CONVERGED"),
        description="relative difference of the peak von Mises stress on the hot-spot surfaces (shaft and "
        "counterweight fillets, oil-bore outlet) between the assessed mesh and the finest level of the "
        "convergence study (docs/fe.md)",
    )


__all__ = [
    "Refinement",
    "richardson",
    "estimate",
    "surface_factor",
    "refine",
    "refinements",
    "refined",
    "of_assessment",
    "criterion",
]
