"""Torsional vibration of the crank train (IACS UR M53 2.2.2): lumped-mass chain, free
vibration (eigenproblem and Holzer), the harmonics of the dynamics stage's cylinder
torques, forced damped response over the speed range, and the vibratory journal torques
handed to the assessment.
docs/torsion.md describes the model, its assumptions and sources."""

from fe_crank.torsion.analysis import Resonance, TorsionResult, analyse_torsion, with_vibratory_torque
from fe_crank.torsion.build import build_model
from fe_crank.torsion.excitation import cylinder_harmonics, order_phase_sum
from fe_crank.torsion.flow import fe_loads, torque_flow
from fe_crank.torsion.forced import forced_response, m53_orders
from fe_crank.torsion.free import holzer_frequencies, holzer_table, natural_modes
from fe_crank.torsion.handover import journal_torques
from fe_crank.torsion.lumped import lumped_model
from fe_crank.torsion.misfire import analyse_misfire
from fe_crank.torsion.model import TorsionModel
from fe_crank.torsion.stiffness import carter_throw_stiffness, fe_throw_stiffness

__all__ = [
    "Resonance",
    "TorsionResult",
    "analyse_torsion",
    "with_vibratory_torque",
    "build_model",
    "cylinder_harmonics",
    "order_phase_sum",
    "forced_response",
    "fe_loads",
    "torque_flow",
    "journal_torques",
    "lumped_model",
    "analyse_misfire",
    "m53_orders",
    "holzer_frequencies",
    "holzer_table",
    "natural_modes",
    "TorsionModel",
    "carter_throw_stiffness",
    "fe_throw_stiffness",
]
