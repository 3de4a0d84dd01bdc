"""Load-case files: engine + operating point (+ geometry, material, criteria, FE, balance).

::

    name = "single-cylinder at rated speed"
    engine = "../engines/single_cylinder.toml"   # or an inline [engine] table

    [operating]
    speed = "2800 rpm"
    overspeed = "3360 rpm"

Sections handled by later stages are parsed by their stages' parsers
(``fe_crank.io.sections``) into the typed ``LoadCase``.  A top-level key that no stage
knows is an error.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from pathlib import Path

from pydantic import Field

from fe_crank import model
from fe_crank.cad.config import CadInput
from fe_crank.errors import InputError
from fe_crank.fe.input import check_torque_reaction
from fe_crank.fe.refinement.convergence import wanted
from fe_crank.fe.refinement.levels import FACTORS
from fe_crank.fe.throw.options import FeOptions
from fe_crank.geometry.engine_fit import throw_at_bearings
from fe_crank.geometry.shaft import engine_shaft_layout, require_film, whole_shaft_wanted
from fe_crank.geometry.spec import CrankGeometry
from fe_crank.io.balance import BalanceSettings
from fe_crank.io.base import InputFile, Strict, read_toml, recording_inputs, validate
from fe_crank.io.bolted import require_joint_data
from fe_crank.io.criteria import Criteria, check_m53_torque
from fe_crank.io.engine import engine_from_reference
from fe_crank.io.geometry import require_counterweight_fillets
from fe_crank.io.includes import input_root, resolve_reference
from fe_crank.io.material import Material
from fe_crank.io.operating import parse_operating
from fe_crank.io.sections import SECTION_KEYS, parse_sections
from fe_crank.io.shaft import require_bearing_widths
from fe_crank.io.torsion import TorsionSettings
from fe_crank.io.torsion_engine import check_torsion_engine
from fe_crank.mesh.options import PRESETS, MeshSection
from fe_crank.mesh.plan import preset_of
from fe_crank.mesh.study_bounds import check_study_edges


@dataclass(frozen=True)
class LoadCase:
    """A whole load case as the stages see it (SI floats, frozen): the engine, the
    operating point and the sections of the file, each parsed by the stage that owns it;
    ``None`` where the file does not give an optional section (``fe`` and ``mesh`` take
    their defaults).  ``geometry``: a parametric geometry, or a CAD file with what its
    ``[cad]`` section states (``fe_crank.io.cad``; recognised by the check's geometry
    stage).  ``inputs``: every file the load case was read from (itself, the engine,
    geometry, CAD and pressure-table files it names), resolved, with the SHA-256 of its
    bytes, in the order read; ``engine_file``: the file the engine was read from (the
    load case itself for an inline ``[engine]``)."""

    name: str
    source_file: str
    engine: model.Engine
    operating: model.OperatingPoint
    description: str = ""
    #: the throw as the checks take it: a parametric geometry's journal stubs reach the
    #: engine's main-bearing centres (``geometry.engine_fit.throw_at_bearings``); a CAD geometry's
    #: bearing centres are the journals' middles recognised in the file (``cad.shaft``)
    geometry: CrankGeometry | CadInput | None = None
    material: Material | None = None
    criteria: Criteria | None = None
    fe: FeOptions = field(default_factory=FeOptions)
    balance: BalanceSettings | None = None
    mesh: MeshSection = field(default_factory=MeshSection)
    torsion: TorsionSettings | None = None
    inputs: tuple[InputFile, ...] = ()
    engine_file: str = ""  # the file the engine was read from (the load case itself when inline)


class LoadCaseHead(Strict):
    name: str = Field(min_length=1)
    description: str = ""
    schema_version: int = 1


def load_loadcase(
    path: str | Path, *, allow_outside_paths: bool | None = None, files_read: list[InputFile] | None = None
) -> LoadCase:
    """Read, validate and convert one load-case file.  Raises InputError.

    Include paths (``engine``, ``geometry``, a gas CSV) must stay in the load case's
    folder tree unless ``allow_outside_paths`` (default: the environment variable
    ``FE_CRANK_ALLOW_OUTSIDE_PATHS``); see ``fe_crank.io.includes.resolve_reference``.
    ``files_read``: a list that receives every input file opened, also when the load
    case is refused (the provenance of an error)."""
    with input_root(path, allow_outside_paths), recording_inputs() as read:
        try:
            lc = _load(Path(path))
        finally:
            if files_read is not None:
                files_read.extend(read)
    return dataclasses.replace(lc, inputs=tuple(read))


def _load(path: Path) -> LoadCase:
    data = read_toml(path)
    if not isinstance(data, dict):  # pragma: no cover - tomllib always returns a dict
        raise InputError("top level must be a table", file=str(path))
    head_keys = set(LoadCaseHead.model_fields)
    known = head_keys | {"engine", "operating"} | set(SECTION_KEYS)
    for key in data:
        if key not in known:
            raise InputError(f"unknown key; known keys are {sorted(known)}", file=str(path), key=_short(key))
    head = validate(LoadCaseHead, {k: v for k, v in data.items() if k in head_keys}, path)
    if "engine" not in data:
        raise InputError("required key is missing", file=str(path), key="engine")
    if "operating" not in data:
        raise InputError("required key is missing", file=str(path), key="operating")
    engine = engine_from_reference(data["engine"], path)
    engine, operating = parse_operating(data["operating"], engine, path)
    sections = parse_sections(data, path)
    criteria, geometry = sections.criteria, sections.geometry
    engine_file = _engine_file(data["engine"], path)
    if isinstance(geometry, CrankGeometry):  # one shaft in both files; bearing centres from the engine
        gfile = geometry.file or str(path)
        geometry = throw_at_bearings(geometry, engine, geometry_file=gfile, engine_file=engine_file)
        if whole_shaft_wanted(geometry, engine):  # the whole shaft's refusals at input too
            layout = engine_shaft_layout(geometry, engine, geometry_file=gfile, engine_file=engine_file)
            if criteria is not None:
                require_film(layout, [lim.key for lim in criteria.limits if "oil_film" in lim.key], path)
                quantities = [lim.quantity for lim in criteria.limits]
                require_bearing_widths(layout.bearings, quantities, gfile, str(path))
    if criteria is not None and isinstance(geometry, CrankGeometry):
        require_counterweight_fillets(geometry, [lim.quantity for lim in criteria.limits], path)
        require_joint_data(geometry, path)
    if sections.torsion is not None and isinstance(geometry, CadInput):
        raise InputError(
            "the torsional model takes its throws' inertias and stiffness from a parametric geometry; with a CAD "
            "geometry it is not available: check the torsional vibration with a parametric geometry of the shaft",
            file=str(path),
            key="torsion",
        )
    if sections.torsion is not None:
        check_torsion_engine(sections.torsion, engine, path, full_load=operating.full_load)
        _check_torsion_range(sections.torsion, operating, path)
    if criteria is not None:
        _check_whole_shaft_criteria(criteria, geometry, engine, path)
    if isinstance(geometry, CrankGeometry):
        _check_counterweight_clearance(geometry, engine, engine_file)
        check_study_fillets(geometry, sections.mesh or MeshSection(), None, None, str(path))
    if sections.fe is not None:
        check_torque_reaction(sections.fe, engine, path, torsion=sections.torsion is not None)
    if criteria is not None:
        check_m53_torque(criteria, engine, sections.torsion is not None, path)
    return LoadCase(
        name=head.name,
        source_file=str(path),
        description=head.description,
        engine=engine,
        operating=operating,
        geometry=geometry,
        material=sections.material,
        criteria=criteria,
        fe=sections.fe or FeOptions(),
        balance=sections.balance,
        mesh=sections.mesh or MeshSection(),
        torsion=sections.torsion,
        engine_file=engine_file,
    )


def check_study_fillets(
    geometry: CrankGeometry, section: MeshSection, size: str | None, convergence: bool | None, file: str
) -> None:
    """Refuse a fillet or oil bore too small for the hot-spot convergence study's finest
    level (``mesh.study_bounds``) when the study runs: at the mesh size ``size`` (the
    command line's) or the section's, the study ``convergence`` (the command line's) or
    the section's."""
    preset = preset_of(section, size)
    if wanted(convergence if convergence is not None else section.convergence, preset):
        check_study_edges(geometry, PRESETS[preset], max(FACTORS), preset, file)


def _check_torsion_range(torsion: TorsionSettings, operating: model.OperatingPoint, path: Path) -> None:
    """The torsional sweep must contain the operating speed (the torsional stage's
    journal torque is taken there)."""
    lo, hi = torsion.speed_range
    if not lo <= operating.speed <= hi:
        raise InputError(
            f"the torsional sweep {lo * 30 / math.pi:.6g}-{hi * 30 / math.pi:.6g} rpm does not contain the operating "
            f"speed {operating.speed * 30 / math.pi:.6g} rpm (operating.speed): widen the range",
            file=str(path),
            key="torsion.speed_range",
        )


#: criteria (``io.criteria`` quantities) that only the whole-shaft model evaluates
#: (``assess.criteria.judge.EVALUATORS`` whose per-throw finder is ``no_throw_value``): the main
#: bearings' loads and their oil film
WHOLE_SHAFT_QUANTITIES = ("main_bearing_load", "main_bearing_specific_load", "oil_film_thickness", "oil_film_pressure")


def _check_whole_shaft_criteria(criteria: Criteria, geometry, engine: model.Engine, path: Path) -> None:
    """A main-bearing criterion needs the whole-shaft model: a parametric geometry of an
    engine with several throws along one shaft, or a ``[shaft]`` section."""
    for lim in criteria.limits:
        if lim.quantity not in WHOLE_SHAFT_QUANTITIES:
            continue
        if isinstance(geometry, CadInput):
            z = [t.axial_position for t in engine.throws]
            if len(engine.shafts) == 1 and len(z) > 1 and max(z) - min(z) > 0:
                continue  # the drawing is checked when it is recognised (``pipeline.cad_geometry.cad_layout``)
            why = (
                f"the load case's geometry is the CAD file {geometry.file.name} and the engine has a single throw "
                "(or its throws at one axial position, or several shafts): the whole-shaft model of a drawing is "
                "built for an engine of several throws along one shaft; drop the criterion"
            )
        elif not isinstance(geometry, CrankGeometry):
            why = "the load case has no geometry"
        elif not whole_shaft_wanted(geometry, engine):
            why = (
                "the engine has a single throw (or its throws at one axial position) and the geometry no [shaft] "
                "section; add a [shaft] section to the geometry (docs/shaft.md)"
            )
        else:
            continue
        what = "oil film" if "oil_film" in lim.quantity else "main-bearing loads"
        raise InputError(f"needs the whole-shaft model's {what}: {why}", file=str(path), key=lim.key)


def _check_counterweight_clearance(g: CrankGeometry, engine: model.Engine, engine_file: str) -> None:
    """A counterweight must pass below the piston at bottom dead centre: its outer radius
    must stay within ``L - R``, the distance of the gudgeon-pin centre from the crank
    axis at BDC (rod length L, crank radius R) of every cylinder on the shaft that is not
    an articulated rod's (the piston's skirt and the rod's big end lie closer still, so
    this bound only refuses counterweights that cannot be built)."""
    clear = [
        (c.rod.length - engine.throw(c.throw).crank_radius, c.name) for c in engine.cylinders if c.articulation is None
    ]
    if not clear:
        return
    room, name = min(clear)
    for i, t in enumerate(g.throws):
        for cw in t.counterweights:
            if cw.outer_radius > room:
                key = f"throws[{i}].counterweight.outer_radius" if len(g.throws) > 1 else "counterweight.outer_radius"
                raise InputError(
                    f"{cw.outer_radius * 1e3:.6g} mm reaches beyond the piston pin of cylinder {name!r} at bottom dead "
                    f"centre, {room * 1e3:.6g} mm from the crank axis (rod length less crank radius, {engine_file}): "
                    "the counterweight cannot turn",
                    file=g.file or engine_file,
                    key=key,
                )


def _engine_file(value: object, path: Path) -> str:
    """The engine file a load case names (the load case itself for an inline table)."""
    return str(resolve_reference(value, path, key="engine")) if isinstance(value, str) else str(path)


def _short(key: object) -> str:
    """A key as written, cut to 40 characters for a message."""
    text = str(key)
    return text if len(text) <= 40 else text[:37] + "..."
