"""Pictures and the HTML fragment of the torsional section; JSON of a ``TorsionResult``.

* ``campbell.png``: natural frequencies (horizontal) and the order lines ``f = n N / 60``
  over the speed range, the resonances inside the range marked;
* ``torsion_response.png``: M_TN (half the range of the synthesised torque) of every
  shaft segment vs speed, the operating speed and each journal's governing speed marked;
* ``torsion_modes.png``: the elastic mode shapes along the chain.
"""

from __future__ import annotations

import html
import io
from pathlib import Path

import numpy as np

from fe_crank.files import write_atomic

RPM = 30.0 / np.pi
PNGS = ("campbell.png", "torsion_response.png", "torsion_modes.png")


def _plt():
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    return plt


def _save(fig, path: Path) -> Path:
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=110, bbox_inches="tight")
    _plt().close(fig)
    return write_atomic(path, buf.getvalue())


def _round(a, digits=6):
    return [float(f"{x:.{digits}g}") for x in np.asarray(a, float).ravel()]


def plot_campbell(res, path: Path) -> Path:
    plt = _plt()
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    lo, hi = res.speed_range
    n_max = res.response.orders.max()
    x = np.array([0.0, 1.1 * hi]) * RPM
    for n in res.response.orders:
        major = n == int(n)
        ax.plot(x, n * x / 60.0, color="0.55" if major else "0.8", lw=0.8)
        ax.text(x[1], n * x[1] / 60.0, f"{n:g}", fontsize=6, va="center")
    fmax = n_max * 1.1 * hi * RPM / 60.0
    for r, f in enumerate(res.modes.elastic_hz, start=1):
        if f <= fmax:
            ax.axhline(f, color="C0", lw=1.2)
            ax.text(0.0, f, f" mode {r}: {f:.0f} Hz", fontsize=7, va="bottom", color="C0")
    for rz in res.resonances:
        if rz.in_range:
            ax.plot(rz.speed * RPM, rz.frequency_hz, "o", color="C3", ms=3.5)
    ax.axvspan(lo * RPM, hi * RPM, color="C2", alpha=0.08, label="speed range")
    ax.axvline(res.operating_speed * RPM, color="C2", lw=1.0, ls="--", label="operating speed")
    ax.set_xlim(0, 1.1 * hi * RPM)
    ax.set_ylim(0, fmax)
    ax.set_xlabel("crank speed [rpm]")
    ax.set_ylabel("frequency [Hz]")
    ax.set_title("Campbell diagram: orders 0.5-12 and natural frequencies")
    ax.legend(fontsize=7, loc="upper left")
    return _save(fig, path)


def plot_response(res, path: Path) -> Path:
    plt = _plt()
    fig, ax = plt.subplots(figsize=(6.4, 4.0))
    rpm = res.response.speeds * RPM
    for i, name in enumerate(res.model.segment_names):
        ax.plot(rpm, res.half_range[:, i], lw=1.0, label=name)
        g = res.governing(i)
        ax.plot(rpm[g], res.half_range[g, i], "v", color="k", ms=3)
    ax.axvline(res.operating_speed * RPM, color="C2", lw=1.0, ls="--")
    ax.set_yscale("log")
    ax.set_xlabel("crank speed [rpm]")
    ax.set_ylabel("alternating torque M_TN [N m]")
    ax.set_title("Shaft segment torque (harmonic synthesis) vs speed")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=6, ncol=2)
    return _save(fig, path)


def plot_modes(res, path: Path, count: int = 4) -> Path:
    plt = _plt()
    fig, ax = plt.subplots(figsize=(6.4, 3.6))
    x = np.arange(res.model.size)
    rigid = res.modes.rigid
    for r in range(1, min(count + 1, res.modes.omega.size - rigid + 1)):
        f = res.modes.frequencies_hz[rigid - 1 + r]
        ax.plot(x, res.modes.shapes[:, rigid - 1 + r], "o-", ms=3, label=f"mode {r}: {f:.0f} Hz")
    ax.axhline(0.0, color="k", lw=0.6)
    ax.set_xticks(x, res.model.names, rotation=30, ha="right", fontsize=7)
    ax.set_ylabel("relative amplitude")
    ax.set_title("Torsional mode shapes")
    ax.legend(fontsize=7)
    return _save(fig, path)


def write_plots(res, folder: str | Path) -> list[Path]:
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    return [
        plot_campbell(res, folder / PNGS[0]),
        plot_response(res, folder / PNGS[1]),
        plot_modes(res, folder / PNGS[2]),
    ]


def governing_table(res) -> list[dict]:
    """Per segment: the largest M_TN over the range, where, the vibratory part there,
    and M_TN at the operating speed (N m, rpm)."""
    i_op = res.index(res.operating_speed)
    rows = []
    for i, name in enumerate(res.model.segment_names):
        g = res.governing(i)
        rows.append(
            {
                "segment": name,
                "max_half_range": float(res.half_range[g, i]),
                "governing_speed_rpm": float(res.response.speeds[g] * RPM),
                "vibratory_half_range_at_governing": float(res.vibratory_half_range[g, i]),
                "half_range_at_operating": float(res.half_range[i_op, i]),
                "vibratory_half_range_at_operating": float(res.vibratory_half_range[i_op, i]),
            }
        )
    return rows


