"""Offscreen pyvista pictures of the stress field (no display is ever opened).

pyvista and VTK are imported lazily, inside the functions, so that importing the
report package stays light and works where no GL library is installed.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np


@dataclass(frozen=True)
class RenderedView:
    """A picture written to disk and what it shows (for the caption)."""

    file: str
    caption: str
    exaggeration: float = 1.0


def exaggeration_factor(max_displacement: float, model_size: float, *, fraction: float = 0.05) -> float:
    """Scale for drawing a deformed shape: the largest displacement is drawn as
    ``fraction`` of the model size, ``s = fraction * L / max|u|`` (1 when the
    model does not move).  The factor is stated in every caption."""
    if not max_displacement > 0 or not np.isfinite(max_displacement):
        return 1.0
    s = fraction * model_size / max_displacement
    # round to one significant digit so the caption reads "x 2000", not "x 1987.3"
    mag = 10 ** np.floor(np.log10(s))
    return float(np.round(s / mag) * mag)


def _pv():
    from vtkmodules.vtkCommonCore import vtkLogger

    vtkLogger.SetStderrVerbosity(vtkLogger.VERBOSITY_ERROR)  # no "bad X server" noise
    import pyvista as pv

    pv.OFF_SCREEN = True
    return pv


def tet_grid(points: np.ndarray, tets: np.ndarray, point_data: dict[str, np.ndarray] | None = None):
    """A pyvista grid of linear tetrahedra.

    ``points`` (3, n) or (n, 3) node coordinates (m); ``tets`` (4, m) or (m, 4)
    corner indices (quadratic meshes: the corner nodes, the mid-edge nodes stay
    unused points so nodal fields keep their length).
    """
    pv = _pv()
    pts = np.asarray(points, float)
    if pts.shape[0] == 3 and pts.shape[1] != 3:
        pts = pts.T
    t = np.asarray(tets)
    if t.shape[0] == 4 and t.shape[1] != 4:
        t = t.T
    t = np.array(t[:, :4], dtype=np.int64)
    # VTK wants positively oriented tetrahedra ((b-a) x (c-a) . (d-a) > 0); swap two
    # corners of the others so cell volumes (and normals) come out right
    a, b, c, d = (pts[t[:, k]] for k in range(4))
    neg = np.einsum("ij,ij->i", np.cross(b - a, c - a), d - a) < 0
    t[neg, 1], t[neg, 2] = t[neg, 2], t[neg, 1].copy()
    cells = np.hstack([np.full((t.shape[0], 1), 4), t]).ravel()
    grid = pv.UnstructuredGrid(cells, np.full(t.shape[0], pv.CellType.TETRA, dtype=np.uint8), pts)
    for k, v in (point_data or {}).items():
        grid.point_data[k] = np.asarray(v)
    return grid


def render_field(
    path: str | Path,
    grid,
    scalars: str,
    *,
    title: str,
    displacement: str | None = None,
    scale: float = 1.0,
    hotspot: np.ndarray | None = None,
    focus: tuple[np.ndarray, float] | None = None,
    clim: tuple[float, float] | None = None,
    view: str = "iso",
    window_size: tuple[int, int] = (1000, 760),
) -> Path:
    """Draw ``grid``'s outer surface coloured by ``scalars`` into a PNG.

    ``displacement`` names a (n, 3) point array drawn times ``scale``;
    ``hotspot`` (3,) is marked with a sphere and a label; ``focus`` =
    (centre, radius) zooms the camera onto a region (a fillet close-up).
    """
    pv = _pv()
    surf = grid.extract_surface(algorithm="dataset_surface") if _has_algorithm_kw(grid) else grid.extract_surface()
    if displacement is not None:
        surf = surf.copy()
        surf.points = surf.points + scale * np.asarray(surf.point_data[displacement])
    p = pv.Plotter(off_screen=True, window_size=list(window_size))
    try:
        p.set_background("white")
        p.add_mesh(
            surf, scalars=scalars, cmap="turbo", clim=clim, show_edges=False, smooth_shading=True, ambient=0.3,
            scalar_bar_args={"title": title, "color": "black", "vertical": False, "fmt": "%.4g",
                             "position_x": 0.2, "position_y": 0.03, "width": 0.6, "height": 0.07,
                             "title_font_size": 18, "label_font_size": 15},
        )
        if hotspot is not None:
            hp = np.asarray(hotspot, float).reshape(3)
            rad = (0.04 * focus[1]) if focus else 0.015 * surf.length
            p.add_mesh(pv.Sphere(radius=rad, center=hp), color="magenta")
            p.add_point_labels(hp[None, :], ["hot spot"], font_size=18, text_color="black",
                               shape_opacity=0.6, always_visible=True)
        if view == "front":  # from the front (free) end, looking along +z
            p.view_xy(negative=True)
        elif view == "side":
            p.view_yz()
        else:
            p.view_isometric()
        if focus is not None:
            # look at the focus from outside the part: from the side of the model's centre
            # opposite to the focus, leaning towards the chosen view direction
            centre, radius = np.asarray(focus[0], float), float(focus[1])
            view_dir = np.asarray(p.camera.position) - np.asarray(p.camera.focal_point)
            view_dir /= np.linalg.norm(view_dir)
            outward = centre - np.asarray(surf.center)
            n = np.linalg.norm(outward)
            direction = view_dir if n == 0 else outward / n + 0.6 * view_dir
            direction /= np.linalg.norm(direction)
            p.camera.focal_point = tuple(centre)
            p.camera.position = tuple(centre + 4.0 * radius * direction)
            p.camera.up = (0.0, 1.0, 0.0) if abs(direction[1]) < 0.9 else (0.0, 0.0, 1.0)
        else:
            p.reset_camera()
        p.screenshot(str(path))
    finally:
        p.close()
    return Path(path)


def _has_algorithm_kw(grid) -> bool:
    import inspect

    try:
        return "algorithm" in inspect.signature(grid.extract_surface).parameters
    except (TypeError, ValueError):  # pragma: no cover
        return False


def image_statistics(path: str | Path) -> dict[str, float]:
    """Pixel statistics of a PNG: share of pixels that differ from the corner
    (background) colour and the standard deviation of the grey level.  A blank
    render has ``coverage`` near 0 and ``std`` near 0."""
    import matplotlib.image as mpimg

    img = np.asarray(mpimg.imread(str(path)))[..., :3].astype(float)
    bg = img[0, 0]
    differs = np.any(np.abs(img - bg) > 0.02, axis=-1)
    return {"coverage": float(differs.mean()), "std": float(img.mean(axis=-1).std()),
            "colours": float(len(np.unique((img * 255).astype(np.uint8).reshape(-1, 3), axis=0)))}


def write_vtu(path: str | Path, grid) -> Path:
    """Write the grid and its point fields as a VTK XML file (ParaView) atomically."""
    import os
    import tempfile

    path = Path(path)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.stem}.", suffix=".vtu", dir=path.parent)
    os.close(fd)
    try:
        grid.save(tmp, binary=True)
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)
    return path
