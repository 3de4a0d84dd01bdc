"""One call for the whole balance stage: free forces, counterweights, sectors, shafts."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from fe_crank.balance.counterweights import BalanceStrategy, CounterweightDesign, size_counterweights
from fe_crank.balance.forces import REPORTED_ORDERS, FreeForces, free_forces
from fe_crank.balance.sector import SectorProperties, solve_sector
from fe_crank.balance.shafts import BalanceShaftDesign, balance_shafts
from fe_crank.errors import InputError
from fe_crank.model import Engine

SOURCE_GROUPS = ("rotating", "reciprocating", "yoke", "counterweights", "balance_shafts")


@dataclass(frozen=True)
class BalanceResult:
    engine: str
    speed: float
    forces: FreeForces
    design: CounterweightDesign
    sectors: tuple[SectorProperties | None, ...]  # one per counterweight
    shafts: tuple[BalanceShaftDesign, ...]
    residual: FreeForces  # after counterweights and balance shafts


def analyse_balance(engine: Engine, speed: float, settings=None) -> BalanceResult:
    """Free forces, counterweights (and their annular sectors), balance shafts, residual.

    ``settings`` is a ``fe_crank.io.balance.BalanceSettings`` or ``None`` (rotating masses
    balanced per throw, nothing else).
    """
    strategy = settings.strategy if settings is not None else BalanceStrategy()
    ref_z = settings.reference_z if settings is not None else 0.0
    forces = free_forces(engine, speed, reference_z=ref_z)
    design = size_counterweights(engine, strategy, speed, forces=forces)
    sectors: list[SectorProperties | None] = []
    spec = settings.counterweight if settings is not None else None
    for i, cw in enumerate(design.counterweights):
        if spec is None or cw.unbalance <= 0.0:
            sectors.append(None)
            continue
        sectors.append(
            solve_sector(
                cw.unbalance,
                free=spec.free,
                r_outer=spec.r_outer,
                r_inner=spec.r_inner,
                thickness=spec.thickness,
                angle=spec.angle,
                density=spec.density,
                envelope=spec.envelope,
                journal_radius=spec.journal_radius,
                key=f"balance.counterweight (plane {i + 1}, z = {cw.z * 1e3:.4g} mm, shaft {cw.shaft!r})",
            )
        )
    residual = design.residual
    shaft_designs = []
    ref_sense = engine.shafts[0].sense
    for i, req in enumerate(settings.shafts if settings is not None else ()):
        try:
            d = balance_shafts(
                residual,
                req.component,
                req.order,
                reference_sense=ref_sense,
                offset=req.offset,
                span=req.span,
                positions=req.positions,
            )
        except InputError as exc:
            if exc.key != "balance.shafts.positions":
                raise
            raise InputError(exc.reason, key=f"balance.shafts[{i}].positions") from None
        shaft_designs.append(d)
        residual = d.residual
    return BalanceResult(engine.name, speed, forces, design, tuple(sectors), tuple(shaft_designs), residual)


def _term_dict(ff: FreeForces, order: float, sources) -> dict:
    t = ff.total(order, sources)
    fh, mh = t.force_hodograph(), t.moment_hodograph()
    return {
        "order": order,
        "force": fh.as_dict(),
        "moment": {**mh.as_dict(), "mz": {"cos": float(t.moment[2, 0]), "sin": float(t.moment[2, 1])}},
    }


def forces_table(ff: FreeForces, orders=REPORTED_ORDERS) -> list[dict]:
    """Rows (source, order, force amplitude, moment amplitude, hodograph kinds)."""
    rows = []
    groups = [(s, (s,)) for s in ff.sources] + [("total", None)]
    for name, srcs in groups:
        for k in sorted(set(orders) | ({1.0} if name in ("rotating", "counterweights", "yoke") else set())):
            t = ff.total(k, srcs)
            fh, mh = t.force_hodograph(), t.moment_hodograph()
            if name != "total" and fh.major == 0.0 and mh.major == 0.0:
                continue
            rows.append(
                {
                    "source": name,
                    "order": k,
                    "force_max": fh.major,
                    "force_min": fh.minor,
                    "force_kind": fh.kind,
                    "force_tilt_deg": math.degrees(fh.tilt),
                    "moment_max": mh.major,
                    "moment_min": mh.minor,
                    "moment_kind": mh.kind,
                }
            )
    return rows


def exact_peak(ff: FreeForces, sources=("reciprocating",)) -> dict:
    """Largest force and couple magnitude over a revolution, all orders summed."""
    th = np.linspace(0.0, 2.0 * np.pi, 721)
    f, m = ff.evaluate(th, sources=sources)
    return {"force_max": float(np.hypot(f[:, 0], f[:, 1]).max()), "moment_max": float(np.hypot(m[:, 0], m[:, 1]).max())}


def result_to_dict(res: BalanceResult) -> dict:
    """JSON-ready summary (SI units; angles in degrees as the keys say)."""

    def by_source(ff: FreeForces) -> dict:
        out = {}
        for s in ff.sources:
            out[s] = [
                _term_dict(ff, k, (s,))
                for k in REPORTED_ORDERS
                if ff.total(k, (s,)).force.any() or ff.total(k, (s,)).moment.any()
            ]
        out["total"] = [_term_dict(ff, k, None) for k in REPORTED_ORDERS]
        return out

    return {
        "engine": res.engine,
        "speed_rad_s": res.speed,
        "reference_z_m": res.forces.reference_z,
        "free_forces": by_source(res.forces),
        "exact_reciprocating": exact_peak(res.forces),
        "strategy": {
            "rotating_fraction": res.design.strategy.rotating_fraction,
            "reciprocating_fraction": res.design.strategy.reciprocating_fraction,
            "couple": res.design.strategy.couple,
            "planes_m": list(res.design.strategy.planes),
        },
        "counterweights": [
            {
                "shaft": c.shaft,
                "z_m": c.z,
                "unbalance_kg_m": c.unbalance,
                "angle_deg": math.degrees(c.angle),
                "angle_on_shaft_deg": math.degrees(c.angle_on_shaft),
                "sector": s.as_dict() if s is not None else None,
            }
            for c, s in zip(res.design.counterweights, res.sectors)
        ],
        "balance_shafts": [
            {
                "component": d.component,
                "order": d.order,
                "shafts": [
                    {
                        "name": s.name,
                        "speed_ratio": s.speed_ratio,
                        "unbalance_kg_m": s.unbalance,
                        "angle_deg": math.degrees(s.angle),
                        "z_m": list(s.z),
                        "position_m": list(s.position),
                        "on_crankshaft": s.on_crankshaft,
                        "constraint": s.constraint,
                    }
                    for s in d.shafts
                ],
                "roll_moment_n_m": d.roll_moment,
            }
            for d in res.shafts
        ],
        "residual": by_source(res.residual)["total"],
    }
