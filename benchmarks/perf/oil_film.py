"""Benchmark: the oil-film stage alone (``assess.oil_film.film_sweep``) at its design size.

The whole shaft of a load case is solved once at the ``test`` preset; its main bearings'
loads at the operating speed are then scaled to ``--speeds`` speeds (the inertia loads as
omega^2, the bearing loads of a full-load curve stand-in) and every bearing keeps the
film its geometry states (the shipped inline-4's), or without one is given the film of
``--clearance`` / ``--viscosity`` with a full groove, so that the film stage sees
n_bearings x speeds x 2 counterweight states orbits, timed alone:

    .venv/bin/python benchmarks/perf/oil_film.py --loadcase loadcases/inline4_rated.toml --speeds 20

Prints the film stage's wall time, the orbits, the largest number of cycles to a periodic
orbit and the thinnest film.
"""

from __future__ import annotations

import argparse
import dataclasses
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--loadcase", default=str(ROOT / "loadcases" / "inline4_rated.toml"))
    ap.add_argument("--speeds", type=int, default=20)
    ap.add_argument("--clearance", type=float, default=25e-6)
    ap.add_argument("--viscosity", type=float, default=7e-3)
    ap.add_argument("--groove", type=float, default=3e-3)
    a = ap.parse_args()

    from fe_crank.assess.loads import FIRING
    from fe_crank.assess.oil_film import film_sweep
    from fe_crank.assess.shaft import BearingState
    from fe_crank.fe.shaft.cycle import BearingLoads
    from fe_crank.fe.shaft.whole_shaft import BearingResult, analyse_whole_shaft, throw_masses
    from fe_crank.geometry.oil import FilmSpec
    from fe_crank.io.loadcase import load_loadcase
    from fe_crank.mechanism.cycles import engine_cycles
    from fe_crank.mesh.shaft import mesh_shaft
    from fe_crank.pipeline.stages import shaft_layout

    lc = load_loadcase(a.loadcase)
    layout = shaft_layout(lc)
    assert layout is not None
    film = FilmSpec(a.clearance, a.viscosity, "full", a.groove)
    layout = dataclasses.replace(
        layout,
        bearings=tuple(
            b if b.law.film is not None else dataclasses.replace(b, law=dataclasses.replace(b.law, film=film))
            for b in layout.bearings
        ),
    )
    dyn = engine_cycles(lc.engine, lc.operating).operating
    result, cases = analyse_whole_shaft(mesh_shaft(layout, size="test"), lc.material, dyn, mass=throw_masses(layout))
    cases.model.free_factors()
    w0 = float(dyn.speed)
    states = []
    for w in np.linspace(0.2 * w0, w0, a.speeds):
        k = (w / w0) ** 2

        def scaled(b: BearingLoads, k=k) -> BearingLoads:
            return dataclasses.replace(b, load_n=b.load_n * k, slope=None if b.slope is None else b.slope * k)

        states.append(
            BearingState(
                float(w),
                FIRING,
                tuple(
                    BearingResult(scaled(b.with_counterweights), scaled(b.without_counterweights))
                    for b in result.bearings
                ),
            )
        )
    t0 = time.perf_counter()
    out = film_sweep(layout, tuple(states), result.crank_angle_deg)
    dt = time.perf_counter() - t0
    orbits = [o for s in out for b in s.bearings for o in (b.with_counterweights, b.without_counterweights)]
    print(
        f"film stage: {len(orbits)} orbits ({len(layout.bearings)} bearings x {a.speeds} speeds x 2), "
        f"{len(result.crank_angle_deg)} angles per cycle: {dt:.2f} s wall; "
        f"cycles <= {max(o.cycles for o in orbits)}, all periodic: {all(o.converged for o in orbits)}, "
        f"thinnest film {min(o.min_film_m for o in orbits) * 1e6:.3g} um"
    )


if __name__ == "__main__":
    main()
