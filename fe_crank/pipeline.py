"""One load case end to end, and batches of them.

``run_case(path, out_dir, options) -> CaseResult`` reads top to bottom like
DESIGN.md: load case -> dynamics -> balance -> mesh (cached) -> FE unit cases ->
cycle assessment -> verdict -> report.  Every stage is timed.  Any ``FeCrankError``
becomes a result with status ``"error"`` and its message; the batch never crashes
on one bad case.

Files are written atomically: a case folder is built under a hidden temporary name
in ``out_dir`` and renamed into place only when it is complete, so an interrupted
run never leaves a report that looks finished.

``run_cases(paths, out_dir, options, jobs=..., scheduler=...)`` runs many cases in
this process, in local processes (``concurrent.futures`` with the ``spawn`` start
method) or on an existing Dask distributed cluster; the results are the same
whichever way they run (they are computed by the same ``run_case``).
"""

from __future__ import annotations

import hashlib
import importlib
import json
import os
import re
import shutil
import tempfile
import time
import traceback
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Callable, Iterable, Sequence

from fe_crank.errors import FeCrankError, InputError

#: Stage names in the order they run (also the keys of ``CaseResult.timings``).
STAGES = ("load", "dynamics", "balance", "mesh", "fe", "assess", "report")

STATUS_PASS, STATUS_FAIL, STATUS_ERROR = "pass", "fail", "error"
_EXIT = {STATUS_PASS: 0, STATUS_FAIL: 1, STATUS_ERROR: 2}


class StageUnavailable(FeCrankError, RuntimeError):
    """A pipeline stage whose module is not part of this installation."""


@dataclass(frozen=True)
class CheckOptions:
    """How ``run_case`` runs: all fields plain data so the options pickle to workers.

    ``mesh_size`` is a preset of ``fe_crank.mesh`` ("test", "coarse", "medium",
    "fine") that overrides the load case's ``[mesh] size`` (default "coarse"); ``cache_dir`` holds meshes keyed by the hash of their inputs;
    ``render`` switches the pyvista pictures on; ``write_vtu`` the ``.vtu`` fields;
    ``allow_outside_paths`` lets include paths leave the load case's folder tree;
    ``max_elements`` overrides the estimated-element-count limit (docs/limits.md).
    """

    mesh_size: str | None = None
    cache_dir: str = ".cache/meshes"
    render: bool = True
    write_vtu: bool = True
    allow_outside_paths: bool = False
    max_elements: int | None = None


MESH_PRESETS = ("test", "coarse", "medium", "fine")


@dataclass(frozen=True)
class MeshSection:
    """The load case's ``[mesh]`` table: ``size`` is a preset of ``fe_crank.mesh``
    ("coarse", the default, keeps fillet elements within r/4 as IACS UR M53 asks;
    "test" is for quick trials and demonstrations only)."""

    size: str = "coarse"
    max_elements: int | None = None


def parse_mesh_section(value: object, file, key: str = "mesh") -> MeshSection:
    """Section parser registered as ``SECTIONS["mesh"]``: ``[mesh] size = "coarse"``."""
    if not isinstance(value, dict):
        raise InputError('must be a table, e.g. [mesh] size = "coarse"', file=str(file), key=key)
    for k in value:
        if k not in ("size", "max_elements"):
            raise InputError("unknown key; the [mesh] table takes size and max_elements", file=str(file),
                             key=f"{key}.{k}")
    limit = value.get("max_elements")
    if limit is not None and (isinstance(limit, bool) or not isinstance(limit, int) or limit < 1):
        raise InputError("must be a positive whole number of elements", file=str(file), key=f"{key}.max_elements")
    size = value.get("size", "coarse")
    if size not in MESH_PRESETS:
        raise InputError(f"unknown mesh size {size!r}; pick one of {list(MESH_PRESETS)}", file=str(file),
                         key=f"{key}.size")
    return MeshSection(size=size, max_elements=limit)


@dataclass(frozen=True)
class CriterionResult:
    """One acceptance criterion of a load case, as the check reports it.

    ``margin`` is ``value / limit - 1`` for a "not below" criterion (a safety
    factor) and ``1 - value / limit`` for a "not above" one (a stress, a
    residual unbalance): a criterion passes when its margin is not negative.
    """

    name: str
    passed: bool
    value: float
    limit: float
    margin: float
    description: str = ""
    location: str = ""
    unit: str = ""


