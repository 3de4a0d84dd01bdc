"""The study's files: the table of every candidate (CSV, JSON, markdown), the Pareto plot,
and the recommended candidate's geometry and load case for ``fe-crank check``."""

from __future__ import annotations

import csv
import io
import json
import math
import os
from pathlib import Path

import numpy as np

from fe_crank.assess.joint_criteria import JOINT_QUANTITIES
from fe_crank.errors import InputError
from fe_crank.files import write_atomic
from fe_crank.io.base import read_toml
from fe_crank.io.includes import folder_tree
from fe_crank.study.run import CandidateResult, StudyResult

COLUMNS = (
    ("index", "#"),
    ("placement", "placement"),
    ("rotating_rate_percent", "rotating rate %"),
    ("reciprocating_share_percent", "recip. share %"),
    ("offset_deg", "offset deg"),
    ("counterweight_mass_kg", "cw mass kg"),
    ("mass_change_kg", "shaft mass change kg"),
    ("polar_inertia_change_kg_m2", "J change kg m^2"),
    ("first_torsional_frequency_hz", "1st torsional natural frequency Hz"),
    ("peak_main_bearing_load_n", "peak bearing load N"),
    ("peak_specific_load_mpa", "peak specific load MPa"),
    ("max_web_bending_moment_nm", "max web moment N m"),
    ("min_oil_film_um", "min oil film um"),
    ("peak_film_pressure_mpa", "peak film pressure MPa"),
    ("fillet_peak_von_mises_mpa", "fillet peak von Mises MPa"),
    ("fillet_static_safety", "fillet static safety"),
    ("fillet_fatigue_safety", "fillet fatigue safety"),
    ("counterweight_junction_peak_mpa", "cw junction peak MPa"),
    ("overspeed_peak_von_mises_mpa", "overspeed peak von Mises MPa"),
    ("overspeed_safety", "overspeed safety"),
    ("counterweight_overspeed_peak_mpa", "cw junction overspeed peak MPa"),
    ("counterweight_body_peak_mpa", "cw peak (per-throw model) MPa"),
    ("m53_acceptability", "UR M53 Q"),
    ("bolt_assembly_utilisation", "bolt assembly utilisation nu"),
    ("bolt_working_safety", "bolt working safety S_F"),
    ("bolt_fatigue_safety", "bolt fatigue safety S_D"),
    ("bolt_separation_safety", "bolt separation safety S_sep"),
    ("bolt_slip_safety", "bolt slip safety S_G"),
    ("free_force_first_order_n", "free force 1st N"),
    ("free_moment_first_order_nm", "free moment 1st N m"),
    ("buildable", "buildable"),
    ("meets_limits", "meets limits"),
    ("recommended", "recommended"),
)


def row(r: CandidateResult, recommended: bool) -> dict:
    c = r.candidate
    st = r.stresses
    os = r.overspeed
    return {
        "index": c.index,
        "placement": c.placement,
        "rotating_rate_percent": round(c.rotating * 100, 9),
        "reciprocating_share_percent": round(c.reciprocating * 100, 9),
        "offset_deg": round(math.degrees(c.offset), 9),
        "counterweight_mass_kg": r.counterweight_mass,
        "mass_change_kg": r.mass_change,
        "polar_inertia_change_kg_m2": r.polar_inertia_change,
        "first_torsional_frequency_hz": r.torsional_frequency,
        "peak_main_bearing_load_n": r.peak_bearing_load,
        "peak_specific_load_mpa": r.peak_specific_load / 1e6,
        "max_web_bending_moment_nm": r.max_web_moment,
        "min_oil_film_um": None if r.film is None else r.film.min_film * 1e6,
        "peak_film_pressure_mpa": None if r.film is None else r.film.peak_pressure / 1e6,
        "fillet_peak_von_mises_mpa": None if st is None else st.shaft_peak / 1e6,
        "fillet_static_safety": None if st is None else st.static_safety,
        "fillet_fatigue_safety": None if st is None else st.fatigue_safety,
        "counterweight_junction_peak_mpa": None if st is None else st.counterweight_peak / 1e6,
        "overspeed_peak_von_mises_mpa": None if os is None else os.peak / 1e6,
        "overspeed_safety": None if os is None else os.safety,
        "counterweight_overspeed_peak_mpa": None if os is None else os.counterweight_peak / 1e6,
        "counterweight_body_peak_mpa": None if r.bodies is None else r.bodies.peak / 1e6,
        "m53_acceptability": None if r.m53 is None else r.m53.acceptability,
        **{k: _joint(r, k) for k in JOINT_COLUMNS},
        "free_force_first_order_n": r.free_force,
        "free_moment_first_order_nm": r.free_moment,
        "buildable": c.buildable,
        "meets_limits": r.meets_limits,
        "recommended": recommended,
    }


