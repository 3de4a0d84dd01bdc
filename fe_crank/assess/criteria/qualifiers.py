"""What a criterion's number is, stated on its verdict line: words appended to the
criterion's remarks (``criteria.judge_criteria``'s ``qualifiers``), so that the report's
row, results.json, the JUnit case and case.json all carry them.

* UR M53 on a machine that is not an internal-combustion engine (an air motor, a
  compressor: outside the rule's scope, "Calculation of crankshafts for I.C. engines"):
  "UR M53 by analogy: not an internal-combustion engine" (``M53Basis.analogy``);
* UR M53 with the quasi-static journal torque accepted in place of the forced-vibration
  calculation of UR M53 2.2 (``[criteria] m53_quasi_static_torque`` without a ``[torsion]``
  section; any number of cylinders): "not UR M53-conform (quasi-static torque)".
"""

from __future__ import annotations

from fe_crank.io.criteria import Criteria
from fe_crank.rules.m53.basis import M53Basis

ANALOGY = "UR M53 by analogy: not an internal-combustion engine"
QUASI_STATIC = "not UR M53-conform (quasi-static torque)"


def criterion_qualifiers(basis: M53Basis, criteria: Criteria, *, torsion: bool) -> dict[str, str]:
    """quantity -> the words its verdict line carries (module docstring); ``basis`` an
    ``m53_basis.M53Basis``, ``criteria`` the load case's ``Criteria``, ``torsion``: the
    journal torques carry the torsional stage's vibratory torque."""
    m53 = []
    if basis.analogy:
        m53.append(ANALOGY)
    if criteria.m53_quasi_static_torque and not torsion:
        m53.append(QUASI_STATIC)
    return {"m53_acceptability": "; ".join(m53)} if m53 else {}


def qualified(location: str, words: str) -> str:
    """``location`` with ``words`` appended ("; " between them)."""
    if not words:
        return location
    return f"{location}; {words}" if location else words


__all__ = ["ANALOGY", "QUASI_STATIC", "criterion_qualifiers", "qualified"]
