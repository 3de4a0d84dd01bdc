"""Firing order and firing offsets of an engine file, and their agreement.

An engine states when each cylinder fires in one or both of two ways:

* ``firing_order = ["1", "3", "4", "2"]`` (every cylinder once): alone, the cylinders
  fire in this order evenly spaced over the cycle (720 deg / n four-stroke,
  360 deg / n two-stroke);
* ``firing_offset`` per cylinder: the cycle angle of its firing TDC (uneven firing,
  V engines with odd firing intervals).

When both are given the offsets are used and the order must be theirs: counted from
the first cylinder of ``firing_order``, the offsets (modulo the cycle) must not decrease
along the stated order.  Cylinders that fire at the same angle may be listed in either
order.  A file whose label and offsets disagree is refused with both orders: the
torsional excitation depends on the order (docs/torsion.md), not only on the set of
angles, so a label that contradicts the offsets is not cosmetic.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from fe_crank.errors import InputError

#: two offsets closer than this (rad) fire "at the same angle"
SAME_ANGLE = 1e-9


def order_of_offsets(offsets: dict[str, float], cycle: float, first: str | None = None) -> list[str]:
    """Cylinder names in the order they fire: sorted by offset modulo ``cycle``, counted
    from ``first`` (default: the cylinder with the smallest offset); ties keep the
    order of ``offsets``."""
    names = list(offsets)
    start = offsets[first] if first is not None else min(v % cycle for v in offsets.values())
    return sorted(names, key=lambda n: _rel(offsets[n], start, cycle))


def _rel(offset: float, start: float, cycle: float) -> float:
    r = (offset - start) % cycle
    return 0.0 if r > cycle - SAME_ANGLE else r


def _text(order: Sequence[str], offsets: dict[str, float]) -> str:
    return "-".join(order) + " (" + ", ".join(f"{n} at {math.degrees(offsets[n]):.6g} deg" for n in order) + ")"


def firing_offsets(
    names: Sequence[str],
    order: Sequence[str] | None,
    given: dict[str, float | None],
    cycle: float,
    *,
    file: str,
    key: str,
) -> dict[str, float]:
    """The firing offset (rad) of every cylinder in ``names`` (module docstring).

    ``order`` the file's ``firing_order`` (or None), ``given`` each cylinder's
    ``firing_offset`` (None where the file gives none); ``key`` the firing order's key
    (``firing_order`` or ``engine.firing_order``).  Raises InputError naming the file,
    the key and, on a disagreement, both orders."""
    stated = {n: v for n, v in given.items() if v is not None}
    if order is None:
        return {n: given.get(n) or 0.0 for n in names}
    for j, n in enumerate(order):
        if n not in names:
            raise InputError(
                f"names cylinder {n!r}, which does not exist (cylinders: {list(names)})", file=file, key=f"{key}[{j}]"
            )
    if sorted(order) != sorted(names):
        missing = sorted(set(names) - set(order))
        twice = sorted({n for n in order if list(order).count(n) > 1})
        raise InputError(
            f"must name every cylinder exactly once (missing: {missing}, named twice: {twice})", file=file, key=key
        )
    if not stated:
        return {n: j * cycle / len(names) for j, n in enumerate(order)}
    if len(stated) != len(names):
        missing = [n for n in names if n not in stated]
        raise InputError(
            f"a firing_order and firing offsets for only some cylinders: give every cylinder its "
            f"firing_offset or none (missing for {missing})",
            file=file,
            key=key,
        )
    start = stated[order[0]]
    rel = [_rel(stated[n], start, cycle) for n in order]
    if any(b < a - SAME_ANGLE for a, b in zip(rel, rel[1:], strict=False)):
        fired = order_of_offsets(stated, cycle, first=order[0])
        raise InputError(
            f"firing order {'-'.join(order)} contradicts the cylinders' firing_offset, which fire "
            f"{_text(fired, stated)}; correct the order or the offsets",
            file=file,
            key=key,
        )
    return dict(stated)


__all__ = ["firing_offsets", "order_of_offsets"]
