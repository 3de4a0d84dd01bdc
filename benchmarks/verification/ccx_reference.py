"""Which nodal recovery is nearer the converged stress: fe-crank's or CalculiX's, as the
fillet elements are refined.

    .venv/bin/python benchmarks/verification/ccx_reference.py --fillet-divisions 1 1.5 2 --json ref.json

For each refinement f (fillet element edge r / f, 6 f elements round the oil bore per pi;
the bulk of the ``test`` preset: coarse divisions 1.5, grading 2.0; f = 1 is the
``test`` preset itself), in a process of its own: the FE stage's unit cases, then per assessed group the check's static peak
sigma_v over the cycle and its Goodman safety (``assess.group.assessment.assess_group`` with the
check's coefficients, ``ccx_groups.cycle_table``) from two nodal recoveries of the same
displacements -- fe-crank's (the P2 stress at the node, averaged) and CalculiX's C3D10
recovery (``ccx_recovery``: linear extrapolation from the 4 integration points, mid-edge
nodes the mean of their corners, averaged), which reproduces CalculiX's own nodal stress
to 1e-5 (``calculix_compare.py``).  The two converge to the same value as the elements
shrink; the one nearer the finest level's value at the coarse levels is the better
recovery there.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))


def level(loadcase: str, f: float) -> dict:
    from ccx_groups import cycle_table
    from ccx_recovery import calculix_nodal_stress, edge_nodes, places

    from fe_crank.assess.group.nodes import assessed_groups, unit_stresses
    from fe_crank.fe import FeOptions, solve_unit_cases
    from fe_crank.io.loadcase import load_loadcase
    from fe_crank.mesh import mesh_throw
    from fe_crank.mesh.options import MeshOptions

    lc = load_loadcase(loadcase)
    tm = mesh_throw(
        lc.geometry,
        size=MeshOptions(coarse_divisions=1.5, fillet_divisions=f, grading=2.0, bore_divisions=6.0 * f),
        cache_dir=".cache/meshes",
    )
    units = solve_unit_cases(tm, lc.material, lc.fe or FeOptions())
    groups = assessed_groups(units)
    unit = unit_stresses(units, groups)
    ids = unit.node_ids
    flags = places(units, ids, getattr(tm, "symmetry", None) or ())
    flags["edge"] = np.isin(ids, np.concatenate([edge_nodes(units, g) for g in groups]))
    sx = calculix_nodal_stress(units, [units.displacement(c) for c in unit.cases], ids)
    cyc = cycle_table(loadcase, unit, {"fe-crank": unit.stress, "CalculiX recovery": sx}, flags)
    return {
        "fillet_divisions": f,
        "dof": int(units.n_dof),
        "elements": int(tm.mesh.t.shape[1]),
        "peak_gb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024**2,
        "cycle": cyc,
    }


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--loadcase", default="loadcases/single_cylinder.toml")
    ap.add_argument("--fillet-divisions", nargs="+", type=float, default=[1.0, 1.5, 2.0])
    ap.add_argument("--json", default=None, help="append the result to this file")
    ap.add_argument("--worker", type=float, help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.worker is not None:
        print(
            json.dumps(
                level(args.loadcase, args.worker), default=lambda o: o.tolist() if hasattr(o, "tolist") else str(o)
            )
        )
        return 0
    out = {"loadcase": args.loadcase, "load_average": os.getloadavg(), "levels": []}
    for f in args.fillet_divisions:
        p = subprocess.run(
            [sys.executable, __file__, "--worker", str(f), "--loadcase", args.loadcase],
            check=True,
            stdout=subprocess.PIPE,
            text=True,
        )
        out["levels"].append(json.loads(p.stdout.strip().splitlines()[-1]))
        lv = out["levels"][-1]
        print(f"r/{f:g}: {lv['dof']} dof, peak {lv['peak_gb']:.2f} GB", flush=True)
        for _t, rows in lv["cycle"].items():
            for g, row in rows.items():
                st, gd = row["static"], row["goodman"]
                line = (
                    f"  {g:22s} static peak: fe-crank {st['fe-crank']['peak'] / 1e6:8.2f} MPa, CalculiX recovery "
                    f"{st['CalculiX recovery']['peak'] / 1e6:8.2f} MPa"
                )
                if gd:
                    line += (
                        f"; Goodman: fe-crank {gd['fe-crank']['min']:.3f}, CalculiX recovery "
                        f"{gd['CalculiX recovery']['min']:.3f}"
                    )
                print(line, flush=True)
    out["load_average_after"] = os.getloadavg()
    if args.json:
        with open(args.json, "a") as fh:
            fh.write(json.dumps(out) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
