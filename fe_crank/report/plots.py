"""matplotlib pictures for the report (Agg backend: files only, never a window).

Small, generic drawing functions; the sections module decides what to draw.  Stages
that ship their own plotting functions for their CLIs are reused by the sections
module where they exist.
"""

from __future__ import annotations

from pathlib import Path
from typing import Mapping, Sequence

import numpy as np


def _plt():
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    return plt


def _save(fig, path: str | Path) -> Path:
    from fe_crank.pipeline import write_atomic
    import io

    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=110, bbox_inches="tight")
    _plt().close(fig)
    return write_atomic(path, buf.getvalue())


def plot_curves(path, x: np.ndarray, curves: Mapping[str, np.ndarray], *, xlabel: str, ylabel: str,
                title: str, xticks_deg: bool = True) -> Path:
    """Several curves over one abscissa (e.g. forces over the crank angle in degrees)."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(7.0, 3.6))
    for label, y in curves.items():
        ax.plot(x, y, label=label, lw=1.3)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.grid(True, alpha=0.35)
    ax.axhline(0.0, color="k", lw=0.6)
    if xticks_deg and len(x) and np.ptp(x) >= 360:
        ax.set_xticks(np.arange(0, float(np.max(x)) + 1, 90))
    if len(curves) > 1:
        ax.legend(fontsize=8, ncol=min(len(curves), 4))
    return _save(fig, path)


def plot_polar_diagram(path, fx: np.ndarray, fy: np.ndarray, *, title: str, unit: str = "kN",
                       scale: float = 1e-3, marks: Sequence[int] = ()) -> Path:
    """Polar load diagram: the locus of the force vector's tip in the throw frame
    (x tangential, y radial outward), with the origin and the mean vector marked."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(5.0, 5.0))
    ax.plot(fx * scale, fy * scale, lw=1.3)
    for i in marks:
        ax.plot(fx[i] * scale, fy[i] * scale, "o", ms=3, color="k")
        ax.annotate(str(i), (fx[i] * scale, fy[i] * scale), fontsize=7)
    ax.plot([0], [0], "k+", ms=10)
    ax.plot([0, np.mean(fx) * scale], [0, np.mean(fy) * scale], "r-", lw=1.0, label="mean")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(f"tangential [{unit}]")
    ax.set_ylabel(f"radial, outward [{unit}]")
    ax.set_title(title)
    ax.grid(True, alpha=0.35)
    ax.legend(fontsize=8)
    return _save(fig, path)


def plot_ellipses(path, curves: Mapping[str, tuple[np.ndarray, np.ndarray]], *, title: str, unit: str) -> Path:
    """Hodographs: the tip of a free force (or moment) vector over one turn."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(5.0, 5.0))
    for label, (x, y) in curves.items():
        ax.plot(x, y, label=label, lw=1.3)
    ax.plot([0], [0], "k+", ms=10)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(f"x [{unit}]")
    ax.set_ylabel(f"y [{unit}]")
    ax.set_title(title)
    ax.grid(True, alpha=0.35)
    if curves:
        ax.legend(fontsize=8)
    return _save(fig, path)


def plot_bars(path, labels: Sequence[str], series: Mapping[str, Sequence[float]], *, ylabel: str, title: str) -> Path:
    """Grouped bars (e.g. required vs built counterweight m*r per plane)."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(6.0, 3.4))
    n = max(len(series), 1)
    w = 0.8 / n
    x = np.arange(len(labels))
    for j, (name, vals) in enumerate(series.items()):
        ax.bar(x + (j - (n - 1) / 2) * w, vals, width=w, label=name)
    ax.set_xticks(x, labels)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.grid(True, axis="y", alpha=0.35)
    ax.legend(fontsize=8)
    return _save(fig, path)
