"""The torsional stage of a load case: model, free vibration, forced response over the
speed range, the governing speed, and the journal torques handed to the assessment.

IACS UR M53 Rev.1 2.2.2: the alternating torque of every shaft section is found over the
whole speed range by harmonic synthesis of the forced vibration (orders 0.5 .. 12 for
four-stroke, 1 .. 15 for two-stroke engines), with the system's damping;
``M_TN = (M_Tmax - M_Tmin) / 2`` and the highest value over the speed range is used.
The speed grid is uniform over ``speed_range`` plus the operating speed plus every
resonance speed ``omega_r / n`` (mode ``r``, order ``n``) that falls in the range, so no
resonance peak is stepped over, plus the speeds of the full-load curve in the range (so
that the torque flow at each speed of the sweep has its vibration, ``flow.torque_flow``).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from fe_crank.errors import InputError
from fe_crank.io.torsion import TorsionSettings
from fe_crank.mechanism.torques import CylinderTorques
from fe_crank.torsion.build import build_model, shear_modulus
from fe_crank.torsion.excitation import CylinderHarmonics, cylinder_harmonics
from fe_crank.torsion.forced import ForcedResponse, forced_response
from fe_crank.torsion.free import Modes, holzer_frequencies, natural_modes
from fe_crank.torsion.model import TorsionCase, TorsionModel
from fe_crank.torsion.stiffness import carter_throw_stiffness


@dataclass(frozen=True)
class Resonance:
    mode: int  # 1 = first elastic mode
    order: float
    frequency_hz: float
    speed: float  # rad/s of the crank at which order * speed = mode frequency
    in_range: bool


@dataclass(frozen=True)
class TorsionResult:
    model: TorsionModel
    modes: Modes
    holzer_hz: np.ndarray
    harmonics: CylinderHarmonics
    response: ForcedResponse
    theta: np.ndarray  # cycle grid of the synthesis
    half_range: np.ndarray  # (n_speeds, n_segments) M_TN = (max - min)/2 of the synthesis, N m
    vibratory_half_range: np.ndarray  # (n_speeds, n_segments) of the vibratory part alone
    operating_speed: float
    speed_range: tuple[float, float]
    resonances: tuple[Resonance, ...]
    flywheel_fluctuation: float  # (w_max - w_min)/w_mean of the flywheel at the operating speed
    stiffness: dict  # "carter", "fe" (N m/rad per FE span) when known, "used"
    assess_speed: str
    qs_gas: np.ndarray  # (n_gas_parts, n_seg, n_theta) quasi-static segment torque, gas part per diagram
    qs_inertia: np.ndarray  # (n_seg, n_theta) inertia part at harmonics.reference_speed

    def index(self, speed: float) -> int:
        return int(np.argmin(np.abs(self.response.speeds - speed)))

    def governing(self, segment: int) -> int:
        """Speed index where segment ``segment`` has its largest M_TN in the range."""
        s = self.response.speeds
        inside = (s >= self.speed_range[0] - 1e-9) & (s <= self.speed_range[1] + 1e-9)
        hr = np.where(inside, self.half_range[:, segment], -np.inf)
        return int(np.argmax(hr))

    def quasi_static(self, s: int) -> np.ndarray:
        """Rigid-shaft segment torques (n_seg, n_theta) at speed index ``s``: the
        cumulative cylinder torque from the free end, synthesised from the same orders as
        the response (so that the vibratory part is the dynamic amplification of those
        orders; the orders above them stay in the quasi-static torque of the dynamics
        stage, taken as not amplified)."""
        w = self.response.speeds[s]
        ratio = (w / self.harmonics.reference_speed) ** 2
        return np.tensordot(self.harmonics.gas_weights(w), self.qs_gas, axes=1) + ratio * self.qs_inertia

    def vibratory(self, s: int) -> np.ndarray:
        """Vibratory segment torques (n_seg, n_theta): synthesis less quasi-static."""
        return self.response.synthesis(s, self.theta) - self.quasi_static(s)

    def journal_segments(self, throw: str) -> tuple[int, int]:
        """Indices of the segments in front of and behind a throw's mass."""
        i = self.model.throw_mass[throw]
        return i - 1, i


def speed_grid(lo: float, hi: float, steps: int, operating: float, resonances: list[float]) -> np.ndarray:
    grid = np.linspace(lo, hi, steps)
    extra = [operating] + [w for w in resonances if lo <= w <= hi]
    return np.unique(np.concatenate([grid, extra]))


