"""Warnings and assumptions that travel with a verdict.

A ``Note`` is one sentence a reader of the verdict must see: a quality warning (the
mesh is below the sign-off rule, the UR M53 averaging check failed, a counterweight
m r differs from the requirement, the fast solver was unavailable) or an unchecked
assumption (inertia loads only, support model).  ``criteria`` names the criteria it
concerns (their load-case keys, e.g. ``"criteria.min_fatigue_safety"`` or the short
``"min_fatigue_safety"``); empty means the whole case.  ``throws`` names the throws it
concerns (empty: not one throw's); notes that differ only in their throws are shown
once with all of them (``grouped``).

Stages add notes to their own results (the dynamics' ``warnings``, the assessment's
``notes``); ``fe_crank.pipeline.notes`` adds the checks of the outputs themselves and
groups them.  The report shows each note beside the criteria it concerns, results.json
lists them under ``warnings``, the JUnit XML under the test cases they concern.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from fe_crank.throw_scope import ALL_THROWS, ThrowScope

WARNING, ASSUMPTION = "warning", "assumption"
#: how a note that keeps a verdict from being a sign-off starts its verdict-line words
NOT_A_SIGN_OFF = "not a sign-off"


@dataclass(frozen=True)
class Note:
    text: str
    level: str = WARNING  # "warning" | "assumption"
    criteria: tuple[str, ...] = ()  # criterion names it concerns; () = the whole case
    source: str = ""  # the stage or check that raised it
    throws: tuple[str, ...] = ()  # the throws it concerns; () = not one throw's
    verdict: str = ""  # the words shown on the verdict line ("" = shown beside its criteria only)

    @property
    def display(self) -> str:
        """The sentence as shown: prefixed with the throws it concerns."""
        if not self.throws:
            return self.text
        if any(isinstance(t, ThrowScope) for t in self.throws):  # a model standing for every throw
            return f"{ALL_THROWS}: {self.text}"
        names = ", ".join(str(t) for t in self.throws)
        return f"{'throw' if len(self.throws) == 1 else 'throws'} {names}: {self.text}"

    def concerns(self, criterion: str) -> bool:
        """True when the note is case-wide or names ``criterion`` (full or short key)."""
        if not self.criteria:
            return True
        short = criterion.split(".")[-1]
        return any(c == criterion or c.split(".")[-1] == short for c in self.criteria)

    def to_dict(self) -> dict:
        return {
            "level": self.level,
            "text": self.display,
            "criteria": list(self.criteria),
            "source": self.source,
            "throws": [str(t) for t in self.throws],
        }


def from_strings(texts, level: str, source: str) -> list[Note]:
    """Notes of a stage result that holds plain sentences (or ``Note`` objects)."""
    return [t if isinstance(t, Note) else Note(t, level, (), source) for t in texts if t]


def grouped(notes) -> list[Note]:
    """Notes in order, each sentence once per level and criteria; notes that
    differ only in their throws become one note naming all of them (in first-seen order)."""
    out: list[Note] = []
    index: dict[tuple, int] = {}
    for n in notes:
        key = (n.text, n.level, n.criteria, bool(n.throws))
        if key not in index:
            index[key] = len(out)
            out.append(n)
            continue
        i = index[key]
        extra = tuple(t for t in n.throws if t not in out[i].throws)
        if extra:
            out[i] = replace(out[i], throws=out[i].throws + extra)
    return out


def blocks_sign_off(note: Note) -> bool:
    """The note says the verdict is not a sign-off (test mesh, a foundation support)."""
    return note.verdict.startswith(NOT_A_SIGN_OFF)


def verdict_remarks(notes) -> str:
    """The words the verdict line carries after PASS/FAIL: the verdict-line words of the
    notes (``Note.verdict``), the not-a-sign-off ones first, each once, "; " between."""
    seen: list[str] = []
    for n in sorted((n for n in notes if n.verdict), key=lambda n: not blocks_sign_off(n)):
        if n.verdict not in seen:
            seen.append(n.verdict)
    return "; ".join(seen)
