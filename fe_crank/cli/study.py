"""``fe-crank study LOADCASE STUDY [-o DIR]``: counterweight candidates of balance rate and
placement screened on the load case's whole shaft (docs/study.md).

Writes ``study.csv``, ``study.json``, ``study.md``, ``study_pareto.png`` and, for the
candidate the study's rule recommends, ``candidate_geometry.toml`` and
``candidate_loadcase.toml`` for ``fe-crank check``.  Exit 0 with a recommendation, 1 when
no candidate meets every limit, 2 for bad input.
"""

from __future__ import annotations

import logging
import time
from pathlib import Path

from fe_crank.assess.workers import threads
from fe_crank.errors import InputError
from fe_crank.io.loadcase import load_loadcase
from fe_crank.mesh.options import DEFAULT_CACHE_DIR, PRESETS
from fe_crank.pipeline.options import cores_available
from fe_crank.study.candidates import achieved_unbalance
from fe_crank.study.outputs import leaves_tree, pareto_plot, write_candidate, write_tables
from fe_crank.study.run import run_study
from fe_crank.study.spec import parse_study

log = logging.getLogger(__name__)


def add_arguments(p) -> None:
    p.add_argument("loadcase", type=Path, help="load-case .toml file (its whole shaft and full-load curve)")
    p.add_argument("study", type=Path, help="study .toml file: the candidates and the rule ([study] table)")
    p.add_argument(
        "-o", "--output", type=Path, default=Path("reports"), metavar="DIR", help="output folder (default: reports/)"
    )
    p.add_argument(
        "--mesh-size",
        default=None,
        choices=sorted(PRESETS),
        help="mesh preset (default: the load case's [mesh] size)",
    )
    p.add_argument("--cache-dir", default=str(DEFAULT_CACHE_DIR), metavar="DIR", help="mesh cache folder")
    p.add_argument(
        "--candidate",
        type=int,
        default=None,
        metavar="N",
        help="write candidate N's geometry and load case (default: the recommended one)",
    )


def run(args) -> int:
    lc = load_loadcase(args.loadcase)
    spec = parse_study(args.study)
    t0 = time.perf_counter()
    size = args.mesh_size or lc.mesh.size
    with threads(cores_available()):  # the screening's states and the unit-stress recovery
        res = run_study(lc, spec, size=size, cache_dir=Path(args.cache_dir), max_elements=lc.mesh.max_elements)
    out = Path(args.output)
    out.mkdir(parents=True, exist_ok=True)
    chosen = res.recommended
    if args.candidate is not None:
        if not 0 <= args.candidate < len(res.results):
            raise InputError(f"there are candidates 0 to {len(res.results) - 1}", key="--candidate")
        chosen = res.results[args.candidate]
        if not chosen.candidate.buildable:
            raise InputError(
                f"candidate {args.candidate} cannot be built: {'; '.join(chosen.candidate.refusals)}", key="--candidate"
            )
    achieved = achieved_unbalance(res.shaft.layout, chosen.candidate, res.drawn) if chosen else {}
    paths = write_tables(res, out, achieved)
    pareto_plot(res, out / "study_pareto.png")
    print(
        f"{len(res.results)} candidates over {len(res.states)} engine states, mesh {size} "
        f"({res.shaft.n_dof} unknowns), {time.perf_counter() - t0:.1f} s"
    )
    print(f"table: {paths['md']}")
    if res.recommended is None:
        print(f"no recommendation: {res.why}")
    else:
        print(f"recommended #{res.recommended.candidate.index} ({res.recommended.candidate.label}): {res.why}")
    if chosen is None:
        return 1
    geo, lcp = write_candidate(res, chosen, out)
    print(f"written: candidate #{chosen.candidate.index} ({chosen.candidate.label})")
    for (t, w), (want, got) in achieved.items():
        print(f"  web {t}.{w}: m r {want:.5g} kg m aimed at, {got:.5g} kg m of the written sector's solid (screened)")
    flag = " --allow-outside-paths" if leaves_tree(lcp) else ""
    print(f"check it: fe-crank check {lcp}{flag}  (geometry {geo})")
    return 0 if res.recommended is not None else 1