@dataclass(frozen=True)
class StageTime:
    stage: str
    seconds: float


@dataclass(frozen=True)
class CaseResult:
    """Outcome of one load case.  Frozen and picklable (plain data only)."""

    name: str
    source: str
    status: str  # "pass" | "fail" | "error"
    message: str = ""
    criteria: tuple[CriterionResult, ...] = ()
    timings: tuple[StageTime, ...] = ()
    folder: str = ""  # the finished case folder, "" when none could be written
    seconds: float = 0.0
    error_stage: str = ""

    @property
    def exit_code(self) -> int:
        """0 pass, 1 a criterion failed, 2 an input or computation error."""
        return _EXIT[self.status]

    @property
    def worst(self) -> CriterionResult | None:
        """The criterion with the smallest margin (None without criteria)."""
        if not self.criteria:
            return None
        return min(self.criteria, key=lambda c: (c.margin, c.name))

    def to_dict(self) -> dict:
        d = _finite(asdict(self))
        d["exit_code"] = self.exit_code
        w = self.worst
        d["worst"] = w.name if w else None
        return d


def _finite(x):
    """Non-finite floats (an unloaded part's infinite safety) -> None, for strict JSON."""
    if isinstance(x, float):
        return x if x == x and x not in (float("inf"), float("-inf")) else None
    if isinstance(x, dict):
        return {k: _finite(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_finite(v) for v in x]
    return x


# --------------------------------------------------------------------------- files


def write_atomic(path: str | Path, data: str | bytes) -> Path:
    """Write ``data`` to ``path`` through a temporary file in the same folder and
    ``os.replace``: readers see the old file or the whole new one, never a part."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    mode = "wb" if isinstance(data, bytes) else "w"
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, mode, **({} if mode == "wb" else {"encoding": "utf-8"})) as fh:
            fh.write(data)
            fh.flush()
            os.fsync(fh.fileno())
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    return path


PARTIAL_MARK = ".partial-"


def _pid_alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # pragma: no cover - someone else's process
        return True
    return True


def clean_stale_partials(out_dir: str | Path) -> list[Path]:
    """Remove temporary case folders left by runs that were killed (their process is
    gone).  Returns what was removed."""
    out = Path(out_dir)
    removed = []
    if not out.is_dir():
        return removed
    for p in out.iterdir():
        m = re.match(r"^\..+\.partial-(\d+)-", p.name)
        if m and p.is_dir() and not _pid_alive(int(m.group(1))):
            shutil.rmtree(p, ignore_errors=True)
            removed.append(p)
    return removed


def _publish(tmp_dir: Path, final: Path) -> Path:
    """Rename the finished ``tmp_dir`` to ``final``, replacing an older report.

    A folder cannot be renamed over a non-empty one, so the old folder is first
    renamed aside and deleted after the new one is in place; at every instant
    ``final`` is either absent, the old complete report or the new complete one.
    """
    old = None
    if final.exists():
        old = final.with_name(f".{final.name}.old-{os.getpid()}-{time.monotonic_ns()}")
        os.replace(final, old)
    os.replace(tmp_dir, final)
    if old is not None:
        shutil.rmtree(old, ignore_errors=True)
    return final


def case_slug(path: str | Path) -> str:
    """Folder name of a case's report: the file stem, made filesystem-safe."""
    stem = Path(path).stem
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", stem) or "case"


# --------------------------------------------------------------------------- discovery


def is_loadcase_file(path: Path) -> bool:
    """A ``.toml`` with an ``[operating]`` table.  An unreadable TOML counts too, so
    that a broken load case in a folder is reported instead of silently skipped."""
    from fe_crank.io.base import read_toml

    try:
        data = read_toml(path)  # bounded: size, nesting depth; never a traceback
    except InputError:
        return True
    return isinstance(data.get("operating"), dict)


def find_loadcases(paths: Iterable[str | Path]) -> list[Path]:
    """Expand files and folders into load-case files.

    A file is taken as given (a wrong one becomes an error result); a folder
    contributes its ``*.toml`` files (recursively, sorted) that have an
    ``[operating]`` table.  A path that does not exist raises ``InputError``.
    """
    out: list[Path] = []
    for p in map(Path, paths):
        if p.is_dir():
            out.extend(f for f in sorted(p.rglob("*.toml")) if is_loadcase_file(f))
        elif p.exists():
            out.append(p)
        else:
            raise InputError("no such file or folder", file=str(p))
    seen, unique = set(), []
    for p in out:
        try:
            key = p.resolve()
        except (OSError, RuntimeError):  # a symbolic-link loop: reported when the case is read
            key = p.absolute()
        if key not in seen:
            seen.add(key)
            unique.append(p)
    return unique


def unique_slugs(paths: Sequence[Path]) -> list[str]:
    """Folder names for a batch: the stem, with a short hash of the path where two
    files share a stem."""
    stems = [case_slug(p) for p in paths]
    out = []
    for p, s in zip(paths, stems):
        if stems.count(s) > 1:
            s = f"{s}-{hashlib.sha1(os.path.abspath(p).encode()).hexdigest()[:6]}"
        out.append(s)
    return out


# --------------------------------------------------------------------------- stages


def stage_function(module: str, name: str, stage: str) -> Callable:
    """Import ``module.name`` for ``stage``; a module not in this installation is a
    ``StageUnavailable`` error naming the stage (any other import error is a bug
    and propagates)."""
    try:
        mod = importlib.import_module(module)
    except ModuleNotFoundError as exc:
        if exc.name and (exc.name == module or module.startswith(exc.name + ".")):
            raise StageUnavailable(
                f"the {stage} stage is not available in this installation (module {module} is missing)"
            ) from None
        raise
    try:
        return getattr(mod, name)
    except AttributeError:
        raise StageUnavailable(
            f"the {stage} stage is not available in this installation ({module}.{name} is missing)"
        ) from None


@dataclass
class _Run:
    """Mutable state of one run (private; the result is frozen)."""

    path: Path
    timings: list = field(default_factory=list)
    stage: str = ""
    on_stage: Callable[[str, str], None] | None = None

    def timed(self, stage: str, fn: Callable, *args, **kwargs):
        self.stage = stage
        if self.on_stage is not None:
            self.on_stage(str(self.path), stage)
        t0 = time.perf_counter()
        try:
            return fn(*args, **kwargs)
        finally:
            self.timings.append(StageTime(stage, time.perf_counter() - t0))


def _compute(run: _Run, options: CheckOptions, out: dict) -> dict:
    """Run the computational stages, filling ``out`` with each stage's output as it
    finishes (so that a report of a case that stopped shows what did run)."""
    from fe_crank.io.loadcase import load_loadcase

    lc = out["loadcase"] = run.timed("load", load_loadcase, run.path,
                                     allow_outside_paths=options.allow_outside_paths)
    out["dynamics"] = run.timed("dynamics", _dynamics_stage, lc)
    out["balance"] = run.timed("balance", _balance_stage, lc)
    out["meshes"] = run.timed("mesh", _mesh_stage, lc, options)
    out["units"] = run.timed("fe", _fe_stage, lc, out["meshes"])
    out["assessment"] = run.timed("assess", _assess_stage, lc, out)
    return out


def _dynamics_stage(lc):
    """Forces and torques over the whole cycle at the operating speed."""
    analyse = stage_function("fe_crank.dynamics", "analyse", "dynamics")
    res = analyse(lc.engine, lc.operating)
    refuse_non_finite_dynamics(res, lc.source_file)
    return res


def refuse_non_finite_dynamics(res, file) -> None:
    """Forces and torques over the cycle must be finite: a NaN or inf (an input at the
    edge of what the mechanism allows) is an error of the case, never a result."""
    import numpy as np

    arrays = {"torque": res.torque}
    arrays.update({f"throw {n} pin force": t.pin_force for n, t in res.throws.items()})
    for what, a in arrays.items():
        if not np.all(np.isfinite(a)):
            raise FeCrankError(f"{file}: the dynamics gave a non-finite {what} (NaN or inf); check the engine data")


def _assess_stage(lc, out):
    """Stresses, safety factors and the load case's criteria."""
    assess_case = stage_function("fe_crank.assess", "assess_case", "assessment")
    return assess_case(lc, out["dynamics"], out["balance"], out["meshes"], out["units"])


def _balance_stage(lc):
    """Free forces by order, counterweights sized by the ``[balance]`` strategy,
    balance shafts, residual (``fe_crank.balance.analysis.analyse_balance``)."""
    analyse_balance = stage_function("fe_crank.balance.analysis", "analyse_balance", "balance")
    return analyse_balance(lc.engine, lc.operating.speed, lc.balance)


def throw_keys(lc) -> dict[str, str]:
    """Which geometry throw to mesh for each key handed to the assessment.

    A geometry with a single throw stands for every throw of the engine (key
    ``"all throws"``, which ``assess_case`` applies to each throw with its own loads);
    so do several throws that differ only in name and angle; otherwise the geometry's
    throw names must be the engine's throw names, so that no throw goes unchecked.
    """
    g = lc.geometry
    names = [t.name for t in g.throws]
    engine = [t.name for t in lc.engine.throws]
    if len(names) == 1:
        return {names[0] if engine == names else "all throws": names[0]}
    if sorted(names) != sorted(engine) and _all_equal(g.throws):
        # equal throws under other names (e.g. "1", "2" for the engine's "A", "B"):
        # one model stands for every throw, each assessed with its own loads
        return {"all throws": names[0]}
    if sorted(names) != sorted(engine):
        raise InputError(
            f"the geometry's throws {names} must be the engine's throws {engine} "
            "(or give one throw that stands for all)", file=lc.source_file, key="geometry",
        )
    return {n: n for n in engine}


def _all_equal(throws) -> bool:
    """Throws that differ only in name and angle give the same throw model."""
    import dataclasses

    norm = [dataclasses.replace(t, name="", angle=0.0) for t in throws]
    return all(n == norm[0] for n in norm)


def _mesh_stage(lc, options: CheckOptions):
    """Quadratic tetrahedral mesh of each throw (``fe_crank.mesh.mesh_throw``, cached
    by the hash of its inputs: equal throws are meshed once)."""
    if lc.geometry is None:
        raise InputError(
            "the stress check needs a crank geometry: add geometry = \"../geometry/<file>.toml\"",
            file=lc.source_file, key="geometry",
        )
    mesh_throw = stage_function("fe_crank.mesh", "mesh_throw", "mesh")
    section = lc.extras.get("mesh") or MeshSection()
    kwargs = {"cache_dir": options.cache_dir, "size": options.mesh_size or section.size,
              "max_elements": options.max_elements or section.max_elements}
    return {key: mesh_throw(lc.geometry, throw=name, **kwargs) for key, name in throw_keys(lc).items()}


def _fe_stage(lc, meshes):
    """Unit load cases on one assembled stiffness per distinct throw mesh (throws
    with the same mesh key share one solution)."""
    solve_unit_cases = stage_function("fe_crank.fe", "solve_unit_cases", "FE")
    if lc.material is None:
        raise InputError("the stress check needs a [material] section", file=lc.source_file, key="material")
    solved, out = {}, {}
    for key, m in meshes.items():
        mk = getattr(m, "key", None) or id(m)
        if mk not in solved:
            solved[mk] = solve_unit_cases(m, lc.material, lc.fe)
        out[key] = solved[mk]
    return out


def _criteria_of(assessment) -> tuple[CriterionResult, ...]:
    """The assessment's criteria as ``CriterionResult`` (plain, picklable)."""
    out = []
    for c in getattr(assessment, "criteria", ()):
        out.append(
            CriterionResult(
                name=str(c.name), passed=bool(c.passed), value=float(c.value), limit=float(c.limit),
                margin=float(c.margin), description=str(getattr(c, "description", "")),
                location=str(getattr(c, "location", "")), unit=str(getattr(c, "unit", "")),
            )
        )
    return tuple(out)


def _refuse_nan(criteria) -> None:
    """A NaN in a criterion is an error of the case, never a verdict or a JSON value
    (an infinite safety factor of an unloaded part is legitimate and is kept)."""
    for c in criteria:
        if any(x != x for x in (c.value, c.limit, c.margin)):
            raise FeCrankError(f"criterion {c.name}: the computation gave NaN (not a number); "
                               "the case is not assessed")


def run_case(
    path: str | Path,
    out_dir: str | Path,
    options: CheckOptions | None = None,
    *,
    slug: str | None = None,
    on_stage: Callable[[str, str], None] | None = None,
) -> CaseResult:
    """Check one load case and write its report folder ``out_dir/<slug>``.

    Returns a ``CaseResult``; never raises for a bad case: a ``FeCrankError`` (bad
    input, failed mesh or solve, missing stage) gives status ``"error"`` with its
    message, any other exception (a bug) gives status ``"error"`` with the
    exception type and the traceback saved in ``error.txt``.
    """
    options = options or CheckOptions()
    path = Path(path)
    out_dir = Path(out_dir)
    slug = slug or case_slug(path)
    run = _Run(path, on_stage=on_stage)
    t0 = time.perf_counter()
    out_dir.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=f".{slug}{PARTIAL_MARK}{os.getpid()}-", dir=out_dir))
    os.chmod(tmp, 0o755)
    name, status, message, criteria, trace, stage_out = path.stem, STATUS_ERROR, "", (), "", {}
    try:
        try:
            _compute(run, options, stage_out)
            name = stage_out["loadcase"].name
            criteria = _criteria_of(stage_out["assessment"])
            _refuse_nan(criteria)
            status = STATUS_PASS if all(c.passed for c in criteria) else STATUS_FAIL
            if not criteria:
                status, message = STATUS_ERROR, "the assessment returned no criteria: nothing was checked"
        except FeCrankError as exc:
            message = str(exc)
        except Exception as exc:  # a bug: report it, keep the batch going
            message = f"internal error in the {run.stage or 'pipeline'} stage: {type(exc).__name__}: {exc}"
            trace = traceback.format_exc()
        error_stage = run.stage if status == STATUS_ERROR else ""
        if "loadcase" in stage_out:
            name = stage_out["loadcase"].name
        partial = CaseResult(
            name=name, source=str(path), status=status, message=message, criteria=criteria,
            timings=tuple(run.timings), folder="", seconds=0.0, error_stage=error_stage,
        )
        try:
            run.timed("report", _write_report, tmp, partial, stage_out, options, trace)
        except FeCrankError as exc:
            partial = _as_error(partial, f"report: {exc}", "report")
            _write_minimal(tmp, partial, "")
        except Exception as exc:
            partial = _as_error(partial, f"internal error in the report stage: {type(exc).__name__}: {exc}", "report")
            _write_minimal(tmp, partial, traceback.format_exc())
        final = CaseResult(
            **{**_fields(partial), "timings": tuple(run.timings), "seconds": time.perf_counter() - t0,
               "folder": str(out_dir / slug)}
        )
        write_atomic(tmp / "case.json", json.dumps(final.to_dict(), indent=2, default=_json_default, allow_nan=False))
        _publish(tmp, out_dir / slug)
        return final
    finally:
        if tmp.exists():
            shutil.rmtree(tmp, ignore_errors=True)


