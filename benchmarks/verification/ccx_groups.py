"""fe-crank's and CalculiX's nodal stresses compared per assessed group and at the peaks
the check reports (``calculix_compare.py``).

Per unit case and group (``assess.assessed_groups``): the largest |sigma_v,CalculiX -
sigma_v,fe-crank| over the group's nodes relative to the group's largest fe-crank value
(``rel_to_max``) and relative to the local fe-crank value at that node (``local``).

Over the cycle (all unit cases): each code's unit stresses superposed with the check's
own coefficients (``superpose.load_coefficients``, the overspeed cycles of
``mechanism.cycles``) and assessed by the check's ``assess.group.assessment.assess_group``: the
static and overspeed peak sigma_v and the Goodman safety of each group, at the node the
check reports (fe-crank's) and at each code's own worst node.  A third recovery,
CalculiX's reproduced on fe-crank's displacements (``ccx_recovery``), shows that the
whole difference is the recovery.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from fe_crank.fe.core.stress import von_mises

PLACE_FLAGS = ("plane", "point", "near_point", "edge")


def place_of(flags: dict, k: int) -> str:
    """Words for node position k: on the mirror plane, at / next to a point constraint, on
    a group's edge, and the curvature of its elements."""
    words = [
        w
        for f, w in (
            ("plane", "mirror plane"),
            ("point", "point constraint"),
            ("near_point", "next to a point constraint"),
            ("edge", "group edge"),
        )
        if flags[f][k]
    ]
    c = float(flags["curvature"][k])
    words.append(f"curved elements ({100 * c:.1f} %)" if c > 1e-9 else "straight elements")
    return ", ".join(words)


def unit_case_table(vf: np.ndarray, vc: np.ndarray, groups: dict, flags: dict, cases) -> dict:
    """Per group: the largest difference over the unit cases (von Mises (k, n) of each
    code at the assessed nodes), relative to the group's maximum and locally."""
    out = {}
    for g, pos in groups.items():
        best = None
        for c in range(vf.shape[0]):
            f, d = vf[c, pos], np.abs(vc[c, pos] - vf[c, pos])
            top = f.max()
            if top <= 0:
                continue
            k = int(np.argmax(d))
            row = {
                "case": cases[c],
                "rel_to_max": float(d[k] / top),
                "local": float(d[k] / max(f[k], 1e-300)),
                "fe": float(f[k]),
                "ccx": float(vc[c, pos[k]]),
                "place": place_of(flags, pos[k]),
                "peak_fe": float(top),
                "peak_ccx": float(vc[c, pos].max()),
                "peak_rel": float(vc[c, pos].max() / top - 1.0),
            }
            if best is None or row["rel_to_max"] > best["rel_to_max"]:
                best = row
        if best is not None:
            out[g] = best
    return out


def throw_cycles(loadcase_path: str, unit) -> dict:
    """Per throw of the load case: the check's coefficients and arguments of ``assess_group``
    (the lines of ``assess_case`` / ``assess_throw`` that build them)."""
    from fe_crank.assess.adapters import m53_geometry_of
    from fe_crank.assess.superpose import load_coefficients
    from fe_crank.io.loadcase import load_loadcase
    from fe_crank.mechanism.cycles import overspeed_cycles
    from fe_crank.mechanism.dynamics import analyse

    lc = load_loadcase(loadcase_path)
    dyn = analyse(lc.engine, lc.operating)
    omega, os_ = lc.operating.speed, lc.operating.overspeed
    cyc = overspeed_cycles(lc.engine, lc.operating, dyn)
    m53g = m53_geometry_of(lc.geometry)
    out = {}
    for tname, tl in dyn.throws.items():
        throw = lc.engine.throw(tname)
        sense = lc.engine.shaft(throw.shaft).sense
        co = load_coefficients(
            tl.pin_force, tl.torque_front, omega, cases=unit.cases, sense=sense, torque_mz=unit.torque_mz
        )
        loads = [(c.dynamics.throws[tname].pin_force, c.dynamics.throws[tname].torque_front) for c in cyc] or [
            ((os_ / omega) ** 2 * tl.pin_force, (os_ / omega) ** 2 * tl.torque_front)
        ]
        co_os = (
            np.vstack(
                [
                    load_coefficients(p, t, os_, cases=unit.cases, sense=sense, torque_mz=unit.torque_mz)
                    for p, t in loads
                ]
            )
            if os_ is not None
            else None
        )
        theta = np.asarray(dyn.theta) if co_os is None else np.tile(np.asarray(dyn.theta), len(loads))
        out[tname] = dict(
            coefficients=co,
            overspeed_coefficients=co_os,
            theta=theta,
            overspeed=os_,
            crank_radius=throw.crank_radius,
            material=lc.material,
            dp=None if m53g is None else m53g.pin_diameter,
            dj=None if m53g is None else m53g.journal_diameter,
        )
    return out


