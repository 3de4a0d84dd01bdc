"""What ``mesh_throw`` returns: the mesh, its statistics and where its files are."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from skfem import Mesh

from fe_crank.mesh.options import MeshOptions


@dataclass(frozen=True)
class MeshStats:
    nodes: int
    elements: int
    p2_dofs: int  # 3 displacement components per node of the quadratic mesh
    min_quality: float  # gmsh minSICN of the linear tetrahedra (1 ideal, <= 0 inverted)
    straightened: int  # quadratic elements whose mid-edge nodes were moved to the midpoints (see straighten_poor)
    min_jacobian_ratio: float  # min/max of the quadratic map's Jacobian over each element, worst element
    fillet_max_edge: dict[str, float]  # m, longest triangle edge on each fillet surface
    fillet_radii: dict[str, float]
    build_seconds: float
    from_cache: bool = False
    symmetry: tuple[int, ...] = ()  # axes of the mirror planes the mesh was built with (ThrowMesh.symmetry)


@dataclass(frozen=True)
class ThrowMesh:
    """A meshed throw: scikit-fem ``MeshTet2`` with named boundaries/subdomains (throw frame)."""

    mesh: Mesh
    stats: MeshStats
    fillet_radii: dict[str, float]
    msh_path: Path | None  # None: meshed without the cache (``cache_dir=None``): no files written
    vtu_path: Path | None
    throw: str
    key: str
    options: MeshOptions = field(default_factory=MeshOptions)
    #: axes normal to the planes through the origin across which the mesh is an exact mirror
    #: image of itself (0: x = 0, the crank plane; 2: z = 0, the mid-plane); () when not mirrored
    symmetry: tuple[int, ...] = ()

    @property
    def cache_dir(self) -> Path | None:
        """The mesh cache this mesh is an entry of (its folder is ``cache_dir / key``), or None."""
        if self.msh_path is None:
            return None
        folder = Path(self.msh_path).parent
        return folder.parent if folder.name == self.key else None
