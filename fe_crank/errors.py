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


class EnvironmentFault(FeCrankError, OSError):
    """The machine refused a file operation (disk full, permission denied, a read-only
    file system): not a fault of the input nor of the computation.  The message names
    the fault and the path."""

    def __init__(self, message: str, *, path: str | None = None):
        super().__init__(message)
        self.path = path


#: errno -> the fault's name in a message
_FAULTS = {
    28: "disk full (no space left on device)",  # ENOSPC
    122: "disk quota exceeded",  # EDQUOT
    13: "permission denied",  # EACCES
    1: "operation not permitted",  # EPERM
    30: "read-only file system",  # EROFS
    27: "file too large for the file system or the process's file-size limit",  # EFBIG
}


def environment_fault(exc: OSError, action: str, path: object) -> EnvironmentFault:
    """An ``EnvironmentFault`` for ``exc`` raised while ``action`` (e.g. "writing the mesh
    cache") at ``path``: "environment fault: disk full (no space left on device) while
    writing the mesh cache at <path>"."""
    reason = _FAULTS.get(exc.errno or 0) or exc.strerror or type(exc).__name__
    where = getattr(exc, "filename", None) or path
    return EnvironmentFault(f"environment fault: {reason} while {action} at {where}", path=str(where))
