"""What UR M53 takes from the machine and the material, stated once for a load case.

IACS UR M53 "Calculation of crankshafts for I.C. engines" (Rev.1, Dec 2004):

* section 4, additional bending stress sigma_add (misalignment and bedplate deformation,
  axial and bending vibration), added to the alternating bending stress of each fillet
  (5.2: sigma_V = sqrt((sigma_B + sigma_add)^2 + 3 tau^2)): +-10 N/mm^2 for trunk piston
  engines, +-30 N/mm^2 for crosshead engines (20 of them from axial vibration, which an
  axial vibration calculation of the whole system may replace).  From the engine's
  ``construction``; a load case may state a larger value
  (``[criteria] m53_additional_bending``), not a smaller one.
* 2.1.2.1, K_e = 0.8 for two-stroke and 1.0 for four-stroke engines on the web's nominal
  bending and compressive stresses: an empirical allowance for the restraint of the
  neighbouring throws and bearings, fitted to internal-combustion engines.  On a machine
  that is not one (``Engine.internal_combustion`` false: an air motor, a compressor) the
  whole route is an analogy and the allowance is not taken: K_e = 1.0.
* section 6, factor K of the fatigue strength: from the stated manufacturing process
  (``fe_crank.io.material.FORGING_K``; 1.0 when not stated).

``M53Basis.analogy`` is the typed flag for the verdict: the M53 criterion of a machine that
is not an I.C. engine is a comparison, not the rule's sign-off.
"""

from __future__ import annotations

from dataclasses import dataclass

from fe_crank.errors import InputError
from fe_crank.model import Engine
from fe_crank.rules.m53.calculation import M53Material, ke_factor

#: UR M53 section 4: sigma_add by engine construction, Pa
ADDITIONAL_BENDING = {"trunk_piston": 10e6, "crosshead": 30e6}


@dataclass(frozen=True)
class M53Basis:
    """The machine- and process-dependent inputs of UR M53 for one load case (SI)."""

    ke: float  # K_e of 2.1.2.1 on the web's nominal stresses
    additional: float  # sigma_add of section 4, Pa
    additional_source: str
    forging_k: float | None  # K of section 6 (None: the material has none, UR M53 not applicable)
    forging_source: str
    analogy: bool  # True: the machine is not an internal-combustion engine
    notes: tuple[str, ...]


def additional_bending(construction: str, stated: float | None, *, file: str = "") -> tuple[float, str]:
    """sigma_add (Pa) and where it came from: the rule's value for ``construction``
    (UR M53 4), or ``stated`` (``[criteria] m53_additional_bending``) when it is not smaller."""
    try:
        rule = ADDITIONAL_BENDING[construction]
    except KeyError:
        raise ValueError(f"unknown engine construction {construction!r}") from None
    words = construction.replace("_", " ")
    if stated is None:
        return rule, f"UR M53 4, {words} engine: {rule / 1e6:g} MPa"
    if stated < rule:
        raise InputError(
            f"{stated / 1e6:g} MPa is below UR M53 section 4's {rule / 1e6:g} MPa for a {words} engine "
            "(misalignment, bedplate deformation, axial and bending vibration); state the engine's "
            "construction, or a value at least that large",
            file=file,
            key="criteria.m53_additional_bending",
        )
    return stated, f"stated in the load case: {stated / 1e6:g} MPa (UR M53 4 gives {rule / 1e6:g} MPa)"


def m53_basis(
    engine: Engine, material: M53Material | None, stated_additional: float | None, *, file: str = ""
) -> M53Basis:
    """The UR M53 basis of a load case: ``engine`` a ``model.Engine``, ``material`` an
    ``io.material.Material``, ``stated_additional`` the load case's sigma_add or None."""
    ic = bool(engine.internal_combustion)
    ke = ke_factor(engine.strokes) if ic else 1.0
    add, add_source = additional_bending(engine.construction, stated_additional, file=file)
    k = material.m53_k if material is not None else None
    if k is None or material is None:  # no material: no k either
        k_source = "no UR M53 factor K: the material is not a steel the rule covers"
    elif material.forging is not None:
        k_source = f"K = {k:g}: {material.forging.replace('_', ' ')} (UR M53 6)"
    elif material.kind == "steel" and k == 1.0:
        k_source = "K = 1: the forging process is not stated (UR M53 6: free-form forged; drop-forged 1.05)"
    else:
        k_source = f"K = {k:g}: given in the material"
    notes = [f"UR M53 sigma_add {add / 1e6:g} MPa ({add_source})", f"UR M53 fatigue strength {k_source}"]
    if not ic:
        notes.append(
            "UR M53 route by analogy only: the machine is not an internal-combustion engine (the rule's "
            "scope); K_e = 1 (no allowance for the restraint of neighbouring throws)"
        )
    elif engine.strokes == 2:
        notes.append(
            "UR M53 route: two-stroke engine, K_e = 0.8 on the web's nominal bending and compressive "
            "stresses (UR M53 2.1.2.1); not applied to the FE route nor to the oil-bore outlet"
        )
    return M53Basis(ke, add, add_source, k, k_source, not ic, tuple(notes))


__all__ = ["ADDITIONAL_BENDING", "M53Basis", "additional_bending", "m53_basis"]
