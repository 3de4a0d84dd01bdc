"""beta_Q of the SCF mode (UR M53 App. III 3.3.3, method 1): how well is it defined?

    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/studies/beta_q_study.py tests/data/geometry_small.toml \
        --journal 12 24 --preset coarse        # or --fillet-divisions 2 (r/2, faster)

The same throw solved with two journal lengths, i.e. two levers L from the main-bearing
centre plane (the model's end face) to the web centre.  Linear elasticity and Saint-Venant:
near the journal fillet the 3-point stress field is M s_M + Q s_Q with M = Q L the bending
moment at the web centre, s_M the pure-bending field and s_Q the field of the shear force
alone; if the peak stays at one point with one stress direction,

    sigma_3P / Q = A L / W_eqw + B / F,  A = beta_B (the pure-bending case), B = beta_Q,

so method 1's beta_Q = (sigma_3P - beta_B sigma_N3P) / sigma_Q3P is the same for every L.
Two levers give A and B directly (two equations), to compare with beta_B and method 1.
Also printed per lever: the shear part's share of sigma_3P, beta_Q's sensitivity
(d beta_Q / beta_Q per d sigma_3P / sigma_3P = sigma_3P / (beta_Q sigma_Q3P)), and the
empirical values of UR M53 3.3 for the same throw.
"""

from __future__ import annotations

import argparse
import dataclasses
import time

from fe_crank.assess.adapters import m53_geometry_of
from fe_crank.io.geometry import load_geometry
from fe_crank.io.material import load_material
from fe_crank.mesh import PRESETS, MeshOptions, mesh_throw
from fe_crank.rules.m53.scf_mode import compute_scf, web_centres_of


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("geometry")
    ap.add_argument("--journal", nargs="+", type=float, default=[12.0, 24.0], help="journal lengths, mm")
    ap.add_argument("--fillet-divisions", type=float, default=2.0)
    ap.add_argument("--coarse-divisions", type=float, default=1.5)
    ap.add_argument("--preset", default=None, help="a mesh preset (e.g. coarse) instead of the divisions")
    ap.add_argument("--material", default="42CrMo4")
    ap.add_argument("--cache", default=".cache/meshes")
    a = ap.parse_args()
    material = load_material(a.material)
    g0 = load_geometry(a.geometry)
    opts = (
        PRESETS[a.preset]
        if a.preset
        else MeshOptions(coarse_divisions=a.coarse_divisions, fillet_divisions=a.fillet_divisions, grading=2.5)
    )
    rows = []
    for jl in a.journal:
        g = dataclasses.replace(g0, journal_length=jl * 1e-3)
        geo = m53_geometry_of(g)
        t0 = time.process_time()
        tm = mesh_throw(g, size=opts, cache_dir=a.cache)
        r = compute_scf(tm, material, geo, web_centres=web_centres_of(g))
        side = r.details["three_point"][0]
        rows.append((jl, geo, r, side))
        share = side["beta_Q"] * side["sigma_Q3P"] / side["sigma_3P"]
        emp = r.empirical
        print(
            f"journal {jl:g} mm: L = {side['L'] * 1e3:.2f} mm, {r.stresses.n_dof} dofs, "
            f"CPU {time.process_time() - t0:.0f} s, fillet edge/r max {max(r.element_size.values()):.3f}"
        )
        print(
            f"  beta_B {r.fe['beta_B']:.3f} (emp. {emp['beta_B']:.3f}); sigma_3P/sigma_N3P {r.fe['beta_BQ']:.3f}; "
            f"method 1 beta_Q {side['beta_Q']:.3f} (emp. {emp['beta_Q']:.3f}); shear share of sigma_3P "
            f"{100 * share:.1f} %; sensitivity {1 / share:.1f}; 3P peak {r.quality['beta_Q']['point']}, "
            f"bending peak {r.quality['beta_B']['point']}"
        )
    for (_j1, geo1, r1, s1), (_j2, _geo2, r2, s2) in zip(rows, rows[1:]):
        # sigma_3P/Q = A L/W + B/F at two levers (W, F the same: only the journal changed)
        w_eq = geo1.web_width * geo1.web_thickness**2 / 6.0
        area = geo1.web_width * geo1.web_thickness
        y1, y2 = s1["sigma_3P"] / s1["Q_3P"], s2["sigma_3P"] / s2["Q_3P"]
        l1, l2 = s1["L"], s2["L"]
        big_a = (y2 - y1) / (l2 - l1) * w_eq
        big_b = (y1 - big_a * l1 / w_eq) * area
        print(
            f"levers {l1 * 1e3:.1f} / {l2 * 1e3:.1f} mm: A = {big_a:.3f} (beta_B of pure bending "
            f"{r1.fe['beta_B']:.3f} / {r2.fe['beta_B']:.3f}), B = {big_b:.3f} (method 1 "
            f"{s1['beta_Q']:.3f} / {s2['beta_Q']:.3f}; empirical {r1.empirical['beta_Q']:.3f})"
        )


if __name__ == "__main__":
    main()
