"""Warnings and assumptions that travel with a verdict.

A ``Note`` is one sentence a reader of the verdict must see: a quality warning (the
mesh is below the sign-off rule, the UR M53 averaging check failed, a counterweight
m r differs from the requirement, the fast solver was unavailable) or an unchecked
assumption (inertia loads only, support model).  ``criteria`` names the criteria it
concerns (their load-case keys, e.g. ``"criteria.min_fatigue_safety"`` or the short
``"min_fatigue_safety"``); empty means the whole case.

Any stage may add notes: a stage output (an object in the pipeline's ``stage_out``)
with an attribute ``notes`` or ``warnings`` holding strings or ``Note`` objects
contributes them (strings become case-wide notes of that stage, level "assumption"
for ``notes`` and "warning" for ``warnings``); ``fe_crank.report.quality`` adds the
checks of the outputs themselves.  The report shows each note beside the criteria it
concerns, results.json lists them under ``warnings``, JUnit in each test's output.
"""

from __future__ import annotations

from dataclasses import dataclass

WARNING, ASSUMPTION = "warning", "assumption"


@dataclass(frozen=True)
class Note:
    text: str
    level: str = WARNING  # "warning" | "assumption"
    criteria: tuple[str, ...] = ()  # criterion names it concerns; () = the whole case
    source: str = ""  # the stage or check that raised it

    def concerns(self, criterion: str) -> bool:
        """True when the note is case-wide or names ``criterion`` (full or short key)."""
        if not self.criteria:
            return True
        short = criterion.split(".")[-1]
        return any(c == criterion or c.split(".")[-1] == short for c in self.criteria)

    def to_dict(self) -> dict:
        return {"level": self.level, "text": self.text, "criteria": list(self.criteria), "source": self.source}


def from_stage(name: str, obj) -> list[Note]:
    """The notes a stage output carries (see the module docstring)."""
    out: list[Note] = []
    for attr, level in (("warnings", WARNING), ("notes", ASSUMPTION)):
        for n in getattr(obj, attr, None) or ():
            if isinstance(n, Note):
                out.append(n)
            elif isinstance(n, str) and n:
                out.append(Note(n, level, (), name))
    return out


def unique(notes) -> list[Note]:
    """Notes in order, each text once per level and criteria."""
    seen, out = set(), []
    for n in notes:
        key = (n.text, n.level, n.criteria)
        if key not in seen:
            seen.add(key)
            out.append(n)
    return out
