"""fe-crank: finite-element crankshaft and counterweight stress checker.

The pipeline (see docs/architecture.md): load case -> kinematics -> dynamics -> balance ->
geometry -> mesh -> FE -> assessment -> report.  SI units inside, always.

Top-level API (``fe_crank.check.api``): ``check(paths, output=..., mesh_size=...)`` runs load
cases end to end and returns their results; ``load_case(path)`` reads one load case.
"""

from fe_crank.errors import FeCrankError, InputError
from fe_crank.version import __version__

__all__ = ["__version__", "check", "load_case", "FeCrankError", "InputError"]


def __getattr__(name: str):
    """``fe_crank.check`` (the check package, callable as ``fe_crank.check.api.check``) and
    ``fe_crank.load_case``, imported on first use so that ``import fe_crank`` stays light."""
    if name == "check":
        import fe_crank.check as check

        return check
    if name == "load_case":
        from fe_crank.check.api import load_case

        return load_case
    raise AttributeError(f"module 'fe_crank' has no attribute {name!r}")
