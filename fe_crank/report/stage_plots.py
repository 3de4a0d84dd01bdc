"""Pictures of the dynamics and balance stages, drawn for their own commands
(``fe-crank dynamics``, ``fe-crank balance``) and for the check's report."""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np

from fe_crank.files import write_atomic


def dynamics_plots(res, out: Path) -> None:
    """Piston motion, forces per cylinder, torque and the crankpin polar diagram:
    ``piston_motion.png``, ``forces.png``, ``torque.png``, ``crankpin_polar.png`` in ``out``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    deg = np.degrees(res.theta)

    def save(fig, name):
        buf = io.BytesIO()
        fig.savefig(buf, dpi=110, format="png")
        write_atomic(out / name, buf.getvalue())
        plt.close(fig)

    fig, ax = plt.subplots(3, 1, sharex=True, figsize=(8, 7))
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
    save(fig, "piston_motion.png")

    fig, ax = plt.subplots(figsize=(8, 5))
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
    save(fig, "forces.png")

    fig, ax = plt.subplots(figsize=(8, 4.5))
    ax.plot(deg, res.torque, label="total")
    ax.axhline(res.mean_torque, color="k", lw=0.8, label=f"mean {res.mean_torque:.1f} N·m")
    ax.set_xlabel("cycle angle θ [deg]")
    ax.set_ylabel("torque [N·m]")
    ax.grid(alpha=0.3)
    ax.legend()
    ax.set_title("Indicated torque")
    save(fig, "torque.png")

    fig, ax = plt.subplots(figsize=(6, 6))
    for name, t in res.throws.items():
        ax.plot(t.pin_force[:, 0] / 1e3, t.pin_force[:, 1] / 1e3, label=f"throw {name}")
    ax.plot([0], [0], "k+")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("tangential (throw x) [kN]")
    ax.set_ylabel("radial outward (throw y) [kN]")
    ax.grid(alpha=0.3)
    ax.legend()
    ax.set_title("Crankpin load, polar diagram (throw frame)")
    save(fig, "crankpin_polar.png")


def plot_hodographs(res, out: Path) -> list[Path]:
    """One PNG per reported order: force and couple hodographs by source (Agg backend)."""
    import matplotlib

    matplotlib.use("Agg", force=True)
    import matplotlib.pyplot as plt
    import numpy as np

    from fe_crank.balance.forces import REPORTED_ORDERS

    th = np.linspace(0.0, 2.0 * np.pi, 361)
    paths = []
    for k in REPORTED_ORDERS:
        fig, axes = plt.subplots(1, 2, figsize=(9, 4.5))
        drawn = False
        curves = [(src, res.residual.total(k, (src,)), "-") for src in res.residual.sources]
        curves.append(("free (before balancing)", res.forces.total(k), "-"))
        curves.append(("residual", res.residual.total(k), "--"))
        for src, t, style in curves:
            if not (t.force.any() or t.moment.any()):
                continue
            f, m = t.evaluate(th / k)
            lw = 1 if src in res.residual.sources else 2
            axes[0].plot(f[:, 0] / 1e3, f[:, 1] / 1e3, style, label=src, lw=lw)
            axes[1].plot(m[:, 0] / 1e3, m[:, 1] / 1e3, style, label=src, lw=lw)
            drawn = True
        if not drawn:
            plt.close(fig)
            continue
        for ax, what, unit in ((axes[0], "force", "kN"), (axes[1], "couple (Mx, My)", "kN m")):
            ax.set_aspect("equal", adjustable="datalim")
            ax.axhline(0, color="0.7", lw=0.5)
            ax.axvline(0, color="0.7", lw=0.5)
            ax.set_xlabel(f"x [{unit}]")
            ax.set_ylabel(f"y [{unit}]")
            ax.set_title(f"order {k:g} {what}")
            ax.legend(fontsize=7)
        fig.suptitle(res.engine, fontsize=9)
        fig.tight_layout()
        path = out / f"hodograph_order{k:g}.png"
        buf = io.BytesIO()
        fig.savefig(buf, dpi=100, format="png")
        plt.close(fig)
        write_atomic(path, buf.getvalue())
        paths.append(path)
    return paths
