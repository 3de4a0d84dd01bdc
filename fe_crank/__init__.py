"""fe-crank: finite-element crankshaft and counterweight stress checker.

The pipeline (see docs/contracts.md): load case -> kinematics -> dynamics -> balance ->
geometry -> mesh -> FE -> assessment -> report.  SI units inside, always.

Top-level API (``fe_crank.api``): ``check(paths, output=..., mesh_size=...)`` runs load
cases end to end and returns their results; ``load_case(path)`` reads one load case.
"""

__version__ = "0.1.0"

# ``fe_crank.check`` is the check package, callable as ``fe_crank.api.check`` (its
# __init__ makes it so): ``fe_crank.check(paths, ...)`` and ``fe_crank.check.run_cases``
import fe_crank.check  # noqa: E402  (after __version__: provenance reads it)
from fe_crank.api import load_case  # noqa: E402
from fe_crank.errors import FeCrankError, InputError  # noqa: E402

__all__ = ["__version__", "check", "load_case", "FeCrankError", "InputError"]
