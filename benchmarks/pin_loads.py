"""Time of the crankpin unit loads: one facet basis per direction (former) vs one for all.

    .venv/bin/python benchmarks/pin_loads.py --preset test

Meshes (cached) the load case's throw, then assembles the 12 pin-direction load vectors
both ways in the same process and prints both times and the largest difference.
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--loadcase", default="loadcases/single_cylinder_seed001.toml")
    ap.add_argument("--preset", default="test")
    args = ap.parse_args(argv)
    from skfem import Basis, ElementTetP2

    from fe_crank.fe.loads import pin_pressure_load, pin_surface
    from fe_crank.fe.pin_directions import pin_cases, unit_force
    from fe_crank.io.loadcase import load_loadcase
    from fe_crank.mesh import mesh_throw

    mesh = mesh_throw(load_loadcase(args.loadcase).geometry, size=args.preset, cache_dir=".cache/meshes").mesh
    basis = Basis(mesh, ElementTetP2(), intorder=2)
    t0 = time.perf_counter()
    old = [pin_pressure_load(basis, unit_force(c))[0] for c in pin_cases()]
    t_old = time.perf_counter() - t0
    t0 = time.perf_counter()
    surf = pin_surface(basis)
    new = [pin_pressure_load(basis, unit_force(c), surface=surf)[0] for c in pin_cases()]
    t_new = time.perf_counter() - t0
    diff = max(np.abs(a - b).max() / np.abs(a).max() for a, b in zip(old, new))
    print(
        f"{len(old)} pin loads, {3 * basis.N} dof: a surface per direction {t_old:.2f} s, one surface "
        f"{t_new:.2f} s (x{t_old / t_new:.1f}); max relative difference {diff:.1e}; load {os.getloadavg()[0]:.1f}"
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
