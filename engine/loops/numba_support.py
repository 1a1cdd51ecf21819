"""What the compiled loops need of numba beyond @njit: a disk cache keyed on the physics they
compile, small arrays on the stack (and views of a shape known when they compile), x and y in
one register (lane-wise arithmetic on pairs), and members run on threads. Nothing here is
physics."""
from __future__ import annotations

import hashlib
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
from llvmlite import ir
from numba.core import cgutils, types
from numba.extending import intrinsic

KERNEL_SOURCES: dict[Path, list[Path]] = {}
"""Kernel file -> the sources its cached kernels are stale without (install_cache_locator)."""


def install_cache_locator(kernel_file: Path, physics_files: list[str]) -> None:
    """Make numba's on-disk cache of the kernels defined in `kernel_file` stale when that file
    or any of `physics_files` (the modules whose functions it compiles) changes; numba alone
    would watch the kernel's file only. One locator serves every kernel file registered here
    (each with its own sources: a kernel file registered second must not fall back to numba's
    own locator, whose cache would outlive a change of the physics). Private numba API:
    without it caching still works, keyed on that file alone."""
    try:
        from numba.core.caching import CacheImpl, InTreeCacheLocator
    except ImportError:  # pragma: no cover - other numba versions
        return
    kernel = Path(kernel_file).resolve()
    # This file too: stack_doubles is compiled into the kernels.
    KERNEL_SOURCES[kernel] = [kernel, Path(__file__).resolve(),
                              *(Path(f).resolve() for f in physics_files)]

    class _PhysicsCacheLocator(InTreeCacheLocator):
        @classmethod
        def from_function(cls, py_func, py_file):
            if Path(py_file).resolve() not in KERNEL_SOURCES:
                return None
            return super().from_function(py_func, py_file)

        def get_source_stamp(self):
            digest = hashlib.sha256()
            for path in KERNEL_SOURCES[Path(self._py_file).resolve()]:
                digest.update(path.read_bytes())
            return digest.hexdigest()

    if not any(c.__name__ == "_PhysicsCacheLocator" for c in CacheImpl._locator_classes):
        CacheImpl._locator_classes.insert(0, _PhysicsCacheLocator)


def kernel_arrays(model: tuple) -> tuple:
    """`model` with each read-only array copied (C-contiguous; a one-building batch's
    broadcast views at B = 1, a read-only record): numba types a read-only array apart and
    would compile (and cache) every kernel variant a second time for it. The others, C-
    contiguous already, are passed as they are."""
    return tuple(x.copy() if isinstance(x, np.ndarray) and not x.flags.writeable else x
                 for x in model)


def history_rows(history, size: int):
    """Where a kernel writes each member's histories: (hist_row (size,) int64, the row of each
    member or -1, every, rows: how many, inverse: the asked members' rows, None without
    histories), for an engine.History whose members may repeat or count from the end."""
    hist_row = np.full(size, -1, dtype=np.int64)
    if history is None:
        return hist_row, 1, 0, None
    unique, inverse = np.unique(np.asarray(history.members, dtype=np.int64) % size,
                                return_inverse=True)
    hist_row[unique] = np.arange(unique.size)
    return hist_row, int(history.every), unique.size, inverse


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


@intrinsic
def data_pointer(typingctx, arr):
    """The address of a float64 array's first element: carray(data_pointer(a), shape) views a
    contiguous `a` with a shape known when the kernel compiles, so that its elements sit at
    constant offsets (an array's own shape is a run-time value, its strides held in
    registers or reloaded from the stack)."""
    if not isinstance(arr, types.Array) or arr.dtype != types.float64 or arr.layout != "C":
        return None

    def codegen(context, builder, signature, args):
        return context.make_array(signature.args[0])(context, builder, args[0]).data
    return types.CPointer(types.float64)(arr), codegen


