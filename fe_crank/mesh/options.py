"""Mesh size controls and their presets ("test", "coarse", "medium", "fine"), and the
default cache folder.  The presets are the one list the CLI, the ``[mesh]`` load-case
section and ``mesh_throw`` use."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from fe_crank.errors import MeshError

CACHE_FORMAT = 5  # 2: Netgen optimisation and straightening of poorly curved elements (minSJ <= 0.1); 3: mirrored meshes of symmetric throws, `symmetry` in stats; 4: the end-face sectors' edges with one stated master each (the same mesh on every run); 5: pear webs' arcs broken at the circle's parametric seam (a throw with one counterweight meshes whole)
DEFAULT_CACHE_DIR = Path(".cache") / "meshes"

#: the gmsh options every throw mesh is generated with (beside the session's single thread,
#: ``fe_crank.gmsh_io``, and the size fields); part of the mesh cache key.  Delaunay 3D;
#: Netgen's optimiser removes most boundary slivers (seed-001 coarse: 3866 -> 98 elements
#: with Jacobian ratio < 0.1); gmsh's random seed stated, not left to its default.
GENERATE_OPTIONS: dict[str, float] = {
    "Mesh.Algorithm3D": 1,
    "Mesh.Optimize": 1,
    "Mesh.OptimizeNetgen": 1,
    "Mesh.ElementOrder": 1,
    "Mesh.RandomSeed": 1,
}

FILLET_SAFETY = (
    0.65  # target edge = SAFETY * r / fillet_divisions: gmsh's surface edges exceed the target by up to ~40 %
)


@dataclass(frozen=True)
class MeshOptions:
    """Mesh size controls.

    ``size_max = crankpin_diameter / coarse_divisions`` unless given (m).  Fillet
    element edge ``<= r / fillet_divisions``; size grows away from the fillets by
    ``grading`` m per m of distance.  ``symmetric``: where the throw is exactly
    mirror-symmetric (``fe_crank.mesh.planes.symmetry_planes``), mesh its fundamental part
    and mirror it, so the mesh is an exact mirror image too (``ThrowMesh.symmetry``).
    """

    coarse_divisions: float = 4.0
    fillet_divisions: float = 4.0
    grading: float = 0.35
    size_max: float | None = None
    bore_divisions: float = 6.0  # elements round the oil bore circumference / pi
    optimize_high_order: bool = False  # gmsh's HighOrder optimiser can abort the process (uncaught C++ error)
    interface_sectors: int = (
        1  # end faces split into this many rotated-copy sectors (fe_crank.mesh.interface; whole shaft)
    )
    symmetric: bool = True  # mesh the fundamental part of a mirror-symmetric throw and mirror it (fe_crank.mesh.planes; docs/geometry.md)
    #: elements across the web thickness W: edge <= W / web_divisions in the webs (UR M53 App.
    #: III 2.2 asks for at least 6 in its SCF models, ``rules.m53.web_mesh``); None: no web control
    web_divisions: float | None = None

    def __post_init__(self):
        for name in ("coarse_divisions", "fillet_divisions", "grading", "bore_divisions"):
            v = getattr(self, name)
            if not (np.isfinite(v) and v > 0):
                raise MeshError(f"mesh option {name} must be positive (got {v})")
        if self.web_divisions is not None and not (np.isfinite(self.web_divisions) and self.web_divisions > 0):
            raise MeshError(f"mesh option web_divisions must be positive (got {self.web_divisions})")
        if not 1 <= self.interface_sectors <= 24:
            raise MeshError(f"mesh option interface_sectors must be 1 ... 24 (got {self.interface_sectors})")
        if self.size_max is not None and not self.size_max > 0:
            raise MeshError(f"mesh option size_max must be positive (got {self.size_max})")


PRESETS: dict[str, MeshOptions] = {
    "test": MeshOptions(coarse_divisions=1.5, fillet_divisions=1.0, grading=2.0),
    "coarse": MeshOptions(coarse_divisions=3.0, fillet_divisions=4.0, grading=1.5),
    "medium": MeshOptions(coarse_divisions=4.0, fillet_divisions=5.0, grading=1.0),
    "fine": MeshOptions(coarse_divisions=6.0, fillet_divisions=8.0, grading=0.7),
}


def resolve_options(size: str | MeshOptions) -> MeshOptions:
    if isinstance(size, MeshOptions):
        return size
    try:
        return PRESETS[size]
    except KeyError:
        raise MeshError(f"unknown mesh size {size!r}; pick one of {sorted(PRESETS)} or pass MeshOptions") from None


@dataclass(frozen=True)
class MeshSection:
    """The load case's ``[mesh]`` table: ``size`` is a preset of ``fe_crank.mesh``
    ("coarse", the default, keeps fillet elements within r/4 as IACS UR M53 asks;
    "test" is for quick trials and demonstrations only)."""

    size: str = "coarse"
    max_elements: int | None = None  # limit on the estimated element count (docs/limits.md)
    convergence: bool | None = None  # hot-spot convergence study; None: on unless size = "test"
    symmetric: bool = True  # mesh a mirror-symmetric throw's fundamental part and mirror it (MeshOptions.symmetric)
