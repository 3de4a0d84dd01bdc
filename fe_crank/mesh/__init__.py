"""Quadratic tetrahedral meshes of one crank throw, graded into the fillets, cached on disk.

:func:`mesh_throw` builds the throw (``fe_crank.geometry.throw.add_throw``), meshes it
with gmsh (second-order tetrahedra, curved isoparametric geometry), converts it to a
scikit-fem ``MeshTet2`` with named boundaries and subdomains
(``fe_crank.gmsh_io.model_to_skfem``), checks it and writes ``.msh`` and ``.vtu``.

Element size: a ``Distance`` + ``Threshold`` size field around every fillet surface
sets the element edge there to ``r / fillet_divisions`` (times a safety factor, since
gmsh's edges scatter around the target); IACS UR M53 (appendix, FE guidance) asks for
at most ``r/4`` in the fillets, which the ``coarse``/``medium``/``fine`` presets keep.
Away from the fillets the size grows linearly with the distance (``grading``) to
``size_max``.  Only the ``test`` preset relaxes the fillet rule (edge about ``r``) so that other
stages' unit tests mesh a whole throw in a few seconds.

Cache: ``cache_dir/<key>/`` with ``key`` = SHA-256 of the geometry (dimensions only,
not its name or file), the throw, the mesh options, the fe-crank and gmsh versions and
the cache format.  Entries are written to a temporary folder
(``.<key>.partial-<pid>-*``) and renamed into place (atomic on POSIX), so a reader never
sees half an entry; temporary folders of killed processes are removed by the next
run, and an entry that cannot be read back whole is discarded and rebuilt.
"""

from fe_crank.mesh.build import mesh_throw
from fe_crank.mesh.cache import cache_key
from fe_crank.mesh.export import write_vtu
from fe_crank.mesh.options import CACHE_FORMAT, DEFAULT_CACHE_DIR, PRESETS, MeshOptions, resolve_options
from fe_crank.mesh.quality import STRAIGHTEN_BELOW
from fe_crank.mesh.types import MeshStats, ThrowMesh

__all__ = [
    "CACHE_FORMAT",
    "DEFAULT_CACHE_DIR",
    "PRESETS",
    "STRAIGHTEN_BELOW",
    "MeshOptions",
    "MeshStats",
    "ThrowMesh",
    "cache_key",
    "mesh_throw",
    "resolve_options",
    "write_vtu",
]