# Pairs: (x, y) as a tuple of two float64, the plan kernel's two directions. The operations
# below act on both lanes in one instruction of the processor's vector unit: the same IEEE
# operation per lane as the scalar expression, so the same bits, at half the instructions.
# (numba switches LLVM's SLP vectoriser off, which would otherwise pair such code itself.)
_PAIR = types.UniTuple(types.float64, 2)
_LANES = (ir.Constant(ir.IntType(32), 0), ir.Constant(ir.IntType(32), 1))
_VECTOR = ir.VectorType(ir.DoubleType(), 2)


def _vector(builder, pair):
    """The <2 x double> of a pair (LLVM folds the round trips between vectors and lanes)."""
    vec = ir.Constant(_VECTOR, ir.Undefined)
    for k, lane in enumerate(_LANES):
        vec = builder.insert_element(vec, builder.extract_value(pair, k), lane)
    return vec


def _lanes(builder, vec):
    return [builder.extract_element(vec, lane) for lane in _LANES]


def _lanewise(name, operation, doc):
    def typer(typingctx, p, q):
        if p != _PAIR or q != _PAIR:
            return None

        def codegen(context, builder, signature, args):
            out = operation(builder, *(_vector(builder, pair) for pair in args))
            return context.make_tuple(builder, _PAIR, _lanes(builder, out))
        return _PAIR(_PAIR, _PAIR), codegen
    typer.__name__ = typer.__qualname__ = name
    typer.__doc__ = doc
    return intrinsic(typer)


add2 = _lanewise("add2", lambda b, p, q: b.fadd(p, q), "(p[0] + q[0], p[1] + q[1]).")
sub2 = _lanewise("sub2", lambda b, p, q: b.fsub(p, q), "(p[0] - q[0], p[1] - q[1]).")
mul2 = _lanewise("mul2", lambda b, p, q: b.fmul(p, q), "(p[0] * q[0], p[1] * q[1]).")
div2 = _lanewise("div2", lambda b, p, q: b.fdiv(p, q), "(p[0] / q[0], p[1] / q[1]).")
max2 = _lanewise("max2", lambda b, p, q: b.select(b.fcmp_ordered(">", q, p), q, p),
                 "(max(p[0], q[0]), max(p[1], q[1])), as numba's max(acc, value) decides: the "
                 "value where it is greater, else the accumulator (a NaN value is passed over).")


@intrinsic
def load_pair(typingctx, arr, i):
    """Row i of a C-contiguous (n, 2) float64 array as a pair, in one load (no bounds check)."""
    if not (isinstance(arr, types.Array) and arr.dtype == types.float64 and arr.ndim == 2
            and arr.layout == "C" and isinstance(i, types.Integer)):
        return None

    def codegen(context, builder, signature, args):
        return context.make_tuple(builder, _PAIR, _lanes(builder, builder.load(
            _row_address(context, builder, signature.args[0], *args), align=_ALIGN)))
    return _PAIR(arr, i), codegen


@intrinsic
def store_pair(typingctx, arr, i, pair):
    """Row i of a C-contiguous (n, 2) float64 array set to a pair, in one store."""
    if not (isinstance(arr, types.Array) and arr.dtype == types.float64 and arr.ndim == 2
            and arr.layout == "C" and isinstance(i, types.Integer) and pair == _PAIR):
        return None

    def codegen(context, builder, signature, args):
        builder.store(_vector(builder, args[2]),
                      _row_address(context, builder, signature.args[0], args[0], args[1]),
                      align=_ALIGN)
        return context.get_dummy_value()
    return types.none(arr, i, pair), codegen


# A row is only known to sit on a float64's alignment (8 bytes), not a vector's (16): say so,
# so that LLVM emits loads and stores that need no more (as fast as aligned ones today).
_ALIGN = 8


def _row_address(context, builder, array_type, arr, i):
    """The address of row i of a C-contiguous (n, 2) array, as a <2 x double> pointer."""
    data = context.make_array(array_type)(context, builder, arr).data
    first = builder.gep(data, [builder.mul(i, ir.Constant(i.type, 2))])
    return builder.bitcast(first, _VECTOR.as_pointer())


MIN_CHUNK_MEMBER_STEPS = 2_000_000
"""The least work of one chunk of a run reporting progress (member-steps: about 0.1 s of the
kernel), so that a small batch (a sweep's record with a few members) is not cut into a hundred
chunks whose hand-over to the threads would cost more than their steps."""


