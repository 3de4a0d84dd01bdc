"""The checks a reader needs beside the verdict, as ``fe_crank.notes.Note`` objects.

``case_notes(stage_out, provenance)`` gathers, for one case:

* the notes every stage output carries (``notes.from_stage``: dynamics warnings,
  the assessment's assumptions, and whatever other stages add);
* mesh below the sign-off rule (preset ``test``): "not a sign-off", on every criterion;
* the IACS UR M53 averaging check (Appendix, FE calculation of SCFs: unaveraged vs
  averaged von Mises at a fillet's peak within 5 %), per fillet above 5 %, on the
  stress, fatigue and M53 criteria;
* a counterweight whose built m r differs from the requirement by more than 10 % when
  the load case has no ``unbalance_error`` criterion to judge it;
* an engine without gas pressure (inertia loads only), on the fatigue criteria;
* the fast direct solver unavailable (a slower iterative or sparse-LU path was used).
"""

from __future__ import annotations

from fe_crank.notes import WARNING, Note, from_stage, unique
from fe_crank.report.fields import critical
from fe_crank.report.superposed import angle_index, assessed_dynamics, field_at_angle

#: UR M53 Appendix (FE): averaged and unaveraged fillet stress within 5 %
AVERAGING_LIMIT = 0.05
#: counterweight m r off the requirement by more than this is flagged (no criterion set)
UNBALANCE_FLAG = 0.10

FILLETS = ("crankpin_fillet_1", "crankpin_fillet_2", "journal_fillet_1", "journal_fillet_2")
STRESS_QUANTITIES = ("static_safety", "fatigue_safety", "gough_pollard_safety", "m53_acceptability", "overspeed_safety")
FATIGUE_QUANTITIES = ("fatigue_safety", "gough_pollard_safety", "m53_acceptability")


def _names(assessment, quantities) -> tuple[str, ...]:
    return tuple(c.name for c in getattr(assessment, "criteria", ()) if c.quantity in quantities)


def averaging(stage_out: dict) -> dict[str, dict[str, float]]:
    """UR M53 averaging indicator per FE model key and fillet at the hot-spot angle
    (cached in ``stage_out["averaging"]``; the report's quality table shows it)."""
    if "averaging" in stage_out:
        return stage_out["averaging"]
    out: dict[str, dict[str, float]] = {}
    units_by_key, a, lc = (stage_out.get(k) for k in ("units", "assessment", "loadcase"))
    dyn = assessed_dynamics(stage_out)
    if units_by_key and a is not None and dyn is not None:
        done: dict[int, dict[str, float]] = {}
        for key, units in units_by_key.items():
            if id(units) in done:
                out[key] = done[id(units)]
                continue
            fillets = [g for g in FILLETS if g in (units.mesh.boundaries or {})]
            keys = [k for k, u in units_by_key.items() if u is units]
            crit = critical(a, keys, dyn)
            if not fillets or crit is None:
                continue
            u = field_at_angle(units, dyn, lc, crit.throw, angle_index(dyn, crit.angle))
            out[key] = done[id(units)] = {g: float(v) for g, v in units.averaging_indicator(u, fillets).items()}
    stage_out["averaging"] = out
    return out


def case_notes(stage_out: dict, provenance: dict | None = None) -> list[Note]:
    """Every note of the case, in order: stage notes first, then the checks above."""
    notes: list[Note] = []
    for name in ("loadcase", "dynamics", "balance", "meshes", "units", "assessment"):
        obj = stage_out.get(name)
        if obj is not None and not isinstance(obj, dict):
            notes += from_stage(name, obj)
    a = stage_out.get("assessment")
    prov = provenance or {}
    mesh = prov.get("mesh") or {}
    if mesh.get("preset") and not mesh.get("sign_off"):
        notes.append(
            Note(
                f"NOT A SIGN-OFF: mesh preset '{mesh['preset']}' is below the sign-off rule "
                f"({mesh.get('sign_off_rule', 'coarse or finer')}); use --mesh-size coarse",
                WARNING,
                (),
                "mesh",
            )
        )
    for key, ind in averaging(stage_out).items():
        for g, v in ind.items():
            if abs(v) > AVERAGING_LIMIT:
                notes.append(
                    Note(
                        f"UR M53 averaging check failed at {g} (throw {key}): unaveraged vs averaged "
                        f"von Mises {100 * v:+.1f} % > 5 %; refine the fillet mesh",
                        WARNING,
                        _names(a, STRESS_QUANTITIES),
                        "fe quality",
                    )
                )
    lc = stage_out.get("loadcase")
    has_unbalance = any(c.quantity == "unbalance_error" for c in getattr(a, "criteria", ()))
    for t in getattr(a, "throws", ()):
        for c in t.counterweights:
            err = c.unbalance_error
            if err is not None and abs(err) > UNBALANCE_FLAG and not has_unbalance:
                notes.append(
                    Note(
                        f"throw {t.name}, {c.name}: built m r differs from the required by "
                        f"{100 * err:+.0f} % (no unbalance_error criterion in the load case checks it)",
                        WARNING,
                        (),
                        "counterweights",
                    )
                )
    engine = getattr(lc, "engine", None)
    if engine is not None and getattr(engine, "gas", None) is None and not any("gas" in n.text for n in notes):
        notes.append(
            Note(
                "inertia loads only: the engine has no gas pressure, so firing loads are missing "
                "(not a full fatigue check)",
                WARNING,
                _names(a, FATIGUE_QUANTITIES) or (),
                "dynamics",
            )
        )
    solver = prov.get("solver") or {}
    if solver and not solver.get("fast_available"):
        notes.append(
            Note(
                f"the fast direct solver (MKL PARDISO, pip install 'fe-crank[fast]') is not available; "
                f"solved with {', '.join(solver.get('used') or ['?'])} (same results, slower)",
                WARNING,
                (),
                "fe",
            )
        )
    return unique(notes)