def _fields(r: CaseResult) -> dict:
    return {f: getattr(r, f) for f in r.__dataclass_fields__}


def _as_error(r: CaseResult, message: str, stage: str) -> CaseResult:
    return CaseResult(**{**_fields(r), "status": STATUS_ERROR, "message": message, "error_stage": stage})


def _json_default(o):
    import numpy as np

    if isinstance(o, np.generic):
        return o.item()
    if isinstance(o, np.ndarray):
        return o.tolist()
    if isinstance(o, Path):
        return str(o)
    raise TypeError(f"not JSON serialisable: {type(o).__name__}")


def _write_minimal(folder: Path, result: CaseResult, trace: str) -> None:
    from fe_crank.report.html import write_error_report

    write_error_report(folder, result, trace)


def _write_report(folder: Path, result: CaseResult, stage_out: dict, options: CheckOptions, trace: str) -> None:
    from fe_crank.report import write_case_report

    write_case_report(folder, result, stage_out, options=options, trace=trace)


# --------------------------------------------------------------------------- batches


def _run_case_job(path: str, out_dir: str, options: CheckOptions, slug: str) -> CaseResult:
    """Top-level (picklable) job for process pools and Dask workers."""
    return run_case(path, out_dir, options, slug=slug)


def run_cases(
    paths: Sequence[str | Path],
    out_dir: str | Path,
    options: CheckOptions | None = None,
    *,
    jobs: int = 1,
    scheduler: str | object | None = None,
    on_result: Callable[[CaseResult], None] | None = None,
    on_stage: Callable[[str, str], None] | None = None,
) -> list[CaseResult]:
    """Run a batch; results in the order of ``paths``.

    ``jobs == 1`` and no scheduler: in this process (``on_stage`` reports each stage
    as it starts).  ``jobs > 1``: a ``ProcessPoolExecutor`` with the ``spawn`` start
    method (safe with gmsh, VTK and threaded BLAS).  ``scheduler``: the address of
    a running Dask distributed scheduler (or a ``distributed.Client``); each case is
    one task.  ``on_result`` is called in this process as each case finishes.
    """
    options = options or CheckOptions()
    paths = [Path(p) for p in paths]
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    clean_stale_partials(out_dir)
    slugs = unique_slugs(paths)
    results: list[CaseResult | None] = [None] * len(paths)

    def done(i: int, r: CaseResult) -> None:
        results[i] = r
        if on_result is not None:
            on_result(r)

    if scheduler is not None:
        _run_dask(paths, slugs, out_dir, options, scheduler, done)
    elif jobs > 1 and len(paths) > 1:
        import multiprocessing
        from concurrent.futures import ProcessPoolExecutor, as_completed

        ctx = multiprocessing.get_context("spawn")
        with ProcessPoolExecutor(max_workers=min(jobs, len(paths)), mp_context=ctx) as pool:
            futs = {
                pool.submit(_run_case_job, str(p), str(out_dir.resolve()), options, s): i
                for i, (p, s) in enumerate(zip(paths, slugs))
            }
            for fut in as_completed(futs):
                i = futs[fut]
                done(i, _result_or_crash(fut, paths[i]))
    else:
        for i, (p, s) in enumerate(zip(paths, slugs)):
            done(i, run_case(p, out_dir, options, slug=s, on_stage=on_stage))
    return [r for r in results if r is not None]


