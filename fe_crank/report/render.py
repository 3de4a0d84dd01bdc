"""Offscreen pyvista pictures of a stress field (no window is ever opened).

The pictures are drawn from the same ``meshio.Mesh`` of quadratic tetrahedra that is
written as the ``.vtu`` file (``fe_crank.fe.core.result_fields``): every P2 node, mid-edge nodes
included, carries its value, so the colour bar, the written file and the verdict
table agree on the peak.  Only ``pyvista.Plotter(off_screen=True)`` is used: no
process-wide pyvista or VTK setting is changed.  pyvista is imported inside the
functions so that importing the report package stays light.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np


@dataclass(frozen=True)
class RenderedView:
    """A picture written to disk and what its colour bar shows."""

    file: Path
    clim: tuple[float, float]  # colour-bar range, display unit
    peak: float  # largest value of the drawn field on the whole part, display unit
    exaggeration: float = 1.0
    #: pixel boxes (left, top, right, bottom; image rows from the top, right/bottom
    #: exclusive) of the viewport the part is drawn in and of the colour bar's strip
    part_viewport: tuple[int, int, int, int] = (0, 0, 0, 0)
    bar_viewport: tuple[int, int, int, int] = (0, 0, 0, 0)
    #: pixel box of the colour bar actor (bar, ticks and title) as VTK placed it; None without a bar
    bar_box: tuple[int, int, int, int] | None = None


#: share of the picture's width given to the colour bar's own viewport (right edge)
BAR_STRIP = 0.16
#: the bar inside its strip (normalised coordinates of that viewport)
BAR_PLACE = {"position_x": 0.3, "position_y": 0.1, "width": 0.5, "height": 0.78}


def exaggeration_factor(max_displacement: float, model_size: float, *, fraction: float = 0.05) -> float:
    """Scale for drawing a deformed shape: the largest displacement is drawn as
    ``fraction`` of the model size, ``s = fraction * L / max|u|`` (1 when the
    model does not move), rounded to one significant digit."""
    if not max_displacement > 0 or not np.isfinite(max_displacement):
        return 1.0
    s = fraction * model_size / max_displacement
    mag = 10 ** np.floor(np.log10(s))
    return float(np.round(s / mag) * mag)


def nice_step(span: float, intervals: int = 5) -> float:
    """A round tick step (1, 2, 2.5 or 5 x 10^k) giving about ``intervals`` intervals
    over ``span``."""
    if not span > 0 or not np.isfinite(span):
        return 1.0
    raw = span / intervals
    mag = 10 ** math.floor(math.log10(raw))
    for m in (1.0, 2.0, 2.5, 5.0, 10.0):
        if m * mag >= raw * (1 - 1e-12):
            return m * mag
    return 10.0 * mag  # pragma: no cover


def nice_range(lo: float, hi: float) -> tuple[float, float, int, str]:
    """Colour-bar range on round ticks containing [lo, hi]: (low, high, number of
    labels, printf format).  Fields with ``lo >= 0`` (von Mises) start at 0.  Of the
    round steps giving 4 to 8 intervals, the one whose top lies closest above ``hi``
    (least colour range wasted) is taken."""
    lo = 0.0 if lo >= 0 else lo
    best: tuple[float, float, float] | None = None
    for intervals in (5, 4, 6, 7, 8):
        step = nice_step(hi - lo, intervals)
        a, b = math.floor(lo / step) * step, math.ceil(hi / step) * step
        if b <= a:
            b = a + step
        if best is None or b - hi < best[1] - hi - 1e-12 * abs(hi):
            best = (a, b, step)
    assert best is not None  # the loop ran
    a, b, step = best
    frac = f"{step:.9f}".rstrip("0").split(".")[1]  # decimals the step needs (2.5 -> 1, 0.05 -> 2)
    return a, b, int(round((b - a) / step)) + 1, f"%.{len(frac)}f"


def nice_length(size: float) -> float:
    """A round length (1, 2, 5 x 10^k m) of about a quarter of ``size`` for a scale bar."""
    raw = 0.25 * size
    mag = 10 ** math.floor(math.log10(raw))
    return max(m * mag for m in (1.0, 2.0, 5.0) if m * mag <= raw * (1 + 1e-12))


def grid_of(mesh, display: dict[str, np.ndarray] | None = None):
    """pyvista grid of a ``meshio.Mesh`` (quadratic cells kept), plus display-only
    point arrays (e.g. von Mises in MPa) that are not written to the file."""
    import pyvista as pv

    grid = pv.from_meshio(mesh)
    for k, v in (display or {}).items():
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
    hotspot_label: str = "hot spot",
    marks: tuple[tuple[np.ndarray, str], ...] = (),
    focus: tuple[np.ndarray, float] | None = None,
    view: str = "iso",
    text: str = "",
    unit: str = "MPa",
    window_size: tuple[int, int] = (1000, 760),
    show_bar: bool = True,
) -> RenderedView:
    """Draw ``grid``'s outer surface coloured by ``scalars`` into a PNG.

    The surface of the quadratic cells is subdivided once, so mid-edge values are
    drawn.  The colour bar spans round ticks from 0 (or the minimum) to just above the
    field's peak on the whole part; it has a viewport of its own, a strip of
    ``BAR_STRIP`` of the width at the right edge, so it never covers the part (the part's
    viewport is the rest; ``show_bar=False`` leaves the strip empty).  The peak is
    printed with ``text`` in the upper left.  ``displacement`` names a (n, 3) point
    array drawn times ``scale``; ``hotspot`` (3,) is marked with a magenta sphere and
    ``hotspot_label``, each of ``marks`` (point, label) with a black one; ``focus`` =
    (centre, radius) zooms onto a region (a fillet close-up).  An axis triad and a
    length scale are drawn.
    """
    import pyvista as pv

    values = np.asarray(grid.point_data[scalars], float)
    finite = values[np.isfinite(values)]
    peak = float(finite.max()) if finite.size else 0.0
    lo, hi, n_labels, fmt = nice_range(float(finite.min()) if finite.size else 0.0, peak)
    surf = grid.extract_surface(nonlinear_subdivision=1, algorithm="dataset_surface")
    if displacement is not None:
        surf = surf.copy()
        surf.points = surf.points + scale * np.asarray(surf.point_data[displacement])
    # the part in the left viewport, the colour bar alone in a strip on the right: the
    # bar can never cover the part, whatever the zoom
    p = pv.Plotter(
        off_screen=True,
        window_size=list(window_size),
        shape=(1, 2),
        col_weights=[1.0 - BAR_STRIP, BAR_STRIP],
        border=False,
    )
    try:
        p.set_background("white")
        p.subplot(0, 0)
        actor = p.add_mesh(
            surf,
            scalars=scalars,
            cmap="turbo",
            clim=(lo, hi),
            show_edges=False,
            smooth_shading=True,
            ambient=0.3,
            show_scalar_bar=False,
        )
        if show_bar:
            p.subplot(0, 1)
            p.add_scalar_bar(
                title=title.replace(" [", "\n["),
                mapper=actor.mapper,
                color="black",
                vertical=True,
                fmt=fmt,
                n_labels=n_labels,
                **BAR_PLACE,
                title_font_size=16,
                label_font_size=14,
            )
            p.subplot(0, 0)
        rad = (0.04 * focus[1]) if focus else 0.015 * surf.length
        spots = ([(hotspot, hotspot_label, "magenta")] if hotspot is not None else []) + [
            (pt, lab, "black") for pt, lab in marks
        ]
        for pt, lab, colour in spots:
            hp = np.asarray(pt, float).reshape(3)
            p.add_mesh(pv.Sphere(radius=rad, center=hp), color=colour)
            p.add_point_labels(
                hp[None, :], [lab], font_size=16, text_color="black", shape_opacity=0.6, always_visible=True
            )
        head = f"peak on the part {peak:.4g} {unit}".rstrip()
        p.add_text("\n".join([head, text] if text else [head]), position="upper_left", font_size=10, color="black")
        p.add_axes(color="black", labels_off=False)
        if view == "front":  # from the front (free) end, looking along +z
            p.view_xy(negative=True)
        elif view == "side":
            p.view_yz()
        else:  # isometric, from the octant facing the marked points
            pts = [pt for pt, _, _ in spots]
            p.view_vector(iso_direction(np.asarray(surf.center), pts), viewup=(0.0, 1.0, 0.0))  # y up: crankpin up
        bounds = np.asarray(surf.bounds).reshape(3, 2)
        if focus is not None:
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
            _scale_bar(p, bounds)
            p.reset_camera()
            p.camera.zoom(0.85)  # margin for the ruler under the part (reset_camera fits the 3D props only)
        p.screenshot(str(path))
        boxes = _boxes(p, window_size)
    finally:
        p.close()
    return RenderedView(Path(path), (lo, hi), peak, scale if displacement is not None else 1.0, *boxes)


def iso_direction(centre: np.ndarray, points) -> np.ndarray:
    """The isometric direction towards the camera, ``(+-1, +-1, +-1) / sqrt(3)``, that
    faces the marked ``points`` best: of the eight octants, the one with the largest sum
    of cosines to the unit vectors from the part's ``centre`` to the points, the first
    point (the hot spot) weighted twice; ties and no points give (1, 1, 1) / sqrt(3),
    pyvista's default isometric direction.  Drawn with y (the crankpin side) up."""
    octants = [np.array([sx, sy, sz], float) / math.sqrt(3.0) for sx in (1, -1) for sy in (1, -1) for sz in (1, -1)]
    units = []
    for i, pt in enumerate(points):
        v = np.asarray(pt, float).reshape(3) - np.asarray(centre, float).reshape(3)
        n = np.linalg.norm(v)
        if n > 0:
            units.append((2.0 if i == 0 else 1.0) * v / n)
    if not units:
        return octants[0]
    score = [float(sum(d @ u for u in units)) for d in octants]
    return octants[int(np.argmax(np.asarray(score) > max(score) - 1e-12))]


