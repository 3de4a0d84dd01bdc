"""The geometry stage of a load case whose geometry is a CAD file (``[cad]``).

The file is recognised once (``fe_crank.cad.recognise``); its throws are checked
against the engine's (count, names, crank radius, angles: ``fe_crank.cad.engine``),
which gives the mesh plan's keys; a counterweight stress criterion needs every
counterweight to leave its web in a rounded face (as ``io.geometry.
require_counterweight_fillets`` for a parametric geometry) and at least one recognised
counterweight (else the criterion has nothing to evaluate); the UR M53 dimensions and
the counterweights' built m r per engine throw are measured on the recognised throws
(``assess.throw_geometry.cad_throws``).
"""

from __future__ import annotations

from fe_crank.assess.throw_geometry import cad_throws
from fe_crank.balance.analysis import BalanceResult
from fe_crank.cad import CadFeatures, CadInput, recognise
from fe_crank.cad.engine import engine_keys
from fe_crank.errors import InputError
from fe_crank.io.geometry import COUNTERWEIGHT_STRESS_QUANTITIES
from fe_crank.io.loadcase import LoadCase
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


def recognise_case(lc: LoadCase, cad: CadInput) -> tuple[CadFeatures, dict[str, str]]:
    """Recognise the load case's CAD file and check it against the engine and the
    criteria: the features and the mesh plan's keys (key -> recognised throw name)."""
    features = recognise(cad)
    keys = engine_keys(features, cad, lc.engine, engine_file=lc.engine_file, loadcase=lc.source_file)
    require_cad_counterweight_fillets(features, cad, lc)
    return features, keys


def cad_geometry_stage(
    lc: LoadCase, cad: CadInput, options: CheckOptions, balance: BalanceResult | None
) -> GeometryModel:
    """The geometry stage for a CAD file (module docstring)."""
    features, keys = recognise_case(lc, cad)
    plan = mesh_plan(
        keys, lc.mesh, size=options.mesh_size, max_elements=options.max_elements, cache_dir=options.cache_dir
    )
    design = balance.design if balance is not None else None
    return GeometryModel(plan, cad_throws(features, cad, plan.throws, lc.engine, design), None, features)
