"""CPU seconds of the FE stage's set-up of one load case, piece by piece, without the solve.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/fe_setup.py \
        loadcases/single_cylinder_seed001.toml --preset coarse [--profile FILE] [--top N]

Meshes (cached) the case's first throw, then times, in CPU seconds (user + system,
``os.times``) and in the order ``solve_unit_cases`` runs them: the scalar P2 cell basis,
the determinate supports (``determinate_support``), the stiffness (``assemble_stiffness``)
and the unit load vectors of the case's ``[fe]`` options (centrifugal, torque, the pin
surface and every pin direction).  No factorisation and no solve: this is the part of
the ``fe`` stage that is not PARDISO.  Prints one line per piece, the total and the load
average; ``--profile``/``--top`` add a cProfile of the timed part.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from check_profile import _cpu


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("loadcase")
    ap.add_argument("--preset", default="coarse")
    ap.add_argument("--cache-dir", default=".cache/meshes")
    ap.add_argument("--profile", help="write a cProfile of the timed part here")
    ap.add_argument("--top", type=int, default=0, help="print the N functions with the largest cumulative time")
    ap.add_argument("--save", help="write K and the load vectors here (.npz) for a bitwise comparison")
    args = ap.parse_args(argv)

    import numpy as np

    from fe_crank.fe.assembly import assemble_stiffness
    from fe_crank.fe.determinate import DeterminateLayout, determinate_support
    from fe_crank.fe.fe_options import FeOptions, axial_journal
    from fe_crank.fe.loads import centrifugal_load, face_torque_load, pin_pressure_load, pin_surface
    from fe_crank.fe.pin_directions import pin_direction, unit_force

    try:
        from fe_crank.fe.supports import cell_basis
    except ImportError:  # the code before cell_basis existed: the same basis, built by scikit-fem
        from skfem import Basis, ElementTetP2

        def cell_basis(mesh, intorder):
            return Basis(mesh, ElementTetP2(), intorder=intorder)

    from fe_crank.io.loadcase import load_loadcase
    from fe_crank.mesh import mesh_throw

    lc = load_loadcase(args.loadcase)
    mesh = mesh_throw(lc.geometry, size=args.preset, cache_dir=args.cache_dir).mesh
    opts = lc.fe or FeOptions()
    mat = lc.material
    rows = []
    prof = None
    if args.profile or args.top:
        import cProfile

        prof = cProfile.Profile(timer=time.process_time)
        prof.enable()
    c_all, w_all = _cpu(), time.perf_counter()

    def timed(name, fn):
        c, w = _cpu(), time.perf_counter()
        out = fn()
        rows.append((name, _cpu() - c, time.perf_counter() - w))
        return out

    basis = timed("cell basis", lambda: cell_basis(mesh, opts.intorder))
    layout = DeterminateLayout(journals=tuple(opts.journals), torque_face=opts.reaction_face, axial=axial_journal(opts))
    sup = timed("determinate_support", lambda: determinate_support(basis, layout))
    K = timed("assemble_stiffness", lambda: assemble_stiffness(basis, mat.youngs_modulus, mat.poisson_ratio))
    loads = {}
    if "centrifugal" in opts.cases:
        loads["centrifugal"] = timed("centrifugal_load", lambda: centrifugal_load(basis, mat.density, 1.0))
    if "torque" in opts.cases:
        loads["torque"] = timed("face_torque_load", lambda: face_torque_load(basis, -1.0, boundary=opts.torque_face))
    pins = [c for c in opts.cases if pin_direction(c) is not None]
    if pins:
        surf = timed("pin_surface", lambda: pin_surface(basis, opts.pin_boundary, opts.pin_centre))
        c, w = _cpu(), time.perf_counter()
        for name in pins:
            loads[name] = pin_pressure_load(
                basis, unit_force(name), boundary=opts.pin_boundary, half_angle=opts.pin_half_angle, surface=surf
            )[0]
        rows.append((f"pin_pressure_load x{len(pins)}", _cpu() - c, time.perf_counter() - w))
    total = (_cpu() - c_all, time.perf_counter() - w_all)
    if prof is not None:
        prof.disable()
    print(
        f"{args.loadcase} --preset {args.preset}: {3 * basis.N} DOF, {mesh.t.shape[1]} elements, "
        f"nnz K {K.nnz}, {len(loads)} load vectors"
    )
    print(f"{'piece':<24} {'cpu s':>8} {'wall s':>8}")
    for name, c, w in rows:
        print(f"{name:<24} {c:8.2f} {w:8.2f}")
    print(f"{'total set-up':<24} {total[0]:8.2f} {total[1]:8.2f}")
    print(f"load average at the end: {os.getloadavg()[0]:.2f}")
    print(f"checksums: K {abs(K).sum():.17g}, loads {sum(float(np.abs(v).sum()) for v in loads.values()):.17g}")
    if args.save:
        np.savez(
            args.save,
            K_data=K.data,
            K_indices=K.indices,
            K_indptr=K.indptr,
            G_data=sup.G.data,
            G_indices=sup.G.indices,
            G_indptr=sup.G.indptr,
            A=sup.A,
            held=sup.held,
            **{f"load_{k}": v for k, v in loads.items()},
        )
    if prof is not None:
        if args.profile:
            prof.dump_stats(args.profile)
        if args.top:
            import pstats

            pstats.Stats(prof, stream=sys.stdout).sort_stats("cumulative").print_stats(args.top)
    return 0


if __name__ == "__main__":
    sys.exit(main())