def result_to_dict(res, *, curves: bool = True) -> dict:
    """JSON of a ``TorsionResult`` (SI, speeds also in rpm)."""
    m = res.model
    out = {
        "masses": [
            {"name": n, "inertia": float(j), "absolute_damping": float(c)}
            for n, j, c in zip(m.names, m.inertia, m.absolute_damping)
        ],
        "segments": [
            {"name": n, "stiffness": float(k), "loss_factor": float(e), "damping": float(c)}
            for n, k, e, c in zip(m.segment_names, m.stiffness, m.loss_factor, m.segment_damping)
        ],
        "throw_stiffness": {k: (float(v) if not isinstance(v, str) else v) for k, v in res.stiffness.items()},
        "natural_frequencies_hz": _round(res.modes.elastic_hz),
        "holzer_frequencies_hz": _round(res.holzer_hz),
        "mode_shapes": {
            f"mode_{r}": _round(res.modes.shapes[:, res.modes.rigid - 1 + r])
            for r in range(1, res.modes.elastic_omega.size + 1)
        },
        "resonances_in_range": [
            {"mode": r.mode, "order": r.order, "frequency_hz": r.frequency_hz, "speed_rpm": r.speed * RPM}
            for r in res.resonances
            if r.in_range
        ],
        "operating_speed_rpm": res.operating_speed * RPM,
        "speed_range_rpm": [res.speed_range[0] * RPM, res.speed_range[1] * RPM],
        "orders": _round(res.response.orders),
        "assess_speed": res.assess_speed,
        "flywheel_speed_fluctuation": res.flywheel_fluctuation,
        "segments_governing": governing_table(res),
        "units": {"inertia": "kg m^2", "stiffness": "N m/rad", "damping": "N m s/rad", "torque": "N m"},
    }
    if curves:
        out["speeds_rpm"] = _round(res.response.speeds * RPM)
        out["vibratory_torque_vs_speed"] = {
            n: _round(res.vibratory_half_range[:, i]) for i, n in enumerate(m.segment_names)
        }
        out["torque_half_range_vs_speed"] = {n: _round(res.half_range[:, i]) for i, n in enumerate(m.segment_names)}
    return out


def stiffness_text(res) -> str:
    """Where the throw stiffness comes from, with Carter's and the FE value when known."""
    k = res.stiffness
    if k["used"] == "lumped":
        text = "Lumped model as stated (stations, stiffnesses and damping from the input)"
        return text + (f"; FE throw stiffness {k['fe']:.4g} N m/rad for comparison" if "fe" in k else "")
    text = f"Throw stiffness (FE span): Carter {k['carter']:.4g} N m/rad"
    if "fe" in k:
        text += f", FE {k['fe']:.4g} N m/rad (Carter/FE {k['carter'] / k['fe']:.3f})"
    return text + f"; the model uses {k['used']}"


def html_fragment(res, folder: str | Path) -> str:
    """The torsional section of the report: writes the PNGs into ``folder`` and returns HTML."""
    write_plots(res, folder)
    e = html.escape
    rows = "".join(
        f"<tr><td>{e(r['segment'])}</td><td class=num>{r['max_half_range']:.4g}</td>"
        f"<td class=num>{r['governing_speed_rpm']:.0f}</td><td class=num>{r['vibratory_half_range_at_governing']:.4g}</td>"
        f"<td class=num>{r['half_range_at_operating']:.4g}</td></tr>"
        for r in governing_table(res)
    )
    freqs = ", ".join(f"{f:.1f}" for f in res.modes.elastic_hz[:5])
    elastic = res.modes.elastic_hz
    n = min(res.holzer_hz.size, elastic.size)
    holzer = (
        f"Holzer's table agrees within {np.max(np.abs(res.holzer_hz[:n] / elastic[:n] - 1)):.1e}"
        if n == elastic.size
        else "Holzer's table found only some of the modes: check the model"
    )
    stiff = stiffness_text(res) + "."
    inside = [r for r in res.resonances if r.in_range]

    def strength(r):  # largest vibratory M_TN of the segments at the resonance speed
        return float(res.vibratory_half_range[res.index(r.speed)].max())

    major = sorted(inside, key=strength, reverse=True)[:6]
    res_txt = (
        "; ".join(
            f"mode {r.mode} x order {r.order:g} at {r.speed * RPM:.0f} rpm (vibratory M_TN up to {strength(r):.3g} N m)"
            for r in major
        )
        or "none"
    )
    mode = (
        "the speed of the range where each journal's M_TN is largest (IACS UR M53 2.2.2)"
        if res.assess_speed == "governing"
        else "the operating speed"
    )
    return (
        f"<p>Lumped-mass chain of {res.model.size} masses (docs/torsion.md). Natural frequencies: {e(freqs)} Hz "
        f"({e(holzer)}). {e(stiff)} Resonances inside {res.speed_range[0] * RPM:.0f}-{res.speed_range[1] * RPM:.0f} rpm "
        f"(strongest first): {e(res_txt)}. Flywheel speed fluctuation at the operating speed: "
        f"{100 * res.flywheel_fluctuation:.3g} %.</p>"
        f"<p>The journal torques of the assessment are quasi-static + vibratory, the vibratory part taken at {e(mode)}.</p>"
        "<table><tr><th>segment</th><th>max M_TN [N m]</th><th>at [rpm]</th><th>vibratory part [N m]</th>"
        f"<th>M_TN at operating speed [N m]</th></tr>{rows}</table>"
        "<figure><img src='campbell.png' alt='Campbell diagram'><figcaption>Campbell diagram</figcaption></figure>"
        "<figure><img src='torsion_response.png' alt='torque vs speed'><figcaption>Segment torque vs speed"
        "</figcaption></figure>"
        "<figure><img src='torsion_modes.png' alt='mode shapes'><figcaption>Mode shapes</figcaption></figure>"
    )


def quasi_static_note() -> str:
    """Report text for a case without ``[torsion]``."""
    return (
        "<p>Not computed: the load case has no [torsion] section, so the journal torques are "
        "quasi-static (rigid shaft, cumulative cylinder torque); IACS UR M53 2.2 asks for the vibratory "
        "torque of a forced-vibration calculation (docs/torsion.md).</p>"
    )
