"""The load case's ``[mesh]`` section."""

from __future__ import annotations

from fe_crank.errors import InputError
from fe_crank.mesh.options import PRESETS, MeshSection

MESH_PRESETS = tuple(PRESETS)


def parse_mesh_section(value: object, file, key: str = "mesh") -> MeshSection:
    """Section parser of the load case's ``[mesh]`` section (``fe_crank.io.sections``): ``[mesh] size = "coarse"``."""
    if not isinstance(value, dict):
        raise InputError('must be a table, e.g. [mesh] size = "coarse"', file=str(file), key=key)
    for k in value:
        if k not in ("size", "convergence", "max_elements", "symmetric"):
            raise InputError(
                "unknown key; the [mesh] table takes size, convergence, max_elements and symmetric",
                file=str(file),
                key=f"{key}.{k}",
            )
    conv = value.get("convergence")
    if conv is not None and not isinstance(conv, bool):
        raise InputError("must be true or false", file=str(file), key=f"{key}.convergence")
    sym = value.get("symmetric", True)
    if not isinstance(sym, bool):
        raise InputError("must be true or false", file=str(file), key=f"{key}.symmetric")
    limit = value.get("max_elements")
    if limit is not None and (isinstance(limit, bool) or not isinstance(limit, int) or limit < 1):
        raise InputError("must be a positive whole number of elements", file=str(file), key=f"{key}.max_elements")
    size = value.get("size", "coarse")
    if size not in MESH_PRESETS:
        raise InputError(
            f"unknown mesh size {size!r}; pick one of {list(MESH_PRESETS)}", file=str(file), key=f"{key}.size"
        )
    return MeshSection(size=size, convergence=conv, max_elements=limit, symmetric=sym)