def analyse_torsion(
    loadcase: TorsionCase,
    torques: CylinderTorques,
    *,
    settings: TorsionSettings | None = None,
    inertias: dict[str, float] | None = None,
    fe_stiffness: float | None = None,
) -> TorsionResult:
    """Run the torsional stage of ``loadcase`` (its ``[torsion]`` section, or ``settings``)
    on the dynamics stage's cylinder torques ``torques`` (``EngineCycles.torques``: every
    cylinder firing, or a misfire case, ``fe_crank.torsion.misfire``); ``inertias``: the
    throws' inertias about the crank axis when the caller has them (the check passes its
    geometry stage's CAD mass properties, ``build.throw_inertias``)."""
    settings = settings or loadcase.torsion
    if settings is None:
        raise InputError("the load case has no [torsion] section", file=loadcase.source_file, key="torsion")
    lo, hi = settings.speed_range
    op = loadcase.operating.speed
    if not lo <= op <= hi:
        raise InputError(
            "speed_range must contain the operating speed", file=loadcase.source_file, key="torsion.speed_range"
        )
    model = build_model(loadcase, settings, inertias=inertias, fe_stiffness=fe_stiffness)
    modes = natural_modes(model)
    if not np.isclose(torques.reference_speed, op, rtol=1e-12, atol=0.0):
        raise ValueError("the cylinder torques are not those of the load case's operating speed")
    harmonics = cylinder_harmonics(torques)
    top = 12.0 if loadcase.engine.strokes == 4 else 15.0
    orders = harmonics.orders[(harmonics.orders > 0) & (harmonics.orders <= top + 1e-9)]
    res_list = []
    for r, w in enumerate(modes.elastic_omega, start=1):
        for n in orders:
            res_list.append(Resonance(r, float(n), float(w / (2 * np.pi)), float(w / n), bool(lo <= w / n <= hi)))
    sweep = loadcase.operating.full_load.speeds if loadcase.operating.full_load is not None else ()
    speeds = speed_grid(lo, hi, settings.speed_steps, op, [x.speed for x in res_list] + list(sweep))
    response = forced_response(model, harmonics, speeds, orders)
    theta = torques.theta  # the grid of the dynamics stage
    half = np.zeros((speeds.size, model.size - 1))
    vib_half = np.zeros_like(half)
    stiff: dict[str, str | float] = {"used": settings.throw_stiffness}
    if settings.model == "cad":
        stiff["carter"] = carter_throw_stiffness(loadcase.geometry, shear_modulus(loadcase.material))
    if fe_stiffness is not None:
        stiff["fe"] = fe_stiffness
    qs = []
    kept = np.isin(harmonics.orders, np.concatenate([[0.0], orders]))
    ph = np.exp(1j * np.outer(theta, harmonics.orders[kept]))
    for part in (*harmonics.gas_parts(), harmonics.inertia):
        per_mass = np.zeros((model.size, theta.size))
        for cyl, throw in harmonics.throw_of.items():
            per_mass[model.throw_mass[throw]] += np.real(ph @ part[cyl][kept])
        qs.append(np.cumsum(per_mass, axis=0)[:-1])
    i_op = int(np.argmin(np.abs(speeds - op)))
    fly = "flywheel" if settings.model == "cad" else settings.flywheel_station
    vel = response.velocity_synthesis(i_op, theta)[model.names.index(fly)]
    fluct = float((vel.max() - vel.min()) / op)
    result = TorsionResult(
        model,
        modes,
        holzer_frequencies(model, 1.5 * modes.omega[-1]) / (2 * np.pi),
        harmonics,
        response,
        theta,
        half,
        vib_half,
        op,
        (lo, hi),
        tuple(res_list),
        fluct,
        stiff,
        settings.assess_speed,
        np.stack(qs[:-1]),
        qs[-1],
    )
    syn = response.synthesis_all(theta)  # (n_speeds, n_seg, n_theta)
    half[:] = 0.5 * np.ptp(syn, axis=2)
    ratio = (speeds / harmonics.reference_speed) ** 2
    weights = np.array([harmonics.gas_weights(w) for w in speeds])
    syn -= np.einsum("sk,knt->snt", weights, result.qs_gas) + ratio[:, None, None] * qs[-1][None]  # vibratory part
    vib_half[:] = 0.5 * np.ptp(syn, axis=2)
    return result


def with_vibratory_torque(dynamics, result: TorsionResult, *, handed: dict | None = None):
    """A copy of the dynamics stage's result whose journal torques (``torque_front``,
    ``torque_rear`` of every throw) are the torsional stage's histories of those journals
    (``fe_crank.torsion.handover.journal_torques``: one synthesis, quasi-static and
    vibratory at one speed, the largest of the range), over the same cycle grid: what the
    FE torque unit case and the UR M53 nominal torsional stress take.  A journal at the
    free end (no segment in front of or behind the throw) keeps the dynamics stage's torque.
    ``handed``: segment name -> the histories to take instead (e.g. the worst of the
    misfire cases, ``misfire.MisfireTorsion.journal_torques``)."""
    from fe_crank.torsion.handover import journal_torques

    if not np.allclose(dynamics.theta, result.theta):
        raise ValueError("the torsional synthesis and the dynamics stage use different angle grids")
    if handed is None:
        handed = journal_torques(result)
    names = result.model.segment_names
    throws = {}
    for name, tl in dynamics.throws.items():
        front, rear = result.journal_segments(name)
        tf = handed[names[front]].history if front >= 0 else tl.torque_front
        tr = handed[names[rear]].history if rear < len(names) else tl.torque_rear
        throws[name] = dataclasses.replace(tl, torque_front=tf, torque_rear=tr)
    return dataclasses.replace(dynamics, throws=throws)
