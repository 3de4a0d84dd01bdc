"""The checks a reader needs beside the verdict, as ``fe_crank.notes.Note`` objects.

``case_notes(outputs, mesh_plan_preset, solver)`` gathers, for one case:

* the notes the stages' results carry (the dynamics' warnings, the assessment's
  assumptions);
* mesh below the sign-off rule (preset ``test``): "not a sign-off", on every criterion;
* the foundation support model (statically indeterminate, its stresses depend on the
  stated bearing stiffness, docs/fe.md): "not a sign-off", on every criterion;
* the IACS UR M53 averaging check (Appendix III 2.3: unaveraged vs averaged von Mises at
  a fillet's peak within 5 %, computed by the assessment at the hot spot's state), per
  fillet above 5 %, on the FE criteria located at that fillet (``fillet_criteria``; all
  the FE stress criteria when none is: a better-resolved peak there could govern them),
  named on the verdict line;
* the FE stress criteria the hot-spot convergence study sets (``assess.refinement``, the
  assessment's ``refinements``): on each, the factor and the estimate it rests on;
* a counterweight whose built m r differs from the requirement by more than 10 % when
  the load case has no ``unbalance_error`` criterion to judge it;
* an engine without gas pressure (inertia loads only), on the fatigue and M53 criteria
  and the verdict line;
* the fast direct solver unavailable (a slower iterative or sparse-LU path was used).

A note whose ``verdict`` words are set is shown on the verdict line too
(``fe_crank.notes.verdict_remarks``): which verdicts it concerns, not only that it exists.

Notes that differ only in the throws they concern are shown once, naming the throws.
"""

from __future__ import annotations

from collections.abc import Collection, Iterable

from fe_crank.assess.case import Assessment
from fe_crank.notes import ASSUMPTION, NOT_A_SIGN_OFF, WARNING, Note, from_strings, grouped
from fe_crank.outputs import CaseOutputs
from fe_crank.records import SolverRecord

#: UR M53 Appendix III 2.3: averaged and unaveraged fillet stress within 5 %
AVERAGING_LIMIT = 0.05
#: counterweight m r off the requirement by more than this is flagged (no criterion set)
UNBALANCE_FLAG = 0.10

#: the criteria read from the FE stresses of the check's own mesh at the shaft fillets
FE_STRESS_QUANTITIES = ("static_safety", "fatigue_safety", "gough_pollard_safety", "overspeed_safety")
FATIGUE_QUANTITIES = ("fatigue_safety", "gough_pollard_safety", "m53_acceptability")


def _names(assessment: Assessment | None, quantities: Collection[str]) -> tuple[str, ...]:
    if assessment is None:
        return ()
    return tuple(c.name for c in assessment.criteria if c.quantity in quantities)


def fillet_criteria(assessment: Assessment, fillet: str, throws: Collection[str]) -> tuple[str, ...]:
    """The FE stress criteria whose governing location (``CriterionResult.where``, in
    either model) is the FE group ``fillet`` of one of ``throws``."""
    return tuple(
        c.name
        for c in assessment.criteria
        if c.quantity in FE_STRESS_QUANTITIES
        and c.where is not None
        and c.where.kind == "group"
        and c.where.group == fillet
        and c.where.throw in throws
    )


def _short(names: Iterable[str]) -> str:
    return ", ".join(n.split(".")[-1] for n in names)


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
                verdict=f"{NOT_A_SIGN_OFF}: test mesh (preset '{preset}')",
            )
        )
    lc = out.loadcase
    if lc is not None and lc.fe.support == "foundation":
        notes.append(
            Note(
                "NOT A SIGN-OFF: support = 'foundation' (journals on a radial Winkler foundation of the stated "
                "stiffness): statically indeterminate, the fillet stresses depend on the bearing stiffness; "
                "a study beside the determinate supports, not a sign-off (docs/fe.md)",
                WARNING,
                (),
                "fe",
                verdict=f"{NOT_A_SIGN_OFF}: foundation support",
            )
        )
    for st in a.states if a is not None else ():
        for g, v in st.averaging.items():
            if abs(v) > AVERAGING_LIMIT and a is not None:
                located = fillet_criteria(a, g, st.throws)
                concerns = located or _names(a, FE_STRESS_QUANTITIES)
                text = (
                    f"UR M53 averaging check failed at {g}: unaveraged vs averaged von Mises {100 * v:+.1f} % "
                    "> 5 %; refine the fillet mesh"
                )
                if located:
                    text += f" (the governing location of {_short(located)})"
                elif concerns:
                    text += " (no criterion's governing location: a better-resolved peak there could govern)"
                notes.append(
                    Note(
                        text,
                        WARNING,
                        concerns,
                        "fe quality",
                        tuple(st.keys),
                        verdict=f"averaging check failed at {g} ({100 * v:+.0f} %): concerns {_short(concerns)}"
                        if concerns
                        else "",
                    )
                )
    for r in a.refinements if a is not None else ():
        notes.append(
            Note(
                f"{r.criterion.split('.')[-1]} taken at the convergence study's estimate of the converged peak, "
                f"not the assessed mesh's: {r.words} (no credit when the peak falls with refinement; docs/fe.md)",
                ASSUMPTION,
                (r.criterion,),
                "convergence",
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
    if lc is not None and lc.engine.gas is None:
        fatigue = _names(a, FATIGUE_QUANTITIES)
        notes.append(
            Note(
                "inertia loads only: the engine has no gas pressure, so firing loads are missing "
                "(not a full fatigue check)",
                WARNING,
                fatigue,
                "dynamics",
                verdict=f"inertia loads only (no gas pressure): concerns {_short(fatigue)}" if fatigue else "",
            )
        )
    if solver is not None and not solver.fast_available:
        notes.append(
            Note(
                f"the fast direct solver (MKL PARDISO: pypardiso, a dependency on x86-64 only) is not available; "
                f"solved with {', '.join(solver.used or ('?',))} (same results, slower)",
                WARNING,
                (),
                "fe",
            )
        )
    return tuple(grouped(notes))
