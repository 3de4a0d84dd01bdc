"""The geometry stage of a load case whose geometry is a CAD file (``[cad]``).

The file is recognised once (``fe_crank.cad.recognise``); its throws are checked
against the engine's (count, names, crank radius, angles: ``fe_crank.cad.engine``),
which gives the mesh plan's keys; a counterweight stress criterion needs every
counterweight to leave its web in a rounded face (as ``io.geometry.
require_counterweight_fillets`` for a parametric geometry) and at least one recognised
counterweight (else the criterion has nothing to evaluate); the UR M53 dimensions and
the counterweights' built m r per engine throw are measured on the recognised throws
(``assess.throw_geometry.cad_throws``).  A bolt criterion is refused (a drawing gives no
bolt data); a drawing of the whole shaft gets its layout (``cad_layout``,
``fe_crank.cad.whole``) for the whole-shaft stage, or, where a main-bearing criterion
needs it and the drawing cannot give it, the reason.  ``validate`` runs all of this.
"""

from __future__ import annotations

import dataclasses

from fe_crank.assess.joint_criteria import JOINT_QUANTITIES
from fe_crank.assess.throw_geometry import cad_throws
from fe_crank.balance.analysis import BalanceResult
from fe_crank.cad import CadFeatures, CadInput, recognise
from fe_crank.cad.engine import engine_keys
from fe_crank.cad.whole import MIN_SECTORS, cad_shaft_layout, shared_meshes
from fe_crank.errors import InputError
from fe_crank.geometry.shaft import ShaftLayout
from fe_crank.io.geometry import COUNTERWEIGHT_STRESS_QUANTITIES
from fe_crank.io.loadcase import WHOLE_SHAFT_QUANTITIES, LoadCase
from fe_crank.io.shaft import WIDTH_CRITERIA
from fe_crank.mesh.plan import mesh_plan
from fe_crank.outputs import GeometryModel
from fe_crank.pipeline.options import CheckOptions


def require_cad_counterweight_fillets(features: CadFeatures, cad: CadInput, lc: LoadCase) -> None:
    """Refuse a counterweight stress criterion when a counterweight of the file leaves
    its web in a sharp edge (a stress singularity: its FE stress grows with every mesh
    refinement, so any figure from it would be optimistic)."""
    limits = [
        lim for lim in (lc.criteria.limits if lc.criteria else ()) if lim.quantity in COUNTERWEIGHT_STRESS_QUANTITIES
    ]
    if not limits:
        return
    if not any(t.counterweights for t in features.throws):
        looked = "; ".join(
            f"throw {t.name} beyond r = " + " and ".join(f"{w.side_radius * 1e3:.4g} mm (web_{w.side})" for w in t.webs)
            for t in features.throws
        )
        raise InputError(
            f"required by the criterion {limits[0].key}: a counterweight in the FE model; none is recognised in the "
            f"CAD file {cad.file.name}: looked for material on the far side of the crank axis from each crankpin, "
            f"beyond the web's rounded journal end ({looked}), between a bearing centre and the throw's middle, and "
            "found none there; if the counterweights begin nearer the axis, state where in counterweight_radius "
            f'(e.g. "40 mm") in {cad.where}; counterweights drawn as separate bolted solids (bodies = "bolted") are '
            "not in the FE model and give no stress: drop the criterion",
            file=lc.source_file,
            key=limits[0].key,
        )
    for t in features.throws:
        for cw in t.counterweights:
            if cw.fillet_radius is None:
                raise InputError(
                    f"required by the criterion {limits[0].key}: a rounded transition where counterweight_{cw.web} "
                    f"of throw {t.name} leaves its web; the CAD file {cad.file.name} shows a sharp edge there (no "
                    "concave curved face recognised), a stress singularity whose FE stress grows without bound as "
                    "the mesh is refined: round it in the CAD model or drop the criterion",
                    file=lc.source_file,
                    key=limits[0].key,
                )


#: criteria on the counterweights' bolts: they need bolt data (size, preload, joint), which
#: a drawing does not give (``assess.cad_inputs``: no bolt data, no utilisation)
BOLT_QUANTITIES = ("bolt_utilisation", *JOINT_QUANTITIES)


def refuse_bolt_criteria(lc: LoadCase, cad: CadInput) -> None:
    """A bolt criterion with a CAD geometry: refused (``BOLT_QUANTITIES``), before any meshing."""
    for lim in lc.criteria.limits if lc.criteria else ():
        if lim.quantity in BOLT_QUANTITIES:
            raise InputError(
                f"cannot be evaluated with the CAD file {cad.file.name}: a drawing gives the bolted counterweights' "
                'mass (bodies = "bolted") but no bolt data (size, preload, clamped parts), which the bolt '
                "criteria need; drop the criterion, or check the bolts with a parametric geometry's bolted table",
                file=lc.source_file,
                key=lim.key,
            )


