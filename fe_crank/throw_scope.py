"""Which throws of the engine one throw model stands for.

The check meshes and solves one model per key of ``fe_crank.pipeline.throw_keys`` and the
assessment (``fe_crank.assess.assess_case``) takes the meshes and unit solutions in
dicts keyed alike.  A key is either the name of one throw of the engine (the model is
that throw) or ``ALL_THROWS`` (one model stands for every throw, each assessed with its
own loads).  ``ALL_THROWS`` is a ``StrEnum`` member: it is written as ``"all throws"``
wherever a key is printed or stored (results.json, notes, provenance), and it is told
apart from a throw name by its type, never by its text.
"""

from __future__ import annotations

from enum import StrEnum


class ThrowScope(StrEnum):
    """A key that is not one throw's name."""

    ALL = "all throws"


ALL_THROWS = ThrowScope.ALL


def throws_of(key, engine_throws) -> list[str]:
    """The engine throws a model keyed ``key`` stands for, in the engine's order:
    every throw for ``ALL_THROWS``, else the throw named ``key``.  Any other key is a
    ValueError (a model that would otherwise be assessed for no throw, or for all by
    accident)."""
    names = list(engine_throws)
    if isinstance(key, ThrowScope):
        return names
    if key in names:
        return [key]
    raise ValueError(f"model key {key!r} is neither a throw of the engine {names} nor ALL_THROWS")


__all__ = ["ALL_THROWS", "ThrowScope", "throws_of"]
