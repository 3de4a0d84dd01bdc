"""What a refusal's message must not contain: the input library's internals (pydantic's
union members ``literal[...]``, ``constrained-str``, ``function-after[...]``, its
documentation links) and the names of the input layer's classes (``CounterweightInput``)."""

from __future__ import annotations

import re

INTERNALS = re.compile(
    r"literal\[|constrained-|function-(after|before|wrap|plain)\[|lax-or-strict|json-or-python|"
    r"errors\.pydantic\.dev|\b[A-Z][A-Za-z0-9]*Input\b|pydantic"
)


def internals(message: str) -> list[str]:
    """The internals found in ``message`` (empty: a clean message)."""
    return [m.group(0) for m in INTERNALS.finditer(message)]
