"""How a check runs: ``CheckOptions`` (plain data, pickled to worker processes)."""

from __future__ import annotations

from dataclasses import dataclass

from fe_crank.mesh.options import DEFAULT_CACHE_DIR

#: Stage names in the order they run (also the keys of ``CaseResult.timings``).
STAGES = ("load", "dynamics", "balance", "mesh", "fe", "assess", "convergence", "report")


@dataclass(frozen=True)
class CheckOptions:
    """How ``run_case`` runs: all fields plain data so the options pickle to workers.

    ``mesh_size`` is a preset of ``fe_crank.mesh`` ("test", "coarse", "medium",
    "fine") that overrides the load case's ``[mesh] size`` (default "coarse"); ``cache_dir`` holds meshes keyed by the hash of their inputs;
    ``render`` switches the pyvista pictures on; ``write_vtu`` the ``.vtu`` fields;
    ``convergence`` the hot-spot convergence study (None: the load case's ``[mesh]
    convergence``, by default on unless the mesh is ``test``; ``fe_crank.fe.convergence``).
    """

    mesh_size: str | None = None
    cache_dir: str = str(DEFAULT_CACHE_DIR)
    render: bool = True
    write_vtu: bool = True
    convergence: bool | None = None