def run_members(size: int, n_steps: int, progress, steps) -> None:
    """Run a batch of `size` members through `n_steps` steps: steps(members, s0, s1) advances
    the members (an index array) over steps s0 <= step < s1, in a compiled kernel that
    releases the GIL. The members go, a few at a time, to whichever of numba's threads is
    free (members that pound cost more than those that do not); a member's result depends on
    neither. With progress(step, n_steps), in chunks of about 1% of the steps, or of
    MIN_CHUNK_MEMBER_STEPS member-steps where that is more (the chunks change no bit).

    Threads of this process rather than numba's parallel loops: the same speed, and a kernel
    compiled without parallel=True takes a third of the time to compile."""
    import numba
    import numpy as np

    threads = min(numba.get_num_threads(), size)
    everyone = np.arange(size)
    batches = np.array_split(everyone, min(size, 8 * threads))
    pool = _pool(threads) if threads > 1 else None
    for s0, s1 in chunk_bounds(size, n_steps, progress):
        if pool is None:
            steps(everyone, s0, s1)
        else:
            list(pool.map(lambda members, s0=s0, s1=s1: steps(members, s0, s1), batches))


_POOLS: dict = {}
"""threads -> the ThreadPoolExecutor run_members hands members to, kept for the process's
next batches (starting the threads anew cost a sweep of a million members 0.9 s in 246
batches). Its threads are idle between batches; concurrent batches (a caller's own threads)
share it, each waiting for its own members only."""


def _pool(threads: int) -> ThreadPoolExecutor:
    if threads not in _POOLS:
        _POOLS[threads] = ThreadPoolExecutor(max_workers=threads,
                                             thread_name_prefix="bumpers-members")
    return _POOLS[threads]


def chunk_bounds(size: int, n_steps: int, progress):
    """The (s0, s1) step ranges a run of `size` members goes in: all steps at once without
    progress; with progress(step, n_steps), chunks of about 1% of the steps, or of
    MIN_CHUNK_MEMBER_STEPS member-steps where that is more, progress called before each and
    once at the end (a loop keeps its state between chunks: they change no bit)."""
    if progress is None:
        yield 0, n_steps
        return
    chunk = max(n_steps // 100, -(-MIN_CHUNK_MEMBER_STEPS // size), 1)
    for start in range(0, n_steps, chunk):
        progress(start, n_steps)
        yield start, min(start + chunk, n_steps)
    progress(n_steps, n_steps)


def law_tag(code: int) -> tuple:
    """A law's code as a kernel's argument whose type holds it: (code + 1) zeros, so that the
    code is a compile-time constant of the kernel (len(tag) - 1) and the law's physics alone
    is compiled into it."""
    return (0,) * (int(code) + 1)


def law_groups(*codes):
    """The combinations of law codes a batch meets, for one kernel call each: (tags, group),
    tags[i] the i-th combination's codes as law_tag makes them, one a law; group (B,) int each
    member's combination. codes: each a (B,) int array of the batch (the story law's, the
    isolator law's). Found once a run; by_law splits the members of a call by it."""
    keys = np.stack([np.asarray(c, dtype=np.int64) for c in codes], axis=1)
    if np.all(keys == keys[0]):  # one combination (most batches): no sort
        return [tuple(law_tag(k) for k in keys[0])], np.zeros(len(keys), dtype=np.intp)
    unique, group = np.unique(keys, axis=0, return_inverse=True)
    return [tuple(law_tag(k) for k in key) for key in unique], group.reshape(-1)


def by_law(members, groups):
    """(tags, those members) for each law combination (law_groups' `groups`) among `members`
    (an index array). The groups run in turn; a member's result does not depend on the
    others'. One combination (most batches): the members as they are, at no cost a call."""
    tags, group = groups
    if len(tags) == 1:
        yield tags[0], members
        return
    chosen = group[members]
    for i in np.unique(chosen):
        yield tags[i], members[chosen == i]
