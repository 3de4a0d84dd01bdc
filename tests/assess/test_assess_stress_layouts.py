"""Principal stresses in both stacked layouts against Mohr's circle (one implementation)."""

import numpy as np

from fe_crank.assess.stress import principal as principal_stacked
from fe_crank.fe.core.stress import principal


def test_principal_stresses_mohr_circle_in_both_layouts():
    # plane stress sx = 50, sy = -10, txy = 40 (MPa) plus sz = 5: Mohr's circle centre
    # (50 - 10)/2 = 20, radius sqrt(30^2 + 40^2) = 50 -> 70 and -30; sz = 5 is principal.
    # Descending: (70, 5, -30).  Components (xx, yy, zz, xy, yz, xz).
    one = np.array([50.0, -10.0, 5.0, 40.0, 0.0, 0.0])
    expected = [70.0, 5.0, -30.0]
    np.testing.assert_allclose(principal(one[:, None])[:, 0], expected, atol=1e-12)
    # assessment layout (..., 6, n): 2 angles x 3 nodes of the same state
    stacked = np.broadcast_to(one[None, :, None], (2, 6, 3)).copy()
    out = principal_stacked(stacked)
    assert out.shape == (2, 3, 3)
    np.testing.assert_allclose(out, np.broadcast_to(np.array(expected)[None, :, None], (2, 3, 3)), atol=1e-12)
