"""fe-crank: finite-element crankshaft and counterweight stress checker.

The pipeline (see docs/contracts.md): load case -> kinematics -> dynamics -> balance ->
geometry -> mesh -> FE -> assessment -> report.  SI units inside, always.

Top-level API (``fe_crank.api``): ``check(paths, output=..., mesh_size=...)`` runs load
cases end to end and returns their results; ``load_case(path)`` reads one load case.
"""

__version__ = "0.1.0"

from fe_crank.api import check, load_case  # noqa: E402  (after __version__: provenance reads it)
from fe_crank.errors import FeCrankError, InputError  # noqa: E402

__all__ = ["__version__", "check", "load_case", "FeCrankError", "InputError"]
