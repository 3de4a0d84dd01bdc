"""Load-case files: engine + operating point (+ geometry, material, criteria, FE, balance).

::

    name = "single-cylinder at rated speed"
    engine = "../engines/single_cylinder_seed001.toml"   # or an inline [engine] table

    [operating]
    speed = "2800 rpm"
    overspeed = "3360 rpm"

Sections handled by later stages are parsed by the functions listed in
``fe_crank.io.sections.SECTIONS`` (key -> callable(value, file, key) -> frozen object).  A top-level key
that no stage knows is an error.
"""

from __future__ import annotations

from pathlib import Path

from pydantic import Field

from fe_crank import model
from fe_crank.errors import InputError
from fe_crank.fe.input import check_torque_reaction
from fe_crank.io.base import Strict, input_root, read_toml, validate
from fe_crank.io.criteria import check_m53_torque
from fe_crank.io.engine import engine_from_reference
from fe_crank.io.geometry import require_counterweight_fillets
from fe_crank.io.operating import parse_operating
from fe_crank.io.sections import SECTIONS
from fe_crank.io.torsion import check_torsion_engine


class LoadCaseHead(Strict):
    name: str = Field(min_length=1)
    description: str = ""
    schema_version: int = 1


def load_loadcase(path: str | Path, *, allow_outside_paths: bool | None = None) -> model.LoadCase:
    """Read, validate and convert one load-case file.  Raises InputError.

    Include paths (``engine``, ``geometry``, a gas CSV) must stay in the load case's
    folder tree unless ``allow_outside_paths`` (default: the environment variable
    ``FE_CRANK_ALLOW_OUTSIDE_PATHS``); see ``fe_crank.io.base.resolve_reference``."""
    with input_root(path, allow_outside_paths):
        return _load(Path(path))


def _load(path: Path) -> model.LoadCase:
    data = read_toml(path)
    if not isinstance(data, dict):  # pragma: no cover - tomllib always returns a dict
        raise InputError("top level must be a table", file=str(path))
    head_keys = set(LoadCaseHead.model_fields)
    known = head_keys | {"engine", "operating"} | set(SECTIONS)
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
    sections = {}
    for key, parser in SECTIONS.items():
        if key in data:
            sections[key] = parser(data[key], path, key)
    if sections.get("criteria") is not None:
        require_counterweight_fillets(
            sections.get("geometry"), [lim.quantity for lim in sections["criteria"].limits], path
        )
    if sections.get("torsion") is not None:
        check_torsion_engine(sections["torsion"], engine, path, full_load=operating.full_load)
    if sections.get("fe") is not None:
        check_torque_reaction(sections["fe"], engine, path)
    if sections.get("criteria") is not None:
        check_m53_torque(sections["criteria"], engine, sections.get("torsion") is not None, path)
    extras = {k: v for k, v in sections.items() if k not in ("geometry", "material", "criteria", "fe", "balance")}
    return model.LoadCase(
        name=head.name,
        source_file=str(path),
        description=head.description,
        engine=engine,
        operating=operating,
        geometry=sections.get("geometry"),
        material=sections.get("material"),
        criteria=sections.get("criteria"),
        fe=sections.get("fe"),
        balance=sections.get("balance"),
        extras=extras,
    )


def _short(key: object) -> str:
    """A key as written, cut to 40 characters for a message."""
    text = str(key)
    return text if len(text) <= 40 else text[:37] + "..."
