"""Pictures of the dynamics and balance stages, drawn for their own commands
(``fe-crank dynamics``, ``fe-crank balance``) and for the check's report.

matplotlib ``Figure`` objects on their own Agg canvas (``fe_crank.report.plots.figure``):
no ``matplotlib.use``, no pyplot state, never a window.
"""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np

from fe_crank.files import write_atomic
from fe_crank.report.plots import figure

#: a hodograph whose amplitude is below this share of the largest amplitude of the
#: engine (any order, any source) is negligible or rounding noise: not drawn (the
#: report's and the command's tables still list every amplitude)
HODOGRAPH_NOISE = 1e-3


def _save(fig, path: Path, dpi: int = 110) -> Path:
    buf = io.BytesIO()
    fig.savefig(buf, dpi=dpi, format="png")
    return write_atomic(path, buf.getvalue())


def dynamics_plots(res, out: Path) -> None:
    """Piston motion, forces per cylinder, torque and the crankpin polar diagram:
    ``piston_motion.png``, ``forces.png``, ``torque.png``, ``crankpin_polar.png`` in ``out``."""
    deg = np.degrees(res.theta)

    fig = figure((8, 7))
    ax = fig.subplots(3, 1, sharex=True)
    for name, c in res.cylinders.items():
        ax[0].plot(deg, c.motion.s * 1e3, label=name)
        ax[1].plot(deg, c.motion.v)
        ax[2].plot(deg, c.motion.a)
    ax[0].set_ylabel("s [mm]")
    ax[1].set_ylabel("v [m/s]")
    ax[2].set_ylabel("a [m/s²]")
    ax[2].set_xlabel("cycle angle θ [deg]")
    ax[0].legend(title="cylinder", fontsize=7)
    ax[0].set_title(f"Piston motion — {res.engine}")
    for a in ax:
        a.grid(alpha=0.3)
    _save(fig, out / "piston_motion.png")

    fig = figure((8, 5))
    ax = fig.add_subplot()
    for name, c in res.cylinders.items():
        ax.plot(deg, c.gas / 1e3, label=f"{name}: gas")
        ax.plot(deg, c.inertia / 1e3, "--", label=f"{name}: reciprocating inertia")
        ax.plot(deg, c.tangential / 1e3, label=f"{name}: tangential")
        ax.plot(deg, c.radial / 1e3, ":", label=f"{name}: radial")
    ax.set_xlabel("cycle angle θ [deg]")
    ax.set_ylabel("force [kN]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    ax.set_title("Forces per cylinder")
    _save(fig, out / "forces.png")

    fig = figure((8, 4.5))
    ax = fig.add_subplot()
    ax.plot(deg, res.torque, label="total")
    ax.axhline(res.mean_torque, color="k", lw=0.8, label=f"mean {res.mean_torque:.1f} N·m")
    ax.set_xlabel("cycle angle θ [deg]")
    ax.set_ylabel("torque [N·m]")
    ax.grid(alpha=0.3)
    ax.legend()
    ax.set_title("Indicated torque")
    _save(fig, out / "torque.png")

    fig = figure((6, 6))
    ax = fig.add_subplot()
    for name, t in res.throws.items():
        ax.plot(t.pin_force[:, 0] / 1e3, t.pin_force[:, 1] / 1e3, label=f"throw {name}")
    ax.plot([0], [0], "k+")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("tangential (throw x) [kN]")
    ax.set_ylabel("radial outward (throw y) [kN]")
    ax.grid(alpha=0.3)
    ax.legend()
    ax.set_title("Crankpin load, polar diagram (throw frame)")
    _save(fig, out / "crankpin_polar.png")


def _amplitude(a: np.ndarray) -> float:
    """Largest semi-axis bound of a hodograph: the norm of its cos/sin coefficients."""
    return float(np.linalg.norm(np.asarray(a, float)))


def plot_hodographs(res, out: Path) -> list[Path]:
    """One PNG per reported order that has a free force or couple: force and couple
    hodographs by source.  A curve below ``HODOGRAPH_NOISE`` of the engine's largest
    force (couple) amplitude is left out (negligible or rounding noise); a panel with nothing
    left says so instead of drawing noise; an order with nothing in either panel gets
    no picture."""
    from matplotlib.ticker import MaxNLocator

    from fe_crank.balance.forces import REPORTED_ORDERS

    th = np.linspace(0.0, 2.0 * np.pi, 361)
    every = [res.forces.total(k) for k in REPORTED_ORDERS]
    every += [res.residual.total(k, (s,)) for k in REPORTED_ORDERS for s in res.residual.sources]
    ref_f = max((_amplitude(t.force) for t in every), default=0.0)
    ref_m = max((_amplitude(t.moment) for t in every), default=0.0)
    paths = []
    for k in REPORTED_ORDERS:
        curves = [(src, res.residual.total(k, (src,)), "-") for src in res.residual.sources]
        curves.append(("free (before balancing)", res.forces.total(k), "-"))
        curves.append(("residual", res.residual.total(k), "--"))
        keep_f = [(s, t, st) for s, t, st in curves if _amplitude(t.force) > HODOGRAPH_NOISE * ref_f > 0]
        keep_m = [(s, t, st) for s, t, st in curves if _amplitude(t.moment) > HODOGRAPH_NOISE * ref_m > 0]
        if not (keep_f or keep_m):
            continue
        fig = figure((9, 4.5))
        axes = fig.subplots(1, 2)
        for ax, keep, idx, what, unit in (
            (axes[0], keep_f, 0, "force", "kN"),
            (axes[1], keep_m, 1, "couple (Mx, My)", "kN m"),
        ):
            for src, t, style in keep:
                v = t.evaluate(th / k)[idx]
                lw = 1 if src in res.residual.sources else 2
                ax.plot(v[:, 0] / 1e3, v[:, 1] / 1e3, style, label=src, lw=lw)
            ax.set_title(f"order {k:g} {what}")
            if not keep:
                ax.text(
                    0.5,
                    0.5,
                    f"no free {what.split()[0]} of order {k:g}",
                    ha="center",
                    va="center",
                    transform=ax.transAxes,
                    color="0.4",
                )
                ax.set_xticks([])
                ax.set_yticks([])
                continue
            ax.set_aspect("equal", adjustable="datalim")
            ax.axhline(0, color="0.7", lw=0.5)
            ax.axvline(0, color="0.7", lw=0.5)
            ax.xaxis.set_major_locator(MaxNLocator(5))
            ax.yaxis.set_major_locator(MaxNLocator(5))
            ax.set_xlabel(f"x [{unit}]")
            ax.set_ylabel(f"y [{unit}]")
            ax.legend(fontsize=7)
        fig.suptitle(res.engine, fontsize=9)
        fig.tight_layout()
        paths.append(_save(fig, out / f"hodograph_order{k:g}.png", dpi=100))
    return paths
