"""SCF mode (UR M53 FE appendix) beside the UR M53 empirical SCFs, for geometry files.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/studies/scf_table.py geometry/*.toml --preset coarse

For each geometry: its first throw meshed with ``mesh_throw`` (``--preset``; ``coarse`` or
finer keeps fillet elements <= r/4 as the appendix asks), the three appendix cases solved,
and per factor FE, empirical, FE/empirical and the two mesh checks at the peak.
"""

from __future__ import annotations

import argparse
import time

from fe_crank.assess.adapters import m53_geometry_of
from fe_crank.io.geometry import load_geometry
from fe_crank.io.material import load_material
from fe_crank.mesh import mesh_throw
from fe_crank.rules.m53.scf_mode import compute_scf, web_centres_of

FACTORS = ("alpha_B", "alpha_T", "beta_B", "beta_T", "beta_Q")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("geometry", nargs="+")
    ap.add_argument("--preset", default="coarse")
    ap.add_argument("--material", default="42CrMo4")
    ap.add_argument("--cache", default=".cache/meshes")
    a = ap.parse_args()
    material = load_material(a.material)
    for path in a.geometry:
        g = load_geometry(path)
        geo = m53_geometry_of(g)
        t0 = time.perf_counter()
        tm = mesh_throw(g, size=a.preset, cache_dir=a.cache)
        t1 = time.perf_counter()
        r = compute_scf(tm, material, geo, web_centres=web_centres_of(g))
        t2 = time.perf_counter()
        print(
            f"{path}  preset {a.preset}: {r.stresses.n_dof} dofs, mesh {t1 - t0:.0f} s, SCF mode {t2 - t1:.0f} s; "
            f"fillet edge/r max {max(r.element_size.values()):.3f}; "
            f"out of range: {dict(r.out_of_range)}"
        )
        print(f"  {'factor':8s} {'FE':>7s} {'empir.':>7s} {'FE/emp':>7s} {'princ.%':>8s} {'avg.%':>7s}  peak at (mm)")
        for k in FACTORS:
            e = r.empirical.get(k)
            q = r.quality[k]
            ratio = f"{r.fe[k] / e:7.3f}" if e else "      -"
            emp = f"{e:7.3f}" if e else "      -"
            where = ", ".join(f"{c * 1e3:.1f}" for c in q["point"])
            print(
                f"  {k:8s} {r.fe[k]:7.3f} {emp} {ratio} {100 * q['principal_ratio']:8.2f} {100 * q['averaging']:7.2f}"
                f"  {q['group']} ({where})"
            )
        side = r.details["three_point"][0]
        if r.empirical["beta_Q"] is not None:
            # the journal fillet under the radial force as a whole: sigma_3P / sigma_N3P, which the
            # empirical factors give as beta_B + beta_Q sigma_Q3P / sigma_N3P = beta_B + beta_Q W / (6 L)
            emp_bq = r.empirical["beta_B"] + r.empirical["beta_Q"] * side["sigma_Q3P"] / side["sigma_N3P"]
            print(
                f"  beta_BQ = sigma_3P / sigma_N3P: FE {r.fe['beta_BQ']:.3f}, empirical beta_B + beta_Q W/(6 L) "
                f"{emp_bq:.3f}, FE/emp {r.fe['beta_BQ'] / emp_bq:.3f}"
            )
        print(
            f"  beta_BQ (method 2) {r.fe['beta_BQ']:.3f}; 3-point per side: "
            + "; ".join(
                f"{s['group']}: Q {s['Q_3P']:.4f} N, L {s['L'] * 1e3:.2f} mm, beta_Q {s['beta_Q']:.3f}"
                for s in r.details["three_point"]
            )
        )
        share = side["beta_Q"] * side["sigma_Q3P"] / side["sigma_3P"]
        print(
            f"  shear part beta_Q sigma_Q3P of sigma_3P: {100 * share:.1f} %, so a relative change of sigma_3P "
            f"moves method 1's beta_Q {1 / share:.1f} times as much (benchmarks/studies/beta_q_study.py)"
        )
        print(f"  equilibrium {max(r.equilibrium_error.values()):.1e}; {r.summary()}")


if __name__ == "__main__":
    main()
