"""The report's FE pictures: per FE model, the ``.vtu`` fields (``fe_crank.report.fields``)
and three renders drawn from those same fields, so file, pictures and tables agree:

* von Mises on the deformed throw at the governing crank angle of the hot spot;
* a close-up of the hot spot's fillet (undeformed);
* the governing overspeed state (``fe_crank.assess.states``): the cycle at the
  overspeed with rod and piston inertia, at the crank angle where the overspeed check's
  governing value occurs, the hot spot and the counterweight maximum marked.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from fe_crank.fe.core.result_fields import write_vtu
from fe_crank.outputs import CaseOutputs
from fe_crank.report import render as rd
from fe_crank.report.fields import field_peak, throw_fields
from fe_crank.report.html import Page, esc

#: the overspeed gas assumption in words (``[operating] overspeed_gas``, fe_crank.mechanism.cycles)
GAS_WORDS = {
    "motored": "motored: no combustion, zero gauge gas pressure",
    "as_operating": "gas as operating: the operating gas pressure table",
}


def _long_gas(words: str) -> str:
    """The gas load of the drawn overspeed cycle for the caption."""
    if words in GAS_WORDS:
        return GAS_WORDS[words]
    return f"motored: {words}" if words.startswith("no combustion") else f"gas as operating: {words}"


def _short_gas(words: str) -> str:
    """A few words for the picture's own text; the caption carries the whole description."""
    if words.startswith("no combustion, zero"):
        return "zero gas"
    if words.startswith("no combustion"):
        return "motored"
    return "gas as operating" if "operating" in words else words


def fe_section(folder: Path, so: CaseOutputs, options) -> list[str]:
    """Per FE model: the ``.vtu`` file and the three pictures (module docstring)."""
    a = so.assessment
    units_by_key = so.unit_solutions
    if not units_by_key or a is None:
        return []
    render = options is None or options.render
    write_vtu_files = options is None or options.write_vtu
    if not (render or write_vtu_files):
        return ["<p>Pictures and fields switched off for this run (--no-render --no-vtu).</p>"]
    out = []
    for st in a.states:
        unit_solutions = units_by_key[st.keys[0]]
        tf = throw_fields(unit_solutions, st, a.throws)
        names = st.throws
        if len(names) > 1:  # identical throws share one FE model: drawn once, where it is most critical
            os_txt = "" if tf.overspeed is None else f", the overspeed state of throw {tf.overspeed.throw}"
            out.append(
                f"<p>One FE model stands for throws {esc(', '.join(names))}, each assessed with its own "
                f"loads; it is drawn where it is most critical: the hot spot of throw {esc(tf.hotspot.throw)}"
                f"{esc(os_txt)}.</p>"
            )
        tag = f"throw{_safe(tf.hotspot.throw)}"
        angle_txt = "" if tf.angle_deg is None else f" at crank angle {tf.angle_deg:.0f} deg"
        if write_vtu_files:
            write_vtu(Path(folder) / f"{tag}.vtu", tf.mesh)
            out.append(
                f"<p>Fields for ParaView: <code>{tag}.vtu</code> (quadratic tetrahedra; displacement, stress "
                f"tensor, von Mises and principal stresses of throw {esc(tf.hotspot.throw)}{angle_txt} and, "
                "with the suffix <code>_overspeed</code>, in the governing overspeed state"
                + ("" if tf.overspeed is None else f" (throw {esc(tf.overspeed.throw)})")
                + "; fatigue amplitude, mean "
                "and safety over the cycle; subdomain, boundary and assessed-group ids; units in the field "
                "names).</p>"
            )
        if render:
            size = float(np.linalg.norm(np.ptp(np.asarray(unit_solutions.points), axis=1)))
            grid = rd.grid_of(tf.mesh, _display(tf.mesh.point_data))
            out += _hotspot_figures(Path(folder), tag, tf, grid, size, angle_txt)
            if tf.overspeed is not None:
                out += _overspeed_figure(Path(folder), f"throw{_safe(tf.overspeed.throw)}", tf, grid, size)
    return out


def _display(pd) -> dict[str, np.ndarray]:
    """Display-only copies in MPa of the drawn von Mises fields."""
    out = {"von_mises_MPa": pd["von_mises_Pa"] / 1e6}
    if "von_mises_overspeed_Pa" in pd:
        out["von_mises_overspeed_MPa"] = pd["von_mises_overspeed_Pa"] / 1e6
    return out


