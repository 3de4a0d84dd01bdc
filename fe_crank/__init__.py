"""fe-crank: finite-element crankshaft and counterweight stress checker.

The pipeline (see docs/architecture.md): load case -> kinematics -> dynamics -> balance ->
geometry -> mesh -> FE -> assessment -> report.  SI units inside, always.
"""

__version__ = "0.1.0"
