"""fe-crank: finite-element crankshaft and counterweight stress checker.

The pipeline (see docs/architecture.md): load case -> kinematics -> dynamics -> balance ->
geometry -> mesh -> FE -> assessment -> report.  SI units inside, always.

Top-level API (``fe_crank.api``): ``check(paths, output=..., mesh_size=...)`` runs load
cases end to end and returns their results; ``load_case(path)`` reads one load case.
"""

__version__ = "0.1.0"

from fe_crank.api import load_case  # noqa: E402  (after __version__: provenance reads it)
from fe_crank.errors import FeCrankError, InputError  # noqa: E402

__all__ = ["__version__", "check", "load_case", "FeCrankError", "InputError"]


def __getattr__(name: str):
    """``fe_crank.check``: the check package, callable as ``fe_crank.api.check`` (its
    __init__ makes it so), imported on first use so that ``import fe_crank`` stays light."""
    if name == "check":
        import importlib

        return importlib.import_module("fe_crank.check")
    raise AttributeError(f"module 'fe_crank' has no attribute {name!r}")
