"""The mesh plan of a check, resolved once: which throw models are meshed, with which size.

A geometry with a single throw stands for every throw of the engine (key ``ALL_THROWS``,
``fe_crank.throw_scope``, each throw assessed on it with its own loads); so do several
throws that differ only in name and angle; otherwise the geometry's throw names must be
the engine's throw names, so that no throw goes unchecked.  The size is the command
line's ``--mesh-size``, else the load case's ``[mesh] size`` (``coarse`` by default);
``[mesh] symmetric = false`` meshes a mirror-symmetric throw whole.  When the whole
shaft is modelled too (``shaft``: its layout, held by the plan), the plan decides its
mesh options, and the throws are meshed with them (``mesh.shaft.shaft_options``: end
faces split into rotated-copy sectors), so that both models mesh each throw once (one
cached mesh).  The plan's models are meshed by one entry point,
``fe_crank.cad.source.mesh_models``.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

from fe_crank.errors import InputError
from fe_crank.geometry.shaft import ShaftLayout
from fe_crank.geometry.spec import CrankGeometry, ThrowSpec
from fe_crank.mesh.options import PRESETS, MeshOptions, MeshSection
from fe_crank.throw_scope import ALL_THROWS

#: mesh presets whose verdicts may be signed off (fillet elements <= r/4, IACS UR M53
#: Appendix (FE) guidance on fillet resolution)
SIGN_OFF_PRESETS = ("coarse", "medium", "fine")
SIGN_OFF_RULE = "coarse or finer, fillet elements <= r/4"


@dataclass(frozen=True)
class MeshPlan:
    """How a load case is meshed: ``preset`` (its name), the resolved ``options``, the
    element-count limit, the cache folder, ``throws``: key -> geometry throw name (a
    key is an engine throw's name, or ``ALL_THROWS``) and ``shaft``: the whole shaft's
    layout when it is meshed too, with ``options`` (None: the throw models alone)."""

    preset: str
    options: MeshOptions
    max_elements: int | None
    cache_dir: str | None
    throws: dict[str, str]
    shaft: ShaftLayout | None = None

    @property
    def sign_off(self) -> bool:
        """Whether the preset meets the sign-off rule (``SIGN_OFF_PRESETS``)."""
        return self.preset in SIGN_OFF_PRESETS


def preset_of(section: MeshSection, size: str | None = None) -> str:
    """The preset a case is meshed with: ``size`` (the command line's), else the section's."""
    return size or section.size


def plan_meshes(
    geometry: CrankGeometry,
    engine_throws: tuple[str, ...],
    section: MeshSection,
    *,
    size: str | None = None,
    max_elements: int | None = None,
    cache_dir: str | None = None,
    file: str = "",
    shaft: ShaftLayout | None = None,
) -> MeshPlan:
    """The plan of one load case (module docstring); ``size``/``max_elements`` override the
    section's; ``shaft``: the whole shaft's layout when it is modelled too.  An engine whose
    throws the geometry does not cover is an InputError."""
    keys = throw_keys(geometry, engine_throws, file=file)
    return mesh_plan(keys, section, size=size, max_elements=max_elements, cache_dir=cache_dir, shaft=shaft)


def mesh_plan(
    throws: dict[str, str],
    section: MeshSection,
    *,
    size: str | None = None,
    max_elements: int | None = None,
    cache_dir: str | None = None,
    shaft: ShaftLayout | None = None,
    min_sectors: int = 1,
) -> MeshPlan:
    """The plan for the keys ``throws`` (key -> the throw model's name; a CAD geometry's
    come from ``fe_crank.cad.engine.engine_keys``) with the section's and the command
    line's sizes; with the whole shaft ``shaft``, the options are the shaft's
    (``mesh.shaft.shaft_options``; ``min_sectors``: its, a drawn shaft's
    ``fe_crank.cad.whole.MIN_SECTORS``)."""
    from fe_crank.mesh.shaft import shaft_options

    preset = preset_of(section, size)
    options = PRESETS[preset]
    if not section.symmetric:  # [mesh] symmetric = false: mesh a symmetric throw whole (docs/geometry.md)
        options = dataclasses.replace(options, symmetric=False)
    if shaft is not None:
        options = shaft_options(shaft, options, min_sectors)
    return MeshPlan(
        preset=preset,
        options=options,
        max_elements=max_elements or section.max_elements,
        cache_dir=cache_dir,
        throws=throws,
        shaft=shaft,
    )


def throw_keys(geometry: CrankGeometry, engine_throws: tuple[str, ...], *, file: str = "") -> dict[str, str]:
    """Which geometry throw to mesh for each key handed to the assessment (module docstring)."""
    names = [t.name for t in geometry.throws]
    engine = list(engine_throws)
    if len(names) == 1:
        return {names[0] if engine == names else ALL_THROWS: names[0]}
    if sorted(names) != sorted(engine) and _all_equal(geometry.throws):
        # equal throws under other names (e.g. "1", "2" for the engine's "A", "B"):
        # one model stands for every throw, each assessed with its own loads
        return {ALL_THROWS: names[0]}
    if sorted(names) != sorted(engine):
        raise InputError(
            f"the geometry's throws {names} must be the engine's throws {engine} "
            "(or give one throw that stands for all)",
            file=file,
            key="geometry",
        )
    return {n: n for n in engine}


def _all_equal(throws: tuple[ThrowSpec, ...]) -> bool:
    """Throws that differ only in name and angle give the same throw model."""
    norm = [dataclasses.replace(t, name="", angle=0.0) for t in throws]
    return all(n == norm[0] for n in norm)