def _at(res, node: int) -> float:
    """A group's per-node static peak (``fields``) at mesh node ``node``."""
    ids = res.fields["node_ids"]
    return float(res.fields["max_von_mises"][np.flatnonzero(ids == node)[0]])


def cycle_table(loadcase_path: str, unit, stresses: dict[str, np.ndarray], flags: dict) -> dict:
    """Per throw and group: static / overspeed peak and Goodman safety with each code's unit
    stresses (``stresses``: name -> (n_cases, 6, n), the first fe-crank's), at the node the
    check reports and at each code's own worst node."""
    from fe_crank.assess.group.assessment import assess_group, section_diameter

    pos_of = {int(n): k for k, n in enumerate(unit.node_ids)}
    out = {}
    for tname, a in throw_cycles(loadcase_path, unit).items():
        rows = {}
        for g in sorted(unit.groups):
            res = {
                name: assess_group(
                    dataclasses.replace(unit, stress=s),
                    g,
                    a["coefficients"],
                    a["theta"],
                    a["material"],
                    crank_radius=a["crank_radius"],
                    overspeed=a["overspeed"],
                    overspeed_coefficients=a["overspeed_coefficients"],
                    diameter=section_diameter(g, a["dp"], a["dj"]),
                )
                for name, s in stresses.items()
            }
            ref = next(iter(res.values()))
            node = ref.max_von_mises.node
            row = {
                "node": node,
                "point_mm": [round(1e3 * c, 3) for c in ref.max_von_mises.point],
                "place": place_of(flags, pos_of[node]),
                "static": {},
                "overspeed": {},
                "goodman": {},
            }
            for name, r in res.items():
                row["static"][name] = {
                    "at_check_node": _at(r, node),
                    "peak": r.max_von_mises.value,
                    "peak_node": r.max_von_mises.node,
                    "peak_place": place_of(flags, pos_of[r.max_von_mises.node]),
                }
                if r.max_von_mises_overspeed is not None:
                    row["overspeed"][name] = {
                        "peak": r.max_von_mises_overspeed.value,
                        "peak_node": r.max_von_mises_overspeed.node,
                    }
                if r.fatigue_safety is not None:
                    row["goodman"][name] = {"min": r.fatigue_safety.value, "node": r.fatigue_safety.node}
            f = np.asarray(ref.fields["max_von_mises"])
            for name, r in res.items():
                d = np.abs(np.asarray(r.fields["max_von_mises"]) - f)
                k = int(np.argmax(d))
                row["static"][name]["max_diff_rel_to_max"] = float(d[k] / f.max())
                row["static"][name]["max_diff_local"] = float(d[k] / f[k])
                row["static"][name]["max_diff_place"] = place_of(flags, pos_of[int(ref.fields["node_ids"][k])])
            rows[g] = row
        out[tname] = rows
    return out


def print_groups(r: dict) -> None:
    for g, d in r.get("groups", {}).items():
        print(
            f"    {g:22s} unit cases: largest |dvM| {100 * d['rel_to_max']:5.1f} % of the group max "
            f"({100 * d['local']:5.1f} % locally; {d['case']}; {d['place']}); group peaks differ by "
            f"{100 * d['peak_rel']:+.2f} %",
            flush=True,
        )
    for t, rows in r.get("cycle", {}).items():
        for g, row in rows.items():
            st = row["static"]
            f, c = st["fe-crank"], st["CalculiX"]
            line = (
                f"    {t}/{g:22s} cycle: static peak fe-crank {f['peak'] / 1e6:8.2f} MPa at node {row['node']} "
                f"({row['place']}); CalculiX there {c['at_check_node'] / 1e6:8.2f} "
                f"({100 * (c['at_check_node'] / f['peak'] - 1):+.2f} %), CalculiX's peak {c['peak'] / 1e6:8.2f} "
                f"({100 * (c['peak'] / f['peak'] - 1):+.2f} %); largest |d| {100 * c['max_diff_rel_to_max']:.1f} % "
                f"of max ({100 * c['max_diff_local']:.1f} % locally, {c['max_diff_place']})"
            )
            gd = row["goodman"]
            if gd:
                line += f"; Goodman fe-crank {gd['fe-crank']['min']:.3f} CalculiX {gd['CalculiX']['min']:.3f}"
            print(line, flush=True)


def von_mises_cases(S: np.ndarray) -> np.ndarray:
    """(k, n) von Mises of (k, 6, n) stresses."""
    return np.stack([von_mises(s) for s in S])