#: the joint columns: the study's limit key of each (``study.joints.LIMITS``)
JOINT_COLUMNS = {q: f"{sense}_{q}" for q, (_, sense) in JOINT_QUANTITIES.items()}


def _joint(r: CandidateResult, column: str) -> float | None:
    """A joint column's value: the worst over the candidate's joints and states (None: not
    screened; a slip or fatigue safety with no load to divide by is infinite, written as None)."""
    if r.joints is None:
        return None
    v = r.joints.values.get(JOINT_COLUMNS[column])
    return None if v is None or not math.isfinite(v) else v


def detail(r: CandidateResult) -> dict:
    c = r.candidate
    own = row(r, False)
    if r.torsional_frequency is None:  # a column of the study with [torsion] alone
        del own["first_torsional_frequency_hz"]
    return {
        **own,
        "peak_where": r.peak_where,
        "web_moment_where": r.web_where,
        "stresses_where": None
        if r.stresses is None
        else {
            "fillet_peak": r.stresses.shaft_peak_where,
            "fillet_fatigue": r.stresses.fatigue_where,
            "counterweight_junction_peak": r.stresses.counterweight_where,
        },
        "overspeed_where": None
        if r.overspeed is None
        else {"peak": r.overspeed.peak_where, "counterweight_junction_peak": r.overspeed.counterweight_where},
        "m53_where": None if r.m53 is None else r.m53.where,
        "counterweight_body_peak_where": None if r.bodies is None else r.bodies.where,
        "bolt_where": None if r.joints is None else dict(r.joints.where),
        "oil_film": None
        if r.film is None
        else {
            "min_film_where": r.film.min_film_where,
            "peak_pressure_where": r.film.peak_pressure_where,
            "every_orbit_repeated": r.film.converged,
        },
        "unbalance_kg_m": r.unbalance,
        "balance_rate_by_throw": {k: (None if math.isnan(v) else v) for k, v in r.rates.items()},
        "bearing_peak_n": r.bearing_peaks,
        "bearing_mean_n": r.bearing_means,
        "web_moment_peak_nm": r.web_peaks,
        "limits_failed": list(r.failed),
        "not_buildable": list(c.refusals),
        "factors": {f"{w[0]}.{w[1]}": k for w, k in c.factors.items()},
        "shapes": [
            {
                "web": f"{s.web[0]}.{s.web[1]}",
                "mass_factor": s.factor,
                "free": s.free,
                "sector": None if s.sector is None else s.sector.as_dict(),
                "refused": s.refused,
            }
            for s in c.shapes
        ],
    }


def _fmt(v) -> str:
    if v is None:
        return "-"
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, float):
        return f"{v:.4g}"
    return str(v)


