"""skfem asm(linear_elasticity) vs fe_crank.fe.assembly.assemble_stiffness on one small curved P2 mesh, in one run.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/assembly_ratio.py

Prints the best of 3 times of each and their ratio (the figure quoted in fe/assembly.py).
"""

import time

from skfem import Basis, ElementTetP2, ElementVector, MeshTet2, asm
from skfem.models.elasticity import lame_parameters, linear_elasticity

from fe_crank.fe.assembly import assemble_stiffness

m = MeshTet2.init_ball(nrefs=2)
b = Basis(m, ElementTetP2(), intorder=2)
vb = Basis(m, ElementVector(ElementTetP2()), intorder=2)
print("elements", m.t.shape[1], "dofs", vb.N)
ts, tp = [], []
for _ in range(3):
    t0 = time.perf_counter()
    Kr = asm(linear_elasticity(*lame_parameters(210e9, 0.3)), vb)
    ts.append(time.perf_counter() - t0)
    t0 = time.perf_counter()
    K = assemble_stiffness(b, 210e9, 0.3)
    tp.append(time.perf_counter() - t0)
print(
    f"skfem asm min {min(ts):.3f} s, project min {min(tp):.3f} s, ratio {min(ts) / min(tp):.1f}",
    abs(K - Kr).max() / abs(Kr).max(),
)
