"""The SCF mode on a mesh UR M53's FE appendix accepts: refine until it does, bounded.

IACS UR M53 Appendix III (2.1-2.3) accepts an SCF model whose fillet elements are at most
r/4, which has at least 6 elements across the web thickness, and whose stress at each
factor's peak meets the principal-stress (< 3 %) or the averaging (< 5 %) criterion
(``rules.m53.scf_mode.ScfResult.mesh_ok``).  Factors of a mesh it does not accept must not enter a
verdict; so the check's SCF stage starts from the check's throw mesh at r/4
(``scf.scf_mesh``) and, while the appendix rejects the mesh, meshes the throw again:

* fillet elements longer than r/4, or a peak that meets neither 2.3 criterion: the fillet
  element edge shrinks by ``FILLET_STEP`` (r/4 -> r/6 -> r/9 ...);
* fewer than 6 elements across a web: an edge of at most W/6 in the webs
  (``MeshOptions.web_divisions``), then scaled by 6/n (10 % more) while n stays short.

At most ``MAX_REFINEMENTS`` new meshes; a result still rejected is returned as it is (its
``mesh_ok`` False, its ``refinement`` naming each mesh tried and why), and the verdict
refuses the M53 criterion on it (``assess.criteria.judge``).
"""

from __future__ import annotations

import dataclasses

from fe_crank.cad.config import CadInput
from fe_crank.cad.source import mesh_source_throw
from fe_crank.fe.throw.options import Material
from fe_crank.geometry.spec import CrankGeometry
from fe_crank.mesh.options import MeshOptions
from fe_crank.mesh.types import ThrowMesh
from fe_crank.rules.m53 import calculation as m53
from fe_crank.rules.m53.scf_mode import ScfResult, compute_scf, scf_mesh
from fe_crank.rules.m53.web_mesh import MIN_ELEMENTS_ACROSS

MAX_REFINEMENTS = 3
FILLET_STEP = 1.5
WEB_MARGIN = 1.1


def refined_options(options: MeshOptions, result: ScfResult) -> tuple[MeshOptions, str]:
    """(mesh options of the next mesh, why) for a result the appendix rejects (module doc)."""
    why = []
    new = options
    peaks = sorted(k for k, q in result.quality.items() if not q["mesh_ok"])
    if not result.size_ok or peaks:
        new = dataclasses.replace(new, fillet_divisions=options.fillet_divisions * FILLET_STEP)
        if not result.size_ok:
            why.append(f"fillet elements longer than r/4 (up to r/{1 / max(result.element_size.values()):.1f})")
        if peaks:
            why.append(f"neither App. III 2.3 criterion met at the peak of {', '.join(peaks)}")
    if not result.web_ok:
        across = min(w.across for w in result.web_elements)
        web = (
            float(MIN_ELEMENTS_ACROSS)
            if options.web_divisions is None
            else options.web_divisions * WEB_MARGIN * MIN_ELEMENTS_ACROSS / across
        )
        new = dataclasses.replace(new, web_divisions=web)
        why.append(f"{across:.1f} elements across the web (>= {MIN_ELEMENTS_ACROSS})")
    return new, "; ".join(why)


def _words(options: MeshOptions) -> str:
    web = "" if options.web_divisions is None else f", web edge <= W/{options.web_divisions:.3g}"
    return f"fillets r/{options.fillet_divisions:.3g}{web}"


def accepted_scf(
    throw_mesh: ThrowMesh,
    geometry: object,
    material: Material,
    geo: m53.M53Geometry,
    *,
    web_centres: tuple[float, float] | None = None,
    solver: str = "auto",
    max_refinements: int = MAX_REFINEMENTS,
    first: ScfResult | None = None,
) -> ScfResult:
    """The SCF mode (``scf.compute_scf``) on the check's ``throw_mesh`` (a ``ThrowMesh`` of
    ``geometry``: a ``CrankGeometry`` or a CAD file's ``CadInput``), refined until UR M53
    App. III accepts the mesh or ``max_refinements`` new meshes were made (module docstring).

    ``first``: the SCF mode already solved on the first mesh (``scf_mesh(throw_mesh,
    geometry)``) with the same material, geometry, web centres and solver, e.g. this
    function's result with ``max_refinements=0``: taken as the first mesh's result instead
    of solving that mesh again."""
    mesh = scf_mesh(throw_mesh, geometry)
    tried: list[str] = []
    while True:
        if first is not None and not tried:
            result = first
        else:
            result = compute_scf(mesh, material, geo, web_centres=web_centres, solver=solver)
        opts = mesh.options
        if result.mesh_ok or len(tried) >= max_refinements or not isinstance(geometry, CrankGeometry | CadInput):
            return dataclasses.replace(result, refinement=tuple(tried))
        new, why = refined_options(opts, result)
        tried.append(f"{_words(opts)}: {why}")
        mesh = mesh_source_throw(geometry, mesh.throw, size=new, cache_dir=mesh.cache_dir)


__all__ = ["MAX_REFINEMENTS", "FILLET_STEP", "refined_options", "accepted_scf"]
