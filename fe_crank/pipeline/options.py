"""How a check runs: ``CheckOptions`` (plain data, pickled to worker processes)."""

from __future__ import annotations

from dataclasses import dataclass

from fe_crank.mesh.options import DEFAULT_CACHE_DIR


@dataclass(frozen=True)
class CheckOptions:
    """How ``run_case`` runs: all fields plain data so the options pickle to workers.

    ``mesh_size`` is a preset of ``fe_crank.mesh`` ("test", "coarse", "medium",
    "fine") that overrides the load case's ``[mesh] size`` (default "coarse"); ``cache_dir`` holds meshes keyed by the hash of their inputs;
    ``render`` switches the pyvista pictures on; ``write_vtu`` the ``.vtu`` fields;
    ``allow_outside_paths`` lets include paths leave the load case's folder tree;
    ``max_elements`` overrides the estimated-element-count limit (docs/limits.md);
    ``convergence`` the hot-spot convergence study (None: the load case's ``[mesh]
    convergence``, by default on unless the mesh is ``test``; ``fe_crank.fe.refinement.convergence``).
    """

    mesh_size: str | None = None
    cache_dir: str = str(DEFAULT_CACHE_DIR)
    render: bool = True
    write_vtu: bool = True
    allow_outside_paths: bool = False
    max_elements: int | None = None
    convergence: bool | None = None
    assess_threads: int | None = None


def cores_available() -> int:
    """The cores this process may run on (its CPU affinity; the CPU count where the
    platform has no affinity)."""
    import os

    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # pragma: no cover - platforms without sched_getaffinity
        return max(1, os.cpu_count() or 1)


def assess_threads(options: CheckOptions, processes: int = 1) -> int:
    """Threads of the assess stage of one case: ``options.assess_threads`` when set, else
    the cores this process may use shared among the ``processes`` cases that run at the
    same time (``fe-crank check -j N``), at least 1."""
    if options.assess_threads is not None:
        return max(1, int(options.assess_threads))
    return max(1, cores_available() // max(1, int(processes)))
