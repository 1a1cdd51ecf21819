"""The NetCDF store: peaks gathered in this process, written as one NetCDF archive at the end;
finished batches kept meanwhile in a work folder, so that a run can resume.

Workers return peak arrays and this process alone writes them (no races on shared files).
Finished batches are kept in the work folder as .npz files holding their context key and
members (members.MEMBER_DTYPE) with their peaks, so a killed sweep rerun with the same arguments
computes only the members it is missing. Every member is looked up by its context key and its
member record (pipeline.execute.keys): batch sizes and worker counts may change between runs.
"""
from __future__ import annotations

import os
import shutil
import tempfile
import zipfile
from pathlib import Path

import numpy as np

from engine.results import empty_peaks

from ..archive import build_dataset, write_netcdf
from ..errors import SweepError
from ..members import MEMBER_DTYPE
from ..writing import KEY_ATTRIBUTE, check_writable_folder
from . import batches
from .keys import batch_key, sweep_key


class WorkFolder:
    """Finished batches on disk: `<key>.npz` with the context, members and peaks.

    Each file is read once per process: what it holds is remembered with its size and
    modification time (READ), and what this process writes is remembered as it is written, so
    that the sweeps of one recipe sharing a work folder do not read it again and again."""

    READ: dict = {}
    """file -> ((size, mtime_ns), its entries): the batch files this process has read or
    written, shared by every WorkFolder of the process. A file this process wrote holds its
    (context, members, peaks) until it is loaded (a million members' entries, one dict each,
    cost seconds that a run which never resumes would spend for nothing)."""

    def __init__(self, path: Path):
        self.path = Path(path)  # created with the first batch: a refused run leaves nothing

    def load(self) -> dict[tuple[str, bytes], dict[str, np.ndarray]]:
        """(context, member record bytes) -> that member's peaks, from every readable batch."""
        found = {}
        for file in sorted(self.path.glob("*.npz")):
            try:
                stamp = _stamp(file)
                known = self.READ.get(file)
                if known is None or known[0] != stamp:
                    known = (stamp, _entries(file))
                    self.READ[file] = known
            except (OSError, ValueError, KeyError, EOFError, zipfile.BadZipFile):
                continue  # a damaged file (killed mid-write elsewhere) is simply recomputed
            entries = known[1]
            if isinstance(entries, tuple):  # written here, not yet loaded
                entries = _by_member(*entries)
                self.READ[file] = (known[0], entries)
            found.update(entries)
        return found

    USED: dict = {}
    """folder -> {context key (keys.context_key): the members (MEMBER_DTYPE)} of the sweeps
    this process completed with it: the work a finished run may delete (`finish`); any other
    batch is another configuration's (an interrupted run's too: it never completed)."""

    DONE: dict = {}
    """folder -> the batch files that sweeps this process completed wrote there: theirs, which
    `finish` removes without comparing their members (a million members' records gathered as
    a set to compare them took 1-2 s)."""

    def use(self, contexts, members_of, written=()) -> None:
        """Note that a sweep of this process completed these contexts with this folder, the
        members of context i being members_of(i), and wrote the batch files `written`."""
        self.DONE.setdefault(self.path, set()).update(written)
        used = self.USED.setdefault(self.path, {})
        for i, context in enumerate(contexts):
            runs = used.setdefault(context, [])
            runs.append(members_of(i))

    def finish(self) -> int:
        """Remove the batch files of the sweeps this process completed with this folder (USED:
        their contexts and members), and the folder with them when nothing else is left; a
        file of another configuration (a run interrupted, then run with other options) is
        kept, never deleted unasked. Returns the simulations kept, after a KeptWorkNotice
        saying where when there are any."""
        import warnings

        from ..errors import KeptWorkNotice

        ran = _Completed(self.USED.pop(self.path, {}))
        done = self.DONE.pop(self.path, set())
        kept = 0
        for file in sorted(self.path.glob("*.npz")):
            if file in done:
                file.unlink(missing_ok=True)
                self.READ.pop(file, None)
                continue
            try:
                context, members = _batch_of(file, self.READ.get(file))
            except (OSError, ValueError, KeyError, EOFError, zipfile.BadZipFile):
                context, members = None, None  # damaged: nothing anyone can resume from
            if members is not None and not ran(context, members):
                kept += len(members)
                continue
            file.unlink(missing_ok=True)
            self.READ.pop(file, None)
        if kept:
            warnings.warn(KeptWorkNotice(
                f"{self.path} keeps {kept} finished simulations of another configuration (an "
                f"earlier run with other options: running it again resumes from them); delete "
                f"the folder to drop them"), stacklevel=2)
        else:
            self.remove()
        return kept

    def remove(self) -> None:
        """The folder gone, and what this process remembers of its files with it."""
        shutil.rmtree(self.path, ignore_errors=True)
        self.DONE.pop(self.path, None)
        for file in [f for f in self.READ if f.parent == self.path]:
            del self.READ[file]

    def count(self) -> int:
        """Simulations kept (members of every readable batch file)."""
        kept = 0
        for file in self.path.glob("*.npz"):
            try:
                with np.load(file, allow_pickle=False) as data:
                    kept += len(data["members"])
            except (OSError, ValueError, KeyError, EOFError, zipfile.BadZipFile):
                continue
        return kept

    def save(self, key: str, context: str, members: np.ndarray,
             peaks: dict[str, np.ndarray]) -> Path:
        """Write atomically: a batch file is complete or absent. Returns the file."""
        self.path.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=self.path, prefix=f".{key}.", suffix=".tmp")
        try:
            with os.fdopen(fd, "wb") as f:
                np.savez(f, context=np.array(context), members=members, **peaks)
            file = self.path / f"{key}.npz"
            os.replace(tmp, file)
        except BaseException:
            Path(tmp).unlink(missing_ok=True)
            raise
        self.READ[file] = (_stamp(file), (context, members, peaks))
        return file


