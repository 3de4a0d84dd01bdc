"""FE stage: P2 linear elasticity of the crank throw with scikit-fem.

Public API: :func:`solve_unit_cases` -> :class:`UnitSolutions`; stress recovery
(:func:`stress_at_nodes`, :func:`von_mises`, :func:`principal`, :func:`max_shear`);
lower level: :func:`build_system`, :func:`factorise`, loads and supports.
"""

from fe_crank.fe.core.forms import bearing_support, centrifugal, elasticity, lame_parameters
from fe_crank.fe.core.result_fields import write_fields
from fe_crank.fe.core.stress import max_shear, principal, stress_at_nodes, von_mises
from fe_crank.fe.core.supports import Coupling, Dirichlet, Foundation
from fe_crank.fe.core.system import System, build_system
from fe_crank.fe.linalg.factorise import factorise
from fe_crank.fe.throw.unit_cases import CASES, FeOptions, UnitCase, UnitSolutions, solve_unit_cases

__all__ = [
    "CASES",
    "Coupling",
    "write_fields",
    "Dirichlet",
    "FeOptions",
    "Foundation",
    "System",
    "UnitCase",
    "UnitSolutions",
    "bearing_support",
    "build_system",
    "centrifugal",
    "elasticity",
    "factorise",
    "lame_parameters",
    "max_shear",
    "principal",
    "solve_unit_cases",
    "stress_at_nodes",
    "von_mises",
]