def _boxes(p, window_size) -> tuple:
    """Pixel boxes (left, top, right, bottom) of the two viewports and of the colour bar
    actor, from VTK's own layout (display coordinates have their origin bottom left)."""
    w, h = window_size

    def box(x0, y0, x1, y1):
        return (int(round(x0)), int(round(h - y1)), int(round(x1)), int(round(h - y0)))

    vp = [box(*(np.asarray(r.GetViewport()) * [w, h, w, h])) for r in p.renderers]
    bar = None
    bar_renderer = p.renderers[1]
    actors = list(p.scalar_bars.values())
    if actors:
        a = actors[0]
        x0, y0 = a.GetPositionCoordinate().GetComputedDisplayValue(bar_renderer)
        x1, y1 = a.GetPosition2Coordinate().GetComputedDisplayValue(bar_renderer)
        bar = box(x0, y0, x1, y1)
    return vp[0], vp[1], bar


def _scale_bar(p, bounds: np.ndarray) -> None:
    """A ruler of round length (``nice_length``, in mm) under the part as the camera sees
    it: along the screen's horizontal, centred below the projection of the bounding box,
    so it lies flat in the picture whatever the view direction."""
    size = float(np.linalg.norm(bounds[:, 1] - bounds[:, 0]))
    if not size > 0:
        return
    length = nice_length(size)
    d = np.asarray(p.camera.position, float) - np.asarray(p.camera.focal_point, float)
    d /= np.linalg.norm(d)
    up = np.asarray(p.camera.up, float)
    up = up - (up @ d) * d
    up /= np.linalg.norm(up)
    right = np.cross(up, d)  # the camera looks along -d
    corners = np.array([[x, y, z] for x in bounds[0] for y in bounds[1] for z in bounds[2]])
    centre = corners.mean(axis=0)
    low = float(np.min((corners - centre) @ up)) - 0.03 * size
    a = centre + low * up - 0.5 * length * right
    p.add_ruler(
        list(a),
        list(a + length * right),
        title=f"{length * 1e3:g} mm",
        number_labels=2,
        show_labels=False,
        font_size_factor=0.8,
        label_color="black",
        tick_color="black",
    )
