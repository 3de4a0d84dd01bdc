"""The checks a reader needs beside the verdict, as ``fe_crank.notes.Note`` objects.

``case_notes(outputs, mesh_plan_preset, solver)`` gathers, for one case:

* the notes the stages' results carry (the dynamics' warnings, the assessment's
  assumptions);
* mesh below the sign-off rule (preset ``test``): "not a sign-off", on every criterion;
* the IACS UR M53 averaging check (Appendix III 2.3: unaveraged vs averaged von Mises at
  a fillet's peak within 5 %, computed by the assessment at the hot spot's state), per
  fillet above 5 %, on the stress, fatigue and M53 criteria;
* a counterweight whose built m r differs from the requirement by more than 10 % when
  the load case has no ``unbalance_error`` criterion to judge it;
* an engine without gas pressure (inertia loads only), on the fatigue criteria;
* the fast direct solver unavailable (a slower iterative or sparse-LU path was used).

Notes that differ only in the throws they concern are shown once, naming the throws.
"""

from __future__ import annotations

from fe_crank.assess.case import Assessment
from fe_crank.notes import WARNING, Note, from_strings, grouped
from fe_crank.outputs import CaseOutputs
from fe_crank.records import SolverRecord

#: UR M53 Appendix III 2.3: averaged and unaveraged fillet stress within 5 %
AVERAGING_LIMIT = 0.05
#: counterweight m r off the requirement by more than this is flagged (no criterion set)
UNBALANCE_FLAG = 0.10

STRESS_QUANTITIES = (
    "static_safety",
    "fatigue_safety",
    "gough_pollard_safety",
    "m53_acceptability",
    "overspeed_safety",
)
FATIGUE_QUANTITIES = ("fatigue_safety", "gough_pollard_safety", "m53_acceptability")


def _names(assessment: Assessment | None, quantities) -> tuple[str, ...]:
    if assessment is None:
        return ()
    return tuple(c.name for c in assessment.criteria if c.quantity in quantities)


def case_notes(
    out: CaseOutputs, *, preset: str | None, sign_off: bool, rule: str, solver: SolverRecord | None
) -> tuple[Note, ...]:
    """Every note of the case, in order: stage notes first, then the checks above."""
    notes: list[Note] = []
    if out.cycles is not None:
        notes += from_strings(out.cycles.operating.warnings, WARNING, "dynamics")
    a = out.assessment
    if a is not None:
        notes += list(a.notes)
    if preset and not sign_off:
        notes.append(
            Note(
                f"NOT A SIGN-OFF: mesh preset '{preset}' is below the sign-off rule ({rule}); use --mesh-size coarse",
                WARNING,
                (),
                "mesh",
            )
        )
    for st in a.states if a is not None else ():
        for g, v in st.averaging.items():
            if abs(v) > AVERAGING_LIMIT:
                notes.append(
                    Note(
                        f"UR M53 averaging check failed at {g}: unaveraged vs averaged von Mises {100 * v:+.1f} % "
                        "> 5 %; refine the fillet mesh",
                        WARNING,
                        _names(a, STRESS_QUANTITIES),
                        "fe quality",
                        tuple(st.keys),
                    )
                )
    has_unbalance = a is not None and any(c.quantity == "unbalance_error" for c in a.criteria)
    for t in a.throws if a is not None else ():
        for c in t.counterweights:
            err = c.unbalance_error
            if err is not None and abs(err) > UNBALANCE_FLAG and not has_unbalance:
                notes.append(
                    Note(
                        f"the built m r of {c.name} differs from the required by {100 * err:+.0f} % "
                        "(no unbalance_error criterion in the load case checks it)",
                        WARNING,
                        (),
                        "counterweights",
                        (t.name,),
                    )
                )
    lc = out.loadcase
    if lc is not None and lc.engine.gas is None and not any("gas" in n.text for n in notes):
        notes.append(
            Note(
                "inertia loads only: the engine has no gas pressure, so firing loads are missing "
                "(not a full fatigue check)",
                WARNING,
                _names(a, FATIGUE_QUANTITIES),
                "dynamics",
            )
        )
    if solver is not None and not solver.fast_available:
        notes.append(
            Note(
                f"the fast direct solver (MKL PARDISO, pip install 'fe-crank[fast]') is not available; "
                f"solved with {', '.join(solver.used or ('?',))} (same results, slower)",
                WARNING,
                (),
                "fe",
            )
        )
    return tuple(grouped(notes))
