"""What the compiled loops need of numba beyond @njit: a disk cache keyed on the physics they
compile, small arrays on the stack, and members run on threads. Nothing here is physics."""
from __future__ import annotations

import hashlib
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from numba.core import cgutils, types
from numba.extending import intrinsic


def install_cache_locator(kernel_file: Path, physics_files: list[str]) -> None:
    """Make numba's on-disk cache of the kernels defined in `kernel_file` stale when that file
    or any of `physics_files` (the modules whose functions it compiles) changes; numba alone
    would watch the kernel's file only. Private numba API: without it caching still works,
    keyed on that file alone."""
    try:
        from numba.core.caching import CacheImpl, InTreeCacheLocator
    except ImportError:  # pragma: no cover - other numba versions
        return
    kernel = Path(kernel_file).resolve()
    # This file too: stack_doubles is compiled into the kernels.
    sources = [kernel, Path(__file__).resolve(), *(Path(f).resolve() for f in physics_files)]

    class _PhysicsCacheLocator(InTreeCacheLocator):
        @classmethod
        def from_function(cls, py_func, py_file):
            if Path(py_file).resolve() != kernel:
                return None
            return super().from_function(py_func, py_file)

        def get_source_stamp(self):
            digest = hashlib.sha256()
            for path in sources:
                digest.update(path.read_bytes())
            return digest.hexdigest()

    if not any(c.__name__ == "_PhysicsCacheLocator" for c in CacheImpl._locator_classes):
        CacheImpl._locator_classes.insert(0, _PhysicsCacheLocator)


@intrinsic
def stack_doubles(typingctx, levels):
    """A pointer to len(levels) float64 on the stack of the calling function. `levels` is a
    tuple with one element per level: its length is part of its type, so the size is known
    when the kernel compiles (once per number of levels) and LLVM keeps the values in
    registers."""
    if not isinstance(levels, types.UniTuple):
        return None
    count = levels.count

    def codegen(context, builder, signature, args):
        return cgutils.alloca_once(builder, context.get_value_type(types.float64),
                                   size=context.get_constant(types.intp, count))
    return types.CPointer(types.float64)(levels), codegen


def run_members(size: int, n_steps: int, progress, steps) -> None:
    """Run a batch of `size` members through `n_steps` steps: steps(members, s0, s1) advances
    the members (an index array) over steps s0 <= step < s1, in a compiled kernel that
    releases the GIL. The members go, a few at a time, to whichever of numba's threads is
    free (members that pound cost more than those that do not); a member's result depends on
    neither. With progress(step, n_steps), in chunks of about 1% of the steps.

    Threads of this process rather than numba's parallel loops: the same speed, and a kernel
    compiled without parallel=True takes a third of the time to compile."""
    import numba
    import numpy as np

    threads = min(numba.get_num_threads(), size)
    everyone = np.arange(size)
    batches = np.array_split(everyone, min(size, 8 * threads))
    pool = ThreadPoolExecutor(max_workers=threads) if threads > 1 else None

    def advance(s0, s1):
        if pool is None:
            steps(everyone, s0, s1)
        else:
            list(pool.map(lambda members: steps(members, s0, s1), batches))

    try:
        if progress is None:
            advance(0, n_steps)
        else:
            chunk = max(n_steps // 100, 1)
            for start in range(0, n_steps, chunk):
                progress(start, n_steps)
                advance(start, min(start + chunk, n_steps))
            progress(n_steps, n_steps)
    finally:
        if pool is not None:
            pool.shutdown()
