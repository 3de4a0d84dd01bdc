"""fe-crank: finite-element crankshaft and counterweight stress checker.

The pipeline (docs/architecture.md): load case -> dynamics -> balance -> geometry -> mesh
-> FE -> torsion -> assessment -> verdict -> report.  SI units inside, always.

Top-level API (``fe_crank.pipeline.api``): ``run_check(paths, output=..., mesh_size=...)``
runs load cases end to end and returns their results; ``load_case(path)`` reads one load
case.
"""

from fe_crank.errors import FeCrankError, InputError
from fe_crank.version import __version__

__all__ = ["FeCrankError", "InputError", "__version__", "load_case", "run_check"]


def __getattr__(name: str):
    """``fe_crank.run_check`` and ``fe_crank.load_case``, imported on first use so that
    ``import fe_crank`` stays light."""
    if name in ("run_check", "load_case"):
        from fe_crank.pipeline import api

        return getattr(api, name)
    raise AttributeError(f"module 'fe_crank' has no attribute {name!r}")