def _hotspot_figures(folder: Path, tag: str, tf, grid, size: float, angle_txt: str) -> list[str]:
    """The deformed throw at the hot spot's angle and the close-up of its fillet."""
    crit, pd = tf.hotspot, tf.mesh.point_data
    throw, group = crit.throw, crit.group
    umax = float(np.max(np.linalg.norm(pd["displacement_m"], axis=1)))
    scale = rd.exaggeration_factor(umax, size)
    hp = np.asarray(crit.point, float)
    vm_hot = float(pd["von_mises_Pa"][crit.node]) / 1e6
    label = f"hot spot ({crit.what}) {vm_hot:.4g} MPa"
    v = rd.render_field(
        folder / f"{tag}_von_mises.png",
        grid,
        "von_mises_MPa",
        title="von Mises [MPa]",
        displacement="displacement_m",
        scale=scale,
        hotspot=_drawn(tf, crit.node, "displacement_m", scale),
        hotspot_label=label,
        text=f"throw {throw}{angle_txt}; deformation x {scale:g}",
    )
    rd.render_field(
        folder / f"{tag}_hotspot.png",
        grid,
        "von_mises_MPa",
        title="von Mises [MPa]",
        hotspot=hp,
        hotspot_label=label,
        focus=(hp, max(0.12 * size, 1e-3)),
        text=f"close-up of {group}{angle_txt}, undeformed",
    )
    return [
        Page.figure(
            f"{tag}_von_mises.png",
            f"Throw {throw}: von Mises stress{angle_txt} (largest von Mises of {group}), peak on the part "
            f"{v.peak:.4g} MPa, on the deformed shape; deformation exaggerated x {scale:g} (largest "
            f"displacement {umax * 1e6:.1f} um)",
        ),
        Page.figure(
            f"{tag}_hotspot.png",
            f"Close-up of {group} (undeformed): hot spot of the {crit.what} assessment at "
            f"({', '.join(f'{c * 1e3:.1f}' for c in hp)}) mm{angle_txt}, von Mises there {vm_hot:.4g} MPa",
        ),
    ]


def _overspeed_figure(folder: Path, tag: str, tf, grid, size: float) -> list[str]:
    """The governing overspeed state on the deformed throw: the overspeed check's hot spot
    (magenta) and the counterweight's largest von Mises in this state (black)."""
    os_, pd = tf.overspeed, tf.mesh.point_data
    vm = np.asarray(pd["von_mises_overspeed_Pa"], float)
    umax = float(np.max(np.linalg.norm(pd["displacement_overspeed_m"], axis=1)))
    scale = rd.exaggeration_factor(umax, size)
    vm_hot = float(vm[os_.node]) / 1e6
    safety = "" if os_.safety is None else f", overspeed safety {os_.safety:.3g}"
    marks: tuple[tuple[np.ndarray, str], ...] = ()
    cw_txt, key_txt = "", ""
    peaks = [(*field_peak(vm, g), g) for g in os_.counterweights]
    if peaks:
        value, node, cw = max(peaks, key=lambda p: p[0])
        point = np.asarray(tf.mesh.points[node], float)
        marks = ((_drawn(tf, node, "displacement_overspeed_m", scale), "counterweight max"),)
        key_txt = f"; black: max of {cw.group} {value / 1e6:.4g} MPa"
        ext = cw.max_von_mises_overspeed
        cw_txt = (
            f"; black: the largest von Mises of {cw.group} in this state, {value / 1e6:.4g} MPa at "
            f"({', '.join(f'{c * 1e3:.1f}' for c in point)}) mm (its maximum over the overspeed cycle "
            f"{ext.value / 1e6:.4g} MPa" + ("" if ext.angle is None else f" at {np.degrees(ext.angle):.0f} deg") + ")"
        )
    when = f"{os_.rpm:.0f} rpm, crank angle {os_.angle_deg:.0f} deg"
    v = rd.render_field(
        folder / f"{tag}_overspeed.png",
        grid,
        "von_mises_overspeed_MPa",
        title="von Mises [MPa]",
        displacement="displacement_overspeed_m",
        scale=scale,
        hotspot=_drawn(tf, os_.node, "displacement_overspeed_m", scale),
        hotspot_label="overspeed hot spot",
        marks=marks,
        text=f"throw {os_.throw} at overspeed {when} ({_short_gas(os_.gas)}); deformation x {scale:g}\n"
        f"magenta: overspeed hot spot, {os_.group} {vm_hot:.4g} MPa{key_txt}",
    )
    return [
        Page.figure(
            f"{tag}_overspeed.png",
            f"Throw {os_.throw} at overspeed {when}: the governing state of the overspeed check (the cycle recomputed "
            f"at the overspeed with rod and piston inertia and the crank's own body force; "
            f"{_long_gas(os_.gas)}), the crank angle of the largest von Mises of {os_.group} over that "
            f"cycle; peak on the part {v.peak:.4g} MPa; magenta: the overspeed hot spot, {os_.group} at "
            f"({', '.join(f'{c * 1e3:.1f}' for c in os_.point)}) mm, {vm_hot:.4g} MPa{safety}{cw_txt}; deformation exaggerated x {scale:g} (largest displacement "
            f"{umax * 1e6:.1f} um)",
        )
    ]


def _drawn(tf, node: int, displacement: str, scale: float) -> np.ndarray:
    """Where a node is drawn on a deformed picture: x + scale u (markers sit on the surface)."""
    pd = tf.mesh.point_data
    return np.asarray(tf.mesh.points[node], float) + scale * np.asarray(pd[displacement][node], float)


def _safe(name: str) -> str:
    return re.sub(r"[^A-Za-z0-9_-]+", "_", str(name))