def recognise_case(lc: LoadCase, cad: CadInput) -> tuple[CadFeatures, dict[str, str]]:
    """Recognise the load case's CAD file and check it against the engine and the
    criteria: the features and the mesh plan's keys (key -> recognised throw name)."""
    refuse_bolt_criteria(lc, cad)
    features = recognise(cad)
    keys = engine_keys(features, cad, lc.engine, engine_file=lc.engine_file, loadcase=lc.source_file)
    require_cad_counterweight_fillets(features, cad, lc)
    return features, keys


def cad_layout(lc: LoadCase, cad: CadInput, features: CadFeatures) -> ShaftLayout | None:
    """The drawn whole shaft (``fe_crank.cad.whole``) when the check models it: a load
    case with a material whose engine spreads several throws along one shaft and a
    drawing of them; None where no whole shaft is wanted, or where it cannot be built
    from the drawing and no criterion needs it (the throws then checked one by one, as
    before).  A main-bearing criterion on a drawing the whole-shaft model cannot take is
    refused with the reason."""
    engine = lc.engine
    z = [t.axial_position for t in engine.throws]
    if lc.material is None or len(engine.shafts) != 1 or len(z) < 2 or max(z) - min(z) <= 0:
        return None
    needs = [lim.key for lim in (lc.criteria.limits if lc.criteria else ()) if lim.quantity in WHOLE_SHAFT_QUANTITIES]
    if len(features.throws) < 2 and not needs:
        return None
    try:
        layout = cad_shaft_layout(features, cad, engine, engine_file=lc.engine_file or lc.source_file)
    except InputError:
        if needs:
            raise
        return None
    film = [lim for lim in (lc.criteria.limits if lc.criteria else ()) if "oil_film" in lim.quantity]
    if film and not any(b.law.film is not None for b in layout.bearings):
        raise InputError(
            f"cannot be evaluated: no main bearing of the drawn shaft (the CAD file {cad.file.name}) has an oil "
            "film; the drawing holds the journals, the bearings are the engine's: state them in [cad.shaft] of "
            f'{cad.where} as a geometry\'s [shaft] does (bearing = {{ model = "hydrodynamic", clearance = "28 um", '
            'viscosity = "6 mPa*s" }, bearing_width = "20 mm"), or drop the criterion',
            file=lc.source_file,
            key=film[0].key,
        )
    widths = [lim for lim in (lc.criteria.limits if lc.criteria else ()) if lim.quantity in WIDTH_CRITERIA]
    missing = [b for b in layout.bearings if not b.width_stated]
    if widths and missing:  # a drawing holds no bearing shell: the journal's flat would under-state
        raise InputError(
            f"divides each main bearing's peak load by its projected area (journal diameter x bearing width); the "
            f"CAD file {cad.file.name} draws the journals, not the bearing shells on them (main bearing "
            f"{missing[0].name}: the journal's flat between its fillets, {missing[0].width * 1e3:.3g} mm, is not a "
            f'bearing width): the specific load needs the shells\' width: state it as bearing_width (e.g. "16 mm") '
            f"in [cad] or [cad.shaft] of {cad.where}",
            file=lc.source_file,
            key=widths[0].key,
        )
    return layout


def cad_geometry_stage(
    lc: LoadCase, cad: CadInput, options: CheckOptions, balance: BalanceResult | None
) -> GeometryModel:
    """The geometry stage for a CAD file (module docstring); with the whole shaft
    (``cad_layout``) every engine throw's model is its drawn throw's mesh with the whole
    shaft's end-face sectors (the first of the throws that are the same solid,
    ``cad.whole.shared_meshes``; one mesh for both models, as a parametric shaft's)."""
    features, keys = recognise_case(lc, cad)
    layout = cad_layout(lc, cad, features)
    plan = mesh_plan(
        keys,
        lc.mesh,
        size=options.mesh_size,
        max_elements=options.max_elements,
        cache_dir=options.cache_dir,
        shaft=layout,
        min_sectors=MIN_SECTORS,
    )
    design = balance.design if balance is not None else None
    throws = cad_throws(features, cad, plan.throws, lc.engine, design)
    if layout is not None:
        shared = shared_meshes(features)
        plan = dataclasses.replace(plan, throws={k: shared[v] for k, v in plan.throws.items()})
    return GeometryModel(plan, throws, None, features)
