"""Offscreen pictures from quadratic cells: not blank, the colour bar reaches the peak
of the mid-edge nodes, round ticks, exaggeration stated, VTU round trip."""

from __future__ import annotations

import numpy as np
import pytest
from helpers.images import image_statistics
from skfem import Basis, ElementTetP2, MeshTet, MeshTet2

from fe_crank.fe.core.result_fields import quadratic_tet_mesh, write_vtu
from fe_crank.report.render import (
    exaggeration_factor,
    grid_of,
    iso_direction,
    nice_length,
    nice_range,
    render_field,
)


def test_exaggeration_draws_the_largest_displacement_as_the_chosen_fraction():
    # s = fraction * L / max|u|, rounded to one significant digit
    assert exaggeration_factor(1e-5, 0.2, fraction=0.05) == pytest.approx(1000.0)
    assert exaggeration_factor(3e-5, 0.2, fraction=0.05) == pytest.approx(300.0)  # 333 -> 300
    assert exaggeration_factor(0.0, 0.2) == 1.0
    assert exaggeration_factor(float("nan"), 0.2) == 1.0


def test_colour_bar_ticks_are_round_and_contain_the_peak():
    # 129.2 MPa: steps of 20 give 0..140 (7 intervals, 8 labels), the least waste
    # among 4..8 intervals of 1/2/2.5/5 x 10^k (25 -> 150, 50 -> 150)
    assert nice_range(0.0, 129.2) == (0.0, 140.0, 8, "%.0f")
    # 0.05725: steps of 0.01 -> 0..0.06, two decimals, never "0.05725"
    lo, hi, n, fmt = nice_range(0.0, 0.05725)
    assert (lo, hi, fmt) == (0.0, pytest.approx(0.06), "%.2f") and 4 <= n <= 9
    lo, hi, n, fmt = nice_range(0.0, 15.99)
    assert hi == 16.0 and fmt == "%.0f"
    # a scale bar a quarter of a 0.3 m part: 0.075 -> 0.05 m (1, 2, 5 x 10^k)
    assert nice_length(0.3) == pytest.approx(0.05)


@pytest.fixture(scope="module")
def cube():
    """Unit cube of quadratic tets with a field that peaks at a mid-edge node only:
    f = 100 (1 - 4 (x - 1/2)^2) is 0 at every corner node (x = 0, 1/2 is a mid-edge
    coordinate of the once-refined cube: corners at x = 0, 1/2, 1)."""
    m = MeshTet2.from_mesh(MeshTet().refined(1))
    b = Basis(m, ElementTetP2())
    x, y, z = b.doflocs
    f = 100 * (1 - 16 * (x - 0.25) ** 2) * (x < 0.5)  # 100 at x = 1/4 (mid-edge only), 0 at x = 0, 1/2, 1
    u = np.stack([0 * x, 1e-5 * z**2, 0 * z]).T
    mesh = quadratic_tet_mesh(b.doflocs, b.element_dofs, point_data={"f_MPa": f, "displacement_m": u})
    return mesh, b


def test_grid_has_quadratic_cells_and_the_cube_volume(cube):
    mesh, b = cube
    grid = grid_of(mesh)
    assert grid.n_points == b.doflocs.shape[1] and grid.n_cells == b.element_dofs.shape[1]
    import pyvista as pv

    assert set(np.unique(grid.celltypes)) == {pv.CellType.QUADRATIC_TETRA}
    assert grid.volume == pytest.approx(1.0, rel=1e-12)  # unit cube, closed form


def test_colour_bar_reaches_the_mid_edge_peak(cube, tmp_path):
    # linear cells from the corners would see max 0 here; the quadratic grid sees 100
    mesh, _ = cube
    v = render_field(tmp_path / "f.png", grid_of(mesh), "f_MPa", title="f [MPa]", window_size=(400, 300))
    assert v.peak == pytest.approx(100.0, rel=1e-12)
    assert v.clim[0] == 0.0 and 100.0 <= v.clim[1] <= 125.0


def test_render_is_not_blank_and_the_blank_control_is(cube, tmp_path):
    mesh, _ = cube
    v = render_field(
        tmp_path / "vm.png",
        grid_of(mesh),
        "f_MPa",
        title="von Mises [MPa]",
        displacement="displacement_m",
        scale=1000.0,
        hotspot=np.array([1.0, 1.0, 1.0]),
        window_size=(400, 300),
    )
    assert v.exaggeration == 1000.0
    st = image_statistics(v.file)
    assert st["coverage"] > 0.15 and st["std"] > 0.05 and st["colours"] > 200
    # control: the statistics do flag a blank picture
    import matplotlib.pyplot as plt

    plt.imsave(tmp_path / "blank.png", np.ones((30, 40, 3)))
    blank = image_statistics(tmp_path / "blank.png")
    assert blank["coverage"] == 0.0 and blank["std"] == 0.0