def _batch_of(file: Path, known) -> tuple[str, np.ndarray | None]:
    """(context key, members) of a batch file: from what this process wrote (WorkFolder.READ's
    entry), else read from the file (members None: another version's, which nothing runs)."""
    if known is not None and isinstance(known[1], tuple):  # written here: (context, members,
        return known[1][0], known[1][1]                    # peaks)
    with np.load(file, allow_pickle=False) as data:
        members = data["members"]
        return str(data["context"]), members if members.dtype == MEMBER_DTYPE else None


class _Completed:
    """Whether a batch file's members all ran in the sweeps this process completed under its
    context (`used`: context -> member arrays, WorkFolder.USED's entry): each context's
    members kept as a set of their records' bytes, built once when first asked, so that a
    million-member sweep's few hundred files are each checked in milliseconds (np.isin against
    every member, sorting a million records per file, took 1.3 s a file)."""

    def __init__(self, used: dict):
        self.used, self.seen = used, {}

    def __call__(self, context: str, members: np.ndarray) -> bool:
        runs = self.used.get(context, ())
        if any(len(run) == len(members) and np.array_equal(_rows(run), _rows(members))
               for run in runs):
            return True  # the same members: no set needed
        if context not in self.seen:
            self.seen[context] = set().union(*map(_records, runs))
        seen = self.seen[context]
        return bool(runs) and all(row in seen for row in _records(members))


def _rows(x: np.ndarray) -> np.ndarray:
    """A member array's records as opaque bytes (compared whole, NaN included)."""
    return np.ascontiguousarray(x).view(f"V{x.dtype.itemsize}").ravel()


def _records(x: np.ndarray) -> list[bytes]:
    """Each member's record as bytes."""
    return _rows(x).tolist()


def _stamp(file: Path) -> tuple[int, int]:
    """What tells a batch file changed: its size and modification time (ns)."""
    stat = file.stat()
    return stat.st_size, stat.st_mtime_ns


def _entries(file: Path) -> dict:
    """(context, member bytes) -> peaks of one batch file; {} for another version's."""
    with np.load(file, allow_pickle=False) as data:
        context, members = str(data["context"]), data["members"]
        peaks = {name: data[name] for name in data.files if name not in ("context", "members")}
    if members.dtype != MEMBER_DTYPE:
        return {}  # written by another version: its keys cannot match
    return _by_member(context, members, peaks)


def _by_member(context: str, members: np.ndarray, peaks: dict) -> dict:
    """(context, member bytes) -> that member's peaks, for the (b,) members of one batch."""
    return {(context, member.tobytes()): {name: np.asarray(value[i]).copy()
                                          for name, value in peaks.items()}
            for i, member in enumerate(members)}


def taken(members: np.ndarray, which: np.ndarray | slice) -> np.ndarray:
    """members[which]: a view when `which` is a slice or a run of consecutive indices (a fresh
    grid's batches), instead of a copy of records of 344 bytes each."""
    return members[as_slice(which)]


def as_slice(which: np.ndarray | slice) -> np.ndarray | slice:
    """`which` as a slice when it is a run of consecutive indices (a fresh grid's batches: an
    array indexed by it is a view, and assigned through it a block copy), else itself."""
    if isinstance(which, slice):
        return which
    if which.size and which[-1] - which[0] + 1 == which.size \
            and np.all(np.diff(which) == 1):
        return slice(int(which[0]), int(which[-1]) + 1)
    return which


def check_work_dir(work_dir) -> Path | None:
    """Refuse a work folder that cannot be written, before any compute (it is created with
    the first finished batch)."""
    if work_dir is None:
        return None
    work_dir = Path(work_dir)
    if work_dir.exists() and not work_dir.is_dir():
        raise SweepError(f"work_dir: {work_dir} is a file, not a folder")
    check_writable_folder(work_dir, "work_dir")
    return work_dir


