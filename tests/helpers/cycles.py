"""Stress paths of many nodes over a cycle, as the check builds them."""

from __future__ import annotations

import numpy as np


def cycle_paths(n=300, n_t=720, seed=3):
    """Non-proportional paths of 14 unit cases with cycle coefficients (as the check builds)."""
    rng = np.random.default_rng(seed)
    th = np.linspace(0.0, 4 * np.pi, n_t, endpoint=False)
    coeff = np.column_stack(
        [np.full(n_t, 1e4)]
        + [np.maximum(0.0, np.cos(th * k / 2 + k)) * 1e4 for k in range(12)]
        + [1e3 * np.sin(3 * th)]
    )
    unit = rng.normal(size=(14, 6, n)) * 1e3
    hist = np.tensordot(coeff, unit, axes=(1, 0))
    # a third of the nodes proportional: S(t) = S_0 + sin(t) A
    k = n // 3
    hist[:, :, :k] = hist[:1, :, :k] + np.sin(th)[:, None, None] * unit[0, :, :k] * 1e4
    return hist
