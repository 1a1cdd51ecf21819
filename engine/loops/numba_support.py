"""What the compiled loop needs of numba beyond @njit: a disk cache keyed on the physics it
compiles, and small arrays on the stack. Nothing here is physics."""
from __future__ import annotations

import hashlib
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
