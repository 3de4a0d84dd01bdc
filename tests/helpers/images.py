"""Pixel statistics of the rendered pictures (the report tests read them to tell a
rendered field from a blank window)."""

from __future__ import annotations

from pathlib import Path

import numpy as np


def image_statistics(path: str | Path) -> dict[str, float]:
    """Pixel statistics of a PNG: share of pixels that differ from the corner
    (background) colour and the standard deviation of the grey level.  A blank
    render has ``coverage`` near 0 and ``std`` near 0."""
    import matplotlib.image as mpimg

    img = np.asarray(mpimg.imread(str(path)))[..., :3].astype(float)
    bg = img[0, 0]
    differs = np.any(np.abs(img - bg) > 0.02, axis=-1)
    return {
        "coverage": float(differs.mean()),
        "std": float(img.mean(axis=-1).std()),
        "colours": float(len(np.unique((img * 255).astype(np.uint8).reshape(-1, 3), axis=0))),
    }