def _result_or_crash(fut, path: Path) -> CaseResult:
    """A worker that died (killed, out of memory) is an error result for its case."""
    try:
        return fut.result()
    except Exception as exc:
        return CaseResult(
            name=path.stem, source=str(path), status=STATUS_ERROR,
            message=f"the worker running this case stopped: {type(exc).__name__}: {exc}",
            error_stage="worker",
        )


def _run_dask(paths, slugs, out_dir: Path, options, scheduler, done) -> None:
    try:
        from distributed import Client, as_completed
    except ModuleNotFoundError:  # pragma: no cover - distributed is a dependency
        raise InputError("--dask-scheduler needs the 'distributed' package") from None
    own = not hasattr(scheduler, "submit")
    try:
        client = Client(scheduler, timeout="20s") if own else scheduler
    except OSError as exc:
        raise InputError(f"cannot connect to the Dask scheduler {scheduler!r}: {exc}") from None
    try:
        futs = {}
        for i, (p, s) in enumerate(zip(paths, slugs)):
            f = client.submit(
                _run_case_job, str(p.resolve()), str(out_dir.resolve()), options, s,
                key=f"fe-crank-{s}-{hashlib.sha1(str(p.resolve()).encode()).hexdigest()[:8]}-{time.time_ns()}",
                pure=False,
            )
            futs[f] = i
        for fut in as_completed(list(futs)):
            i = futs[fut]
            done(i, _result_or_crash(fut, paths[i]))
    finally:
        if own:
            client.close()


def batch_exit_code(results: Sequence[CaseResult]) -> int:
    """2 if any case errored, else 1 if any failed, else 0 (an empty batch is 2)."""
    if not results:
        return 2
    return max(r.exit_code for r in results)
