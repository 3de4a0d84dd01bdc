"""The hot-spot convergence study's levels and result (``ConvergenceLevel``,
``ConvergenceStudy``), its constants, and the peaks of one level (``level_peaks``): shared
by the full re-meshed study (``fe.refinement.convergence``) and the study by zones
(``fe.refinement.zone_study``).  The method and its criteria: ``fe.refinement.convergence``'s docstring."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from fe_crank.fe.throw.surface_peaks import COUNTERWEIGHT_FILLETS, OIL_BORE, peak_fillet_stresses
from fe_crank.fe.throw.unit_cases import UnitSolutions

FACTORS = (1.0, 1.5, 2.0)
TOLERANCE = 0.05
#: the orders of convergence a Richardson extrapolation may take (``richardson``)
P_MIN, P_MAX = 0.3, 8.0
#: the peak on the counterweight fillets under load set X is the entry "counterweight fillets, X"
COUNTERWEIGHT_PREFIX = "counterweight fillets, "
#: ... and on the oil bore's surface the entry "oil bore, X"
OIL_BORE_PREFIX = "oil bore, "


@dataclass(frozen=True)
class ConvergenceLevel:
    """One mesh of the study: its fillet size and the peak fillet stress of each load set."""

    fillet_divisions: float  # fillet element edge = r / fillet_divisions
    n_dof: int
    fillet_max_edge: dict[str, float]  # m, longest triangle edge on each fillet (mesh statistics)
    peaks: dict[str, float]  # load set -> peak von Mises on the fillets, Pa (and the
    # counterweight fillets' entries, COUNTERWEIGHT_PREFIX)
    where: dict[str, str]  # load set -> fillet of the peak
    seconds: float
    reused: bool = False  # the check's own mesh and solution (no mesh, no solve)
    bore_divisions: float = 6.0  # oil-bore elements: pi d / (2 bore_divisions) round its circumference
    zones: int = 0  # hot-spot zones solved for this level (``fe.refinement.zone_study``); 0: the whole throw


@dataclass(frozen=True)
class ConvergenceStudy:
    """Levels coarse -> fine, the relative change of the last step per load set, the verdict."""

    levels: tuple[ConvergenceLevel, ...]
    loads: dict[str, dict[str, float]]
    tolerance: float
    changes: dict[str, list[float]] = field(default_factory=dict)  # load set -> change of each step
    method: str = "full"  # "full": the whole throw re-meshed per level; "zones": hot-spot submodels
    zone_radius: float = 0.0  # zones: ball radius / the hot spot's fillet radius

    @property
    def change(self) -> float:
        """Largest relative change of the last refinement over the load sets."""
        return max(c[-1] for c in self.changes.values())

    @property
    def assessed_changes(self) -> dict[str, float]:
        """Load set -> |finest - assessed| / finest (the first level is the assessed mesh)."""
        a, b = self.levels[0], self.levels[-1]
        return {name: abs(b.peaks[name] - a.peaks[name]) / b.peaks[name] for name in self.changes}

    @property
    def assessed_change(self) -> float:
        """Largest difference between the assessed mesh and the finest level over the load sets."""
        return max(self.assessed_changes.values())

    @property
    def converged(self) -> bool:
        return bool(self.assessed_change <= self.tolerance)

    def to_dict(self) -> dict:
        """The ``mesh_convergence`` entry of results.json (SI: Pa, m)."""
        return {
            "levels": [lv.fillet_divisions for lv in self.levels],
            "fillet_size": [f"r/{lv.fillet_divisions:g}" for lv in self.levels],
            "bore_divisions": [lv.bore_divisions for lv in self.levels],
            "n_dof": [lv.n_dof for lv in self.levels],
            "method": self.method,
            "zones": [lv.zones for lv in self.levels],
            "zone_radius": self.zone_radius,
            "peaks": {name: [lv.peaks[name] for lv in self.levels] for name in self.changes},
            "where": {name: [lv.where[name] for lv in self.levels] for name in self.changes},
            "loads": self.loads,
            "changes": self.changes,
            "change": self.change,
            "assessed_changes": self.assessed_changes,
            "assessed_change": self.assessed_change,
            "tolerance": self.tolerance,
            "converged": self.converged,
        }


def level_peaks(unit_solutions: UnitSolutions, fields: dict[str, np.ndarray]) -> dict[str, tuple[float, str]]:
    """{entry: (peak, surface)} of one level: the shaft fillets under each load set, and the
    counterweight fillets' and the oil bore's entries where the mesh has them."""
    got = peak_fillet_stresses(unit_solutions, fields)
    if any(n in (unit_solutions.mesh.boundaries or {}) for n in COUNTERWEIGHT_FILLETS):
        cw = peak_fillet_stresses(unit_solutions, fields, COUNTERWEIGHT_FILLETS)
        got.update({COUNTERWEIGHT_PREFIX + name: v for name, v in cw.items()})
    if OIL_BORE[0] in (unit_solutions.mesh.boundaries or {}):
        bore = peak_fillet_stresses(unit_solutions, fields, OIL_BORE)
        got.update({OIL_BORE_PREFIX + name: v for name, v in bore.items()})
    return got


__all__ = [
    "COUNTERWEIGHT_PREFIX",
    "FACTORS",
    "OIL_BORE_PREFIX",
    "P_MAX",
    "P_MIN",
    "TOLERANCE",
    "ConvergenceLevel",
    "ConvergenceStudy",
    "level_peaks",
]
