"""Independent blocks of the assessment on a pool of threads.

The per-node criteria of a group (``group.assess_group``) are computed block by block
(``fatigue.NODE_BLOCK`` nodes at a time); a block reads only the unit stresses of its
own nodes and writes only its own slice of the group's per-node arrays, so the blocks
are independent.  numpy releases the global interpreter lock inside its array kernels
(ufunc loops, reductions, the BLAS matrix products of the superposition, integer
indexing of float arrays), so the blocks of one process can run on several cores as
threads, sharing the unit stresses instead of copying them to other processes.

Each block runs exactly the operations of the serial loop on exactly the same operands
and writes a slice no other block writes: the results are bit for bit those of one
thread, whatever the number of threads and the order in which the blocks finish.  Each
thread keeps its own scratch buffers (``scratch``), so the memory grows by one block's
buffers per extra thread (a few MB).
"""

from __future__ import annotations

import threading
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from typing import TYPE_CHECKING, TypeVar

if TYPE_CHECKING:
    import numpy as np

T = TypeVar("T")

#: threads of the assessment's blocks in the current context (``threads``)
_THREADS: ContextVar[int] = ContextVar("fe_crank_assess_threads", default=1)


@contextmanager
def threads(count: int) -> Iterator[None]:
    """Within the block, ``run_blocks`` (and so every group's node blocks and the unit-stress
    recovery) uses ``count`` threads: the check sets it once for a case, from the cores
    the case may use."""
    token = _THREADS.set(max(1, int(count)))
    try:
        yield
    finally:
        _THREADS.reset(token)


#: a thread's reusable buffers by name (``scratch_array``), kept from one block to the next
Scratch = dict[str, "np.ndarray"]


def thread_count() -> int:
    """The threads ``run_blocks`` uses in the current context (1 unless ``threads`` set it)."""
    return _THREADS.get()


def run_blocks(fn: Callable[[T, Scratch], None], items: Iterable[T], threads: int | None = None) -> None:
    """Call ``fn(item, scratch)`` for every item, on ``threads`` threads (default: the
    context's, ``thread_count``; 1: in this thread, in order).  ``scratch`` is a dict
    private to the calling thread, kept from one item to the next (reusable buffers).  An
    exception of any item is raised here, after the items already started have finished."""
    threads = thread_count() if threads is None else threads
    items = list(items)
    if threads <= 1 or len(items) <= 1:
        scratch: Scratch = {}
        for it in items:
            fn(it, scratch)
        return
    from concurrent.futures import ThreadPoolExecutor

    local = threading.local()

    def call(it: T) -> None:
        s = getattr(local, "scratch", None)
        if s is None:
            s = local.scratch = {}
        fn(it, s)

    with ThreadPoolExecutor(max_workers=min(int(threads), len(items)), thread_name_prefix="fe-crank-assess") as ex:
        for _ in ex.map(call, items):
            pass


def scratch_array(
    scratch: Scratch, name: str, shape: tuple[int, ...], factory: Callable[[tuple[int, ...]], np.ndarray] | None = None
) -> np.ndarray:
    """A buffer of ``shape`` from ``scratch`` (made, or remade when the shape changed)."""
    import numpy as np

    buf = scratch.get(name)
    if buf is None or buf.shape != tuple(shape):
        buf = scratch[name] = (factory or np.empty)(shape)
    return buf
