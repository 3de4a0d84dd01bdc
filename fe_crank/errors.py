"""Error hierarchy.

Every class also derives from the matching built-in, so callers that only know
Python's exceptions can still catch them.  The CLI turns any ``FeCrankError``
into one message and exit code 2 (1 is reserved for a failed criterion).
"""


class FeCrankError(Exception):
    """Base class of every error fe-crank raises on purpose."""


class InputError(FeCrankError, ValueError):
    """A load case, engine, geometry or material file is wrong.

    The message names the file, the key path and the reason.
    """

    def __init__(self, message: str, *, file: str | None = None, key: str | None = None):
        self.file = file
        self.key = key
        where = []
        if file:
            where.append(str(file))
        if key:
            where.append(key)
        prefix = ": ".join(where)
        super().__init__(f"{prefix}: {message}" if prefix else message)
        self.reason = message


class GeometryError(InputError):
    """A geometry that cannot form a valid solid."""


class MeshError(FeCrankError, RuntimeError):
    """Meshing failed or produced an unusable mesh (inverted, degenerate, missing groups)."""


class SolverError(FeCrankError, RuntimeError):
    """A solve failed: singular matrix, non-convergence, NaN/Inf, unbalanced reactions."""
