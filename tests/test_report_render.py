"""Offscreen pictures: not blank, hot spot drawn, exaggeration stated, VTU round trip."""

from __future__ import annotations

import numpy as np
import pytest
from skfem import MeshTet, MeshTet2

from fe_crank.report.render import exaggeration_factor, image_statistics, render_field, tet_grid, write_vtu


def test_exaggeration_draws_the_largest_displacement_as_the_chosen_fraction():
    # s = fraction * L / max|u|, rounded to one significant digit
    assert exaggeration_factor(1e-5, 0.2, fraction=0.05) == pytest.approx(1000.0)
    assert exaggeration_factor(3e-5, 0.2, fraction=0.05) == pytest.approx(300.0)  # 333 -> 300
    assert exaggeration_factor(0.0, 0.2) == 1.0
    assert exaggeration_factor(float("nan"), 0.2) == 1.0


@pytest.fixture(scope="module")
def cube_grid():
    m = MeshTet2.from_mesh(MeshTet().refined(2))
    x, y, z = m.p
    u = np.stack([0 * x, 1e-5 * z**2, 0 * z]).T
    return tet_grid(m.p, m.t, {"von_mises_mpa": 100 * (x + y + z), "displacement": u}), m


def test_grid_keeps_every_node_so_nodal_fields_fit(cube_grid):
    grid, m = cube_grid
    assert grid.n_points == m.p.shape[1] and grid.n_cells == m.t.shape[1]
    assert grid.volume == pytest.approx(1.0, rel=1e-12)  # unit cube, closed form


def test_render_is_not_blank_and_the_blank_control_is(cube_grid, tmp_path):
    grid, _ = cube_grid
    png = render_field(tmp_path / "vm.png", grid, "von_mises_mpa", title="von Mises [MPa]",
                       displacement="displacement", scale=1000.0, hotspot=np.array([1.0, 1.0, 1.0]),
                       window_size=(400, 300))
    st = image_statistics(png)
    assert st["coverage"] > 0.15 and st["std"] > 0.05 and st["colours"] > 200
    # control: the statistics do flag a blank picture
    import matplotlib.pyplot as plt

    plt.imsave(tmp_path / "blank.png", np.ones((30, 40, 3)))
    blank = image_statistics(tmp_path / "blank.png")
    assert blank["coverage"] == 0.0 and blank["std"] == 0.0


def test_close_up_fills_the_frame(cube_grid, tmp_path):
    grid, _ = cube_grid
    png = render_field(tmp_path / "close.png", grid, "von_mises_mpa", title="MPa",
                       hotspot=np.array([1.0, 1.0, 1.0]), focus=(np.array([1.0, 1.0, 1.0]), 0.2),
                       window_size=(400, 300))
    assert image_statistics(png)["coverage"] > 0.6


def test_vtu_round_trip(cube_grid, tmp_path):
    import pyvista as pv

    grid, _ = cube_grid
    back = pv.read(write_vtu(tmp_path / "field.vtu", grid))
    assert back.n_cells == grid.n_cells
    np.testing.assert_allclose(back.point_data["von_mises_mpa"], grid.point_data["von_mises_mpa"])
    np.testing.assert_allclose(back.point_data["displacement"], grid.point_data["displacement"])
    assert [p.name for p in tmp_path.iterdir()] == ["field.vtu"]
