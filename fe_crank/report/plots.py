"""matplotlib pictures for the report: ``matplotlib.figure.Figure`` objects printed
through the Agg canvas (files only, never a window, no ``matplotlib.use``: the
process's backend is left alone).

Only what no stage draws itself: the curves of dynamics (``fe_crank.cli.dynamics``)
and the hodographs of balance (``fe_crank.cli.balance``) are drawn by those stages'
own plotting functions, which the report reuses.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np


def figure(figsize: tuple[float, float]):
    """A matplotlib ``Figure`` on its own Agg canvas (not registered with pyplot)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=figsize)
    FigureCanvasAgg(fig)
    return fig


def save(fig, path: str | Path) -> Path:
    """Print ``fig`` (``figure``) to the PNG ``path`` (written atomically)."""
    return _save(fig, path)


def _save(fig, path: str | Path) -> Path:
    import io

    from fe_crank.files import write_atomic

    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=110, bbox_inches="tight")
    return write_atomic(path, buf.getvalue())


def plot_bars(path, labels: Sequence[str], series: Mapping[str, Sequence[float]], *, ylabel: str, title: str) -> Path:
    """Grouped bars (e.g. required vs built counterweight m*r per plane)."""
    fig = figure((6.0, 3.4))
    ax = fig.add_subplot()
    n = max(len(series), 1)
    w = 0.8 / n
    x = np.arange(len(labels))
    for j, (name, vals) in enumerate(series.items()):
        ax.bar(x + (j - (n - 1) / 2) * w, vals, width=w, label=name)
    ax.set_xticks(x, labels, rotation=20 if len(labels) > 3 else 0, ha="right" if len(labels) > 3 else "center")
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.grid(True, axis="y", alpha=0.35)
    top = np.nanmax([np.nanmax(np.asarray(v, float)) for v in series.values()] + [0.0])
    if top > 0:
        ax.set_ylim(0.0, 1.25 * top)  # room for the legend above the bars
    ax.legend(fontsize=8, ncol=len(series), loc="upper center")
    return _save(fig, path)


def plot_against_speed(
    path, speeds_rpm: Sequence[float], panels: Sequence[tuple[str, Sequence[float], float, int]]
) -> Path:
    """Criteria over the full-load curve, one panel each: (label, value at every speed,
    limit, index of the worst speed); the limit as a dashed line, the worst speed marked."""
    fig = figure((6.0, 1.2 + 2.0 * len(panels)))
    axes = fig.subplots(len(panels), 1, sharex=True, squeeze=False)[:, 0]
    for ax, (label, values, limit, worst) in zip(axes, panels, strict=True):
        ax.plot(speeds_rpm, values, "o-", ms=3, label="value")
        ax.axhline(limit, color="tab:red", ls="--", label=f"limit {limit:.4g}")
        ax.plot([speeds_rpm[worst]], [values[worst]], "s", color="tab:red", label=f"worst, {speeds_rpm[worst]:.0f} rpm")
        ax.set_ylabel(label, fontsize=8)
        ax.grid(True, alpha=0.35)
        ax.legend(fontsize=7)
    axes[-1].set_xlabel("crank speed [rpm]")
    axes[0].set_title("Criteria over the full-load curve")
    return _save(fig, path)