def write_tables(res: StudyResult, out: Path, achieved: dict | None = None) -> dict[str, Path]:
    """The table in CSV, JSON and markdown; ``achieved``: per web of the written
    candidate (the m r aimed at, the written sector solid's m r, which the screening
    takes), kg m."""
    achieved = achieved or {}
    best = res.recommended
    rows = [row(r, r is best) for r in res.results]
    # the oil-film columns only where a bearing has a film
    cols = [(k, h) for k, h in COLUMNS if any(x[k] is not None for x in rows)]
    rows = [{k: x[k] for k, _ in cols} for x in rows]
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=[k for k, _ in cols], lineterminator="\n")
    w.writeheader()
    for x in rows:
        w.writerow({k: (repr(v) if isinstance(v, float) else v) for k, v in x.items()})
    paths = {"csv": out / "study.csv", "json": out / "study.json", "md": out / "study.md"}
    write_atomic(paths["csv"], buf.getvalue())
    doc = {
        "study": res.spec.name,
        "study_file": res.spec.file,
        "loadcase": res.loadcase.source_file,
        "rule": res.spec.rule,
        "limits": res.spec.limits,
        "joint_limits": res.joint_limits,
        "states": [{"label": s.label, "speed_rad_s": s.speed} for s in res.states],
        "free_forces_at_rad_s": res.residual_speed,
        "n_dof": res.shaft.n_dof,
        "recommended": None if best is None else best.candidate.index,
        "why": res.why,
        "written_unbalance_kg_m": {
            f"{t}.{w}": {"aimed_at": a, "written_solid": b} for (t, w), (a, b) in achieved.items()
        },
        "notes": list(res.notes),
        "candidates": [detail(r) | {"recommended": r is best} for r in res.results],
    }
    write_atomic(paths["json"], json.dumps(doc, indent=1, allow_nan=False) + "\n")
    lines = [f"# Counterweight study: {res.spec.name}", "", f"Load case: `{res.loadcase.source_file}`", ""]
    lines.append("| " + " | ".join(h for _, h in cols) + " |")
    lines.append("|" + "---|" * len(cols))
    for x in rows:
        lines.append("| " + " | ".join(_fmt(x[k]) for k, _ in cols) + " |")
    lines += [
        "",
        "-: not screened for that candidate (nothing to screen, such as a joint where no "
        "counterweight is bolted or the joint's figure has no load to divide by, or a check "
        "that could not run: the list below says which and why).",
        "",
        f"**Recommended** ({res.spec.rule}): "
        + (f"#{best.candidate.index}, {best.candidate.label}: " if best else "")
        + res.why,
        "",
    ]
    for (t, w), (a, b) in achieved.items():
        lines.append(
            f"* web {t}.{w}: m r {a:.5g} kg m aimed at, {b:.5g} kg m of the written sector's solid "
            f"({(b / a - 1) * 100:+.2f} %; the screening takes the written solid's)"
        )
    lines.append("")
    for r in res.results:
        if r.candidate.refusals or r.failed:
            lines.append(f"* #{r.candidate.index} {r.candidate.label}: " + "; ".join(r.candidate.refusals + r.failed))
    lines += [""] + [f"Note: {n}" for n in res.notes]
    write_atomic(paths["md"], "\n".join(lines) + "\n")
    return paths


def _colour(rs: list[CandidateResult]) -> tuple[list[float], str]:
    """The Pareto plot's colour: the least screened fillet fatigue safety, else the least
    static safety, else (no stresses screened) the largest web bending moment."""
    st = [r.stresses for r in rs]
    fat = [s.fatigue_safety for s in st if s is not None and s.fatigue_safety is not None]
    if rs and len(fat) == len(rs):
        return fat, "least fillet fatigue safety (screened)"
    static = [s.static_safety for s in st if s is not None and math.isfinite(s.static_safety)]
    if rs and len(static) == len(rs):
        return static, "least fillet static safety (screened)"
    return [r.max_web_moment for r in rs], "largest web bending moment (N m)"