class NetCDFStore:
    """A sweep's peaks in memory, its finished batches in a work folder (pipeline.execute's
    Store interface); `finish` labels them and writes the archive.

    grid: the members (pipeline.grid.Grid); run: what they run under (run.Run); out: the NetCDF
    path, or None (the Dataset is only returned); work_dir: the work folder (None: `<out>.work`
    when out is given, removed once out is written; an explicit one is kept, and may be shared
    by several sweeps; no out and no work_dir: nothing is kept). key: the sweep's resume key
    (keys.sweep_key), stored as the archive's configuration_key. derive: what the peaks mean,
    added to the archive (pipeline.archive.build_dataset's; None: peaks only).
    """

    def __init__(self, grid, run, out=None, work_dir=None, derive=None):
        self.grid, self.run, self.records, self.out = grid, run, run.records, out
        self.derive = derive
        self.own_work_dir = work_dir is None and out is not None
        if self.own_work_dir:
            work_dir = out.with_name(out.name + ".work")
        self.kept_in = check_work_dir(work_dir)
        self.work = WorkFolder(self.kept_in) if self.kept_in is not None else None
        self.contexts = run.contexts()
        self.key = sweep_key(grid.every_member, self.contexts)
        self.total = len(run.records) * grid.n_members
        self.copies: dict = {}  # see pending
        self.written: list[Path] = []  # the batch files this sweep kept
        self.results = [empty_peaks(grid.n_members, run.building.n_levels, run.moat,
                                    run.building.can_collapse, run.n_points)
                        for _ in run.records]

    def pending(self, sizes: list[int]) -> list[batches.Batch]:
        """Fill in the members the work folder holds; the rest in batches of sizes[r]. A
        member listed twice for one record (pipeline.listed) runs once: its copies take its
        peaks when its batch is accepted."""
        cached = self.work.load() if self.work is not None else {}
        todo = []
        self.copies = {}  # (record, member index run) -> the indices of its copies
        for r, context in enumerate(self.contexts):
            missing, first = [], {}
            members = self.grid.members_of(r)
            if not cached and self.grid.listed is None:  # a grid: members once each, none kept
                missing, members_left = np.arange(len(members)), ()
            else:
                members_left = members
            for i, member in enumerate(members_left):
                key = member.tobytes()
                peaks = cached.get((context, key))
                if peaks is not None:
                    for name, value in peaks.items():
                        self.results[r][name][i] = value
                elif key in first:
                    self.copies.setdefault((r, first[key]), []).append(i)
                else:
                    first[key] = i
                    missing.append(i)
            missing = np.asarray(missing, dtype=np.intp)
            for start in range(0, len(missing), sizes[r]):
                which = missing[start:start + sizes[r]]
                todo.append(batches.Batch(r, which, which.size,
                                          batch_key(context, taken(members, which))))
        return todo

    def part(self, batch: batches.Batch, start: int, stop: int) -> batches.Batch:
        """The batch's members start:stop as a batch of their own (kept on its own: the
        executor keeps a long batch's work a part at a time)."""
        which = batch.members[start:stop]
        return batches.Batch(batch.record, which, which.size,
                             batch_key(self.contexts[batch.record],
                                       taken(self.grid.members_of(batch.record), which)))

    def task(self, batch: batches.Batch) -> tuple:
        """The peaks of the batch: batches.simulate_batch."""
        run = self.run
        return batches.simulate_batch, (self.records[batch.record].dt,
                                        taken(self.grid.members_of(batch.record),
                                              batch.members),
                                        run.building, run.dt,
                                        *run.engine_keywords(batch.record).values())

    def accept(self, batch: batches.Batch, peaks: dict[str, np.ndarray]) -> None:
        """Keep the batch in the work folder, and its peaks here."""
        if self.work is not None:
            self.written.append(self.work.save(
                batch.key, self.contexts[batch.record],
                taken(self.grid.members_of(batch.record), batch.members), peaks))
        where = as_slice(batch.members)
        for name, value in peaks.items():
            self.results[batch.record][name][where] = value
        for k, i in enumerate(batch.members if self.copies else ()):
            for copy in self.copies.get((batch.record, int(i)), ()):
                for name, value in peaks.items():
                    self.results[batch.record][name][copy] = value[k]

    def finish(self):
        """The labelled Dataset, written to out when given (the own work folder then goes,
        but for another configuration's work: WorkFolder.finish)."""
        ds = build_dataset(self.grid, self.run, self.results, derive=self.derive)
        ds.attrs[KEY_ATTRIBUTE] = self.key
        if self.out is not None:
            write_netcdf(ds, self.out)
        if self.work is not None:  # this run's work, done: a finish may take it away
            self.work.use(self.contexts, self.grid.members_of, self.written)
        if self.own_work_dir:
            self.work.finish()
        return ds
