"""Result fields of the FE stage for the project's one VTU writer (``fe_crank.vtu_writer``):
stress fields with units in their names, boundary ids of the P2 nodes, ``write_fields``."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from skfem import Mesh

from fe_crank.fe.core.stress import VOIGT, max_shear, principal, von_mises
from fe_crank.vtu_writer import positively_oriented, quadratic_tet_mesh, region_ids, write_vtu

__all__ = [
    "boundary_point_ids",
    "positively_oriented",
    "quadratic_tet_mesh",
    "region_ids",
    "stress_fields",
    "write_fields",
    "write_vtu",
]


def boundary_point_ids(skmesh: Mesh, basis) -> tuple[np.ndarray, dict]:
    """Point data ``boundary``: for every P2 node, the id of the first (sorted) named
    boundary it lies on, -1 for none; and the matching field data."""
    names = sorted(skmesh.boundaries or {})
    ids = np.full(basis.doflocs.shape[1], -1, np.int32)
    for i, name in reversed(list(enumerate(names))):  # the first name wins
        nodes = np.unique(basis.get_dofs(facets=skmesh.boundaries[name]).all())
        ids[nodes] = i
    return ids, {f"boundary:{name}": np.array([i, 2]) for i, name in enumerate(names)}


def stress_fields(stress: np.ndarray, suffix: str = "") -> dict[str, np.ndarray]:
    """Point fields of a (6, n) Voigt stress (xx yy zz xy yz zx, Pa): ``stress_Pa``
    (n, 6), ``von_mises_Pa``, ``principal_1_Pa`` >= ``principal_2_Pa`` >= ``principal_3_Pa``,
    ``max_shear_Pa`` (Tresca, (s1 - s3) / 2); ``suffix`` is appended to every name."""
    s = np.asarray(stress)
    p = principal(s)
    out = {"stress_Pa": np.ascontiguousarray(s.T), "von_mises_Pa": von_mises(s)}
    for k in range(3):
        out[f"principal_{k + 1}_Pa"] = p[k]
    out["max_shear_Pa"] = max_shear(s)
    return {k.replace("_Pa", f"{suffix}_Pa") if suffix else k: v for k, v in out.items()}


def write_fields(
    path: str | Path,
    basis,
    u: np.ndarray | None = None,
    stress: np.ndarray | None = None,
    extra: dict[str, np.ndarray] | None = None,
) -> Path:
    """Write displacement ``displacement_m`` (3 per node), stress ``stress_Pa`` (n, 6,
    Voigt) and the derived scalars of ``stress_fields`` to ``path`` (.vtu), with the
    region ids of ``basis.mesh`` when it has named groups.

    ``basis``: the scalar P2 basis of the solution (``UnitSolutions.system.basis``).
    """
    data: dict[str, np.ndarray] = {}
    if u is not None:
        data["displacement_m"] = np.asarray(u).reshape(-1, 3)
    if stress is not None:
        data.update(stress_fields(stress))
    for name, arr in (extra or {}).items():
        data[name] = np.asarray(arr)
    cdata, fdata = region_ids(basis.mesh)
    if basis.mesh.boundaries:
        data["boundary"], bf = boundary_point_ids(basis.mesh, basis)
        fdata.update(bf)
    mesh = quadratic_tet_mesh(basis.doflocs, basis.element_dofs, point_data=data, cell_data=cdata, field_data=fdata)
    return write_vtu(path, mesh)


STRESS_COMPONENTS = VOIGT