def pareto_plot(res: StudyResult, path: Path) -> Path:
    """Peak main-bearing load against counterweight mass, coloured by the least screened
    fillet fatigue safety (``_colour``); the not-buildable candidates hollow; the limits
    drawn."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7.5, 5.0), dpi=110)
    rs = res.results
    ok = [r for r in rs if r.candidate.buildable]
    bad = [r for r in rs if not r.candidate.buildable]
    colour, label = _colour(ok)
    sc = ax.scatter(
        [r.counterweight_mass for r in ok],
        [r.peak_bearing_load / 1e3 for r in ok],
        c=colour,
        cmap="viridis",
        s=36,
        zorder=3,
    )
    if ok:
        bar = fig.colorbar(sc, ax=ax, label=label)
        key = "min_fillet_fatigue_safety" if "fatigue" in label else "min_fillet_static_safety"
        if "safety" in label and key in res.spec.limits:
            bar.ax.axhline(res.spec.limits[key], color="r", lw=1.5)  # the limit on the colour scale
    if bad:
        ax.scatter(
            [r.counterweight_mass for r in bad],
            [r.peak_bearing_load / 1e3 for r in bad],
            facecolors="none",
            edgecolors="red",
            s=36,
            label="cannot be built",
            zorder=3,
        )
    for name in dict.fromkeys(r.candidate.placement for r in rs):
        own = sorted((r for r in rs if r.candidate.placement == name), key=lambda r: r.counterweight_mass)
        ax.plot([r.counterweight_mass for r in own], [r.peak_bearing_load / 1e3 for r in own], lw=0.8, label=name)
    lim = res.spec.limits
    if "max_main_bearing_load" in lim:
        ax.axhline(lim["max_main_bearing_load"] / 1e3, color="k", ls="--", lw=1, label="bearing load limit")
    if "max_main_bearing_specific_load" in lim:
        layout = res.shaft.layout
        w = min(b.width for b in layout.bearings)
        ax.axhline(
            lim["max_main_bearing_specific_load"] * layout.geometry.journal_diameter * w / 1e3,
            color="k",
            ls="-.",
            lw=1,
            label="specific load limit (narrowest bearing)",
        )
    if "max_counterweight_mass" in lim:
        ax.axvline(lim["max_counterweight_mass"], color="k", ls=":", lw=1, label="mass limit")
    if res.recommended is not None:
        r = res.recommended
        ax.scatter(
            [r.counterweight_mass],
            [r.peak_bearing_load / 1e3],
            marker="*",
            s=220,
            c="orange",
            zorder=4,
            label="recommended",
        )
    ax.set_xlabel("counterweight mass of the shaft (kg)")
    ax.set_ylabel("peak main-bearing load (kN)")
    ax.set_title(res.spec.name, fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)
    return path


def _toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, float)):
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, list):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{_key(k)} = {_toml_value(x)}" for k, x in v.items()) + " }"
    raise TypeError(f"cannot write {type(v).__name__} to TOML")


def _key(k: str) -> str:
    return k if k.replace("_", "").replace("-", "").isalnum() else json.dumps(k)


def to_toml(data: dict, head: str = "") -> str:
    """A TOML text of ``data``: scalars, tables, arrays of tables (one level), the rest inline."""
    lines = [f"# {x}" for x in head.splitlines()]
    tables = {k: v for k, v in data.items() if isinstance(v, dict)}
    arrays = {k: v for k, v in data.items() if isinstance(v, list) and v and all(isinstance(x, dict) for x in v)}
    for k, v in data.items():
        if k not in tables and k not in arrays:
            lines.append(f"{_key(k)} = {_toml_value(v)}")
    for k, v in tables.items():
        lines += ["", f"[{_key(k)}]"] + [f"{_key(a)} = {_toml_value(b)}" for a, b in v.items()]
    for k, v in arrays.items():
        for t in v:
            lines += ["", f"[[{_key(k)}]]"] + [f"{_key(a)} = {_toml_value(b)}" for a, b in t.items()]
    return "\n".join(lines) + "\n"


def _mm(x: float) -> str:
    return f"{x * 1e3:.12g} mm"


def leaves_tree(lc_path: Path) -> bool:
    """Whether the written load case names a file outside its folder tree (``fe-crank
    check`` then wants ``--allow-outside-paths``)."""
    root = folder_tree(lc_path)
    data = read_toml(lc_path, record=False)
    for key in ("engine", "geometry"):
        v = data.get(key)
        if isinstance(v, str) and not (lc_path.parent / v).resolve().is_relative_to(root):
            return True
    return False


def write_candidate(res: StudyResult, r: CandidateResult, out: Path) -> tuple[Path, Path]:
    """The candidate's geometry (the drawn file with each throw's counterweight table
    replaced by the candidate's sectors, ``false`` where it has none) and a load case
    naming it (the study's load case with its geometry and engine paths re-pointed)."""
    lc = res.loadcase
    g = lc.geometry
    gfile = Path(getattr(g, "file", "") or lc.source_file)
    gdata = read_toml(gfile, record=False)
    shapes = {s.web: s for s in r.candidate.shapes}
    throws_out = []
    layout = res.shaft.layout
    src_throws = gdata.get("throws") or [{}]
    if len(src_throws) != len(layout.throws):
        raise InputError(
            "a geometry of one throw for every throw of the engine cannot take per-throw counterweights",
            file=str(gfile),
            key="throws",
        )
    for th, t_in in zip(layout.throws, src_throws):
        t_out = {k: v for k, v in t_in.items() if k != "counterweight"}
        own = [shapes[(th.name, w)] for w in (1, 2) if (th.name, w) in shapes and shapes[(th.name, w)].factor > 0]
        if not own:
            t_out["counterweight"] = False
        else:
            dims = [(x.sector.r_outer, x.sector.r_inner, x.sector.angle, x.sector.thickness) for x in own if x.sector]
            if len(dims) != len(own) or not np.allclose(dims, dims[0], rtol=1e-9, atol=0.0):
                raise InputError(
                    f"throw {th.name}: its webs' counterweights differ and a geometry file takes one per throw",
                    file=res.spec.file,
                    key="study.placements",
                )
            s = own[0].sector
            assert s is not None
            drawn = next(d for d in th.spec.counterweights if d.web == own[0].web[1])
            cw: dict = {
                "outer_radius": _mm(s.r_outer),
                "inner_radius": _mm(s.r_inner),
                "angle": f"{math.degrees(s.angle):.12g} deg",
                "thickness": _mm(s.thickness),
                "webs": [x.web[1] for x in own],
            }
            if drawn.fillet_radius is not None:
                cw["fillet_radius"] = _mm(drawn.fillet_radius)
            if r.candidate.offset != 0.0:  # turned from opposite the pin (the candidate's offset)
                cw["offset"] = f"{math.degrees(r.candidate.offset):.12g} deg"
            raw_cw = t_in.get("counterweight") or gdata.get("counterweight") or {}
            if isinstance(raw_cw, dict) and "bolted" in raw_cw:
                cw["bolted"] = raw_cw["bolted"]
            t_out["counterweight"] = cw
        throws_out.append(t_out)
    gdata = {k: v for k, v in gdata.items() if k != "counterweight"}
    gdata["throws"] = throws_out
    out.mkdir(parents=True, exist_ok=True)
    geo_path = out / "candidate_geometry.toml"
    head = f"Counterweight study {res.spec.name!r}: candidate #{r.candidate.index}, {r.candidate.label}\nwritten by fe-crank study from {gfile}"
    write_atomic(geo_path, to_toml(gdata, head))
    ldata = read_toml(lc.source_file, record=False)
    base = Path(lc.source_file).parent
    for key in ("engine", "geometry"):
        if isinstance(ldata.get(key), str):
            ldata[key] = os.path.relpath((base / ldata[key]).resolve(), out.resolve())
    ldata["geometry"] = geo_path.name
    if isinstance(ldata.get("name"), str):
        ldata["name"] = f"{ldata['name']} - study candidate #{r.candidate.index}"
    lc_path = out / "candidate_loadcase.toml"
    write_atomic(lc_path, to_toml(ldata, head))
    return geo_path, lc_path
