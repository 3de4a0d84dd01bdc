"""A round bar meshed as a 'throw' (quadratic tetrahedra, named journals, crankpin, fillets, a counterweight and a web), radius R, length L."""

from __future__ import annotations

import numpy as np
from skfem import MeshTet, MeshTet2

R, L = 0.02, 0.12


def bar_throw():
    m = MeshTet.init_tensor(np.linspace(-1, 1, 5), np.linspace(-1, 1, 5), np.linspace(0, 1, 13))
    x, y, z = m.p
    p = np.array([R * x * np.sqrt(1 - y**2 / 2), R * y * np.sqrt(1 - x**2 / 2), L * z])
    m2 = MeshTet2.from_mesh(MeshTet(p, m.t))
    e = 1e-9
    side = lambda x: (x[2] > e) & (x[2] < L - e)
    m2 = m2.with_boundaries(
        {
            "end_1": lambda x: np.abs(x[2]) < e,
            "end_2": lambda x: np.abs(x[2] - L) < e,
            "journal_1": lambda x: side(x) & (x[2] < L / 3),
            "journal_2": lambda x: side(x) & (x[2] > 2 * L / 3),
            "crankpin": lambda x: side(x) & (x[2] > L / 3) & (x[2] < 2 * L / 3),
            "crankpin_fillet_1": lambda x: side(x) & (np.abs(x[2] - L / 3) < L / 12),
            "journal_fillet_2": lambda x: side(x) & (np.abs(x[2] - 2 * L / 3) < L / 12),
        }
    )
    return m2.with_subdomains(
        {"counterweight_1": lambda x: x[2] < L / 6, "web_1": lambda x: (x[2] > L / 6) & (x[2] < L / 3)}
    )