def test_close_up_fills_the_frame(cube, tmp_path):
    mesh, _ = cube
    v = render_field(
        tmp_path / "close.png",
        grid_of(mesh),
        "f_MPa",
        title="MPa",
        hotspot=np.array([1.0, 1.0, 1.0]),
        focus=(np.array([1.0, 1.0, 1.0]), 0.2),
        window_size=(400, 300),
    )
    assert image_statistics(v.file)["coverage"] > 0.6


def _background(img: np.ndarray) -> np.ndarray:
    """Pixels of the white background (any channel within 2 % of white)."""
    return np.all(img[..., :3] > 0.98, axis=-1)


def test_colour_bar_has_its_own_strip_and_never_covers_the_close_up(cube, tmp_path):
    """The close-up fills the frame, so a colour bar drawn over the scene would sit on the
    part.  Check: the same close-up drawn without the bar (same camera: the bar is in a
    viewport of its own) has no part pixel anywhere in the bar's strip, while the bar
    actor's box, as VTK placed it, lies in that strip and is drawn (not background)."""
    import matplotlib.image as mpimg

    mesh, _ = cube
    kw = dict(
        title="von Mises [MPa]",
        hotspot=np.array([1.0, 1.0, 1.0]),
        window_size=(500, 380),
        focus=(np.array([1.0, 1.0, 1.0]), 0.2),
    )
    with_bar = render_field(tmp_path / "bar.png", grid_of(mesh), "f_MPa", **kw)
    part_only = render_field(tmp_path / "part.png", grid_of(mesh), "f_MPa", show_bar=False, **kw)
    img_bar, img_part = (np.asarray(mpimg.imread(str(v.file)), float) for v in (with_bar, part_only))
    assert img_bar.shape[:2] == (380, 500)
    left, top, right, bottom = with_bar.bar_viewport
    assert (left, top, right, bottom) == (420, 0, 500, 380)  # BAR_STRIP 0.16 of 500 px at the right edge
    assert with_bar.part_viewport == (0, 0, 420, 380)
    bl, bt, br, bb = with_bar.bar_box
    assert left <= bl < br <= right and top <= bt < bb <= bottom
    part = ~_background(img_part)
    assert part[:, :left].mean() > 0.9  # the close-up fills its viewport
    assert not part[:, left:].any()  # and never reaches the bar's strip
    assert (~_background(img_bar[bt:bb, bl:br])).mean() > 0.1  # control: the bar is drawn in its box
    # the bar changes nothing in the part's viewport
    assert np.abs(img_bar[:, :left] - img_part[:, :left]).max() < 0.02
    # round ticks: 0..100 in steps of 20 (nice_range)
    assert with_bar.clim == (0.0, 100.0)


def test_isometric_view_faces_the_hot_spot():
    # hot spot below the centre on -z, towards +y: the camera comes from -z, +y; x tied
    # (cosine 0) goes to +x, the first octant
    d = iso_direction(np.zeros(3), [np.array([0.0, 0.3, -1.0])])
    np.testing.assert_allclose(d * np.sqrt(3), [1.0, 1.0, -1.0])
    # the hot spot counts twice: a second mark on the opposite side does not turn the view
    d = iso_direction(np.zeros(3), [np.array([-1.0, -1.0, -1.0]), np.array([1.0, 1.0, 1.0])])
    np.testing.assert_allclose(d * np.sqrt(3), [-1.0, -1.0, -1.0])
    np.testing.assert_allclose(iso_direction(np.zeros(3), []) * np.sqrt(3), [1.0, 1.0, 1.0])


def test_vtu_round_trip_keeps_tetra10_and_fields(cube, tmp_path):
    import meshio

    mesh, b = cube
    back = meshio.read(write_vtu(tmp_path / "field.vtu", mesh))
    assert [c.type for c in back.cells] == ["tetra10"]
    np.testing.assert_allclose(back.point_data["f_MPa"], mesh.point_data["f_MPa"])
    np.testing.assert_allclose(back.point_data["displacement_m"], mesh.point_data["displacement_m"])
    assert [p.name for p in tmp_path.iterdir()] == ["field.vtu"]
