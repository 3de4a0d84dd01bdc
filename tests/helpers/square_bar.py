"""A square bar of 20 mm side as a determinate 'throw' (named ends, journals and crankpin) on a mapped quadratic tetrahedral mesh."""

from __future__ import annotations

import numpy as np

from helpers.verification_meshes import _mapped_tensor_mesh

H, Z1, Z2, LJ = 0.01, -0.05, 0.05, 0.02


def square_bar():
    tol = 1e-12

    def lateral(x):
        return (np.abs(np.abs(x[0]) - H) < tol) | (np.abs(np.abs(x[1]) - H) < tol)

    return _mapped_tensor_mesh(
        np.linspace(-H, H, 3),
        np.linspace(-H, H, 3),
        np.array([Z1, Z1 + LJ, -0.01, 0.01, Z2 - LJ, Z2]),
        lambda p: p,
        {
            "end_1": lambda x: np.abs(x[2] - Z1) < tol,
            "end_2": lambda x: np.abs(x[2] - Z2) < tol,
            "journal_1": lambda x: lateral(x) & (x[2] < Z1 + LJ),
            "journal_2": lambda x: lateral(x) & (x[2] > Z2 - LJ),
            "crankpin": lambda x: lateral(x) & (np.abs(x[2]) < Z2 - LJ),
        },
    )
