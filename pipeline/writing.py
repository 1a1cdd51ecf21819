"""Writing results without ever losing one.

- `check_out`: an output path is checked before any compute, and nothing is created for it
  then (a refused run leaves no empty folder behind);
- `guard`: an existing archive is replaced only by a run of the same configuration (the same
  `configuration_key` attribute: the same inputs on the same engine, so the same numbers) or
  when the caller says force;
- `Staged`: a run's outputs (an archive and its figures) are written to hidden temporary files
  beside their targets, then renamed over them together with Ctrl-C held back, so that they
  are replaced all or none; a failure or an interrupt before that leaves the old ones intact.
"""
from __future__ import annotations

import glob
import hashlib
import json
import os
import shutil
import signal
import tempfile
import threading
from contextlib import contextmanager
from pathlib import Path

from .errors import SweepError

KEY_ATTRIBUTE = "configuration_key"
"""The archive attribute naming the configuration that wrote it."""


def configuration_key(*parts) -> str:
    """A configuration's key: the SHA-256 of its parts as JSON (str() for anything JSON lacks,
    e.g. an engine.Building, whose repr lists every field)."""
    text = json.dumps(parts, sort_keys=True, default=repr)
    return hashlib.sha256(text.encode()).hexdigest()


def check_out(out) -> Path | None:
    """Refuse an output path that cannot be written, before any compute; create nothing."""
    if out is None:
        return None
    out = Path(out)
    if out.is_dir() and out.suffix != ".zarr":  # a Zarr store is a folder
        raise SweepError(f"out: {out} is a directory, not a file name")
    check_writable_folder(out.parent, "out")
    return out


def check_writable_folder(folder: Path, option: str) -> None:
    """The folder, or its nearest existing ancestor (created at write time), is a writable
    directory; SweepError naming `option` otherwise."""
    folder = Path(folder).absolute()
    existing = next(p for p in (folder, *folder.parents) if p.exists())
    if not existing.is_dir():
        raise SweepError(f"{option}: cannot write to {folder}: {existing} is not a folder")
    if not os.access(existing, os.W_OK | os.X_OK):
        raise SweepError(f"{option}: cannot write to {folder}: permission denied on "
                         f"{existing}")
    # The permission bits do not say everything (a read-only file system, /sys or /proc, a
    # full disk under root): a file actually created and removed does.
    try:
        fd, probe = tempfile.mkstemp(dir=existing, prefix=".bumpers-probe.")
        os.close(fd)
        os.unlink(probe)
    except OSError as err:
        raise SweepError(f"{option}: cannot write to {folder}: {err.strerror or err}") \
            from None


def guard(path, key: str, force: bool = False, python: bool = False) -> None:
    """Refuse to replace the archive at `path` unless it holds configuration `key` (the same
    run: nothing is lost) or force is set. SweepError says what is there and how to go on:
    with the command line's options (--force, --out), and where `python` (a function's
    caller) with its arguments (force=True, out) as well."""
    path = Path(path)
    if force or not path.exists():
        return
    found = archive_key(path)
    if found == key:
        return
    what = ("an archive of another configuration" if found else
            "a file this version cannot identify (no configuration_key)")
    told = f"{path} exists and holds {what}: it is kept. Give {{}} to replace it, or another {{}}"
    command_line = told.format("--force", "--out")
    raise SweepError(told.format("force=True", "out") if python else command_line, command_line)


def archive_key(path: Path) -> str | None:
    """The configuration_key attribute of a NetCDF archive or Zarr store (None: none, or not
    readable as one)."""
    try:
        if path.suffix == ".zarr":
            import zarr

            return zarr.open_group(str(path), mode="r").attrs.get(KEY_ATTRIBUTE)
        import netCDF4

        with netCDF4.Dataset(path) as nc:
            return getattr(nc, KEY_ATTRIBUTE, None)
    except Exception:  # noqa: BLE001 - anything unreadable is "cannot identify"
        return None


class Staged:
    """Outputs written to temporary files first, then renamed over their targets together.

        with Staged() as stage:
            ds.to_netcdf(stage.path(archive)); fig.savefig(stage.path(png))
            stage.commit()        # all renamed, Ctrl-C held back meanwhile
    Leaving the block without commit (an error, Ctrl-C) removes the temporary files and
    leaves every target as it was.
    """

    def __init__(self):
        self.pending: list[tuple[Path, Path]] = []  # (temporary, target)

    def __enter__(self) -> Staged:
        return self

    def path(self, target) -> Path:
        """A fresh hidden temporary file beside `target` (its folder created if need be)."""
        target = Path(target)
        target.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}.", suffix=".tmp")
        os.close(fd)
        self.pending.append((Path(tmp), target))
        return Path(tmp)

    def folder(self, target) -> Path:
        """A fresh hidden temporary folder beside `target`, for an output that is a folder (a
        Zarr store); committed like a file, the folder it replaces removed after."""
        target = Path(target)
        target.parent.mkdir(parents=True, exist_ok=True)
        tmp = Path(tempfile.mkdtemp(dir=target.parent, prefix=f".{target.name}.",
                                    suffix=".tmp"))
        os.chmod(tmp, 0o777 & ~_umask())  # mkdtemp made it private; an output is not
        self.pending.append((tmp, target))
        return tmp

    def commit(self) -> None:
        """Make every temporary file durable, then rename each over its target."""
        for tmp, _ in self.pending:
            if tmp.is_dir():
                continue
            with open(tmp, "rb") as f:
                os.fsync(f.fileno())  # the bytes are on disk before the names point at them
            os.chmod(tmp, 0o666 & ~_umask())  # mkstemp made it private; an output is not
        replaced = []
        with sigint_held():
            for tmp, target in self.pending:
                if tmp.is_dir() and target.is_dir():  # a folder cannot be renamed over one
                    old = Path(tempfile.mkdtemp(dir=target.parent,
                                                prefix=f".{target.name}.", suffix=".tmp"))
                    os.replace(target, old / target.name)
                    replaced.append(old)
                os.replace(tmp, target)
        for old in replaced:
            shutil.rmtree(old, ignore_errors=True)
        for _, target in self.pending:
            for stale in target.parent.glob(f".{glob.escape(target.name)}.*.tmp"):
                _remove(stale)  # left by writers killed before their rename
        self.pending = []

    def __exit__(self, *exc) -> None:
        for tmp, _ in self.pending:
            _remove(tmp)
        self.pending = []


def _remove(path: Path) -> None:
    """A temporary file or folder, gone."""
    if path.is_dir():
        shutil.rmtree(path, ignore_errors=True)
    else:
        path.unlink(missing_ok=True)


@contextmanager
def sigint_held():
    """Ctrl-C (SIGINT) waits until the block ends, then takes effect (main thread only; a
    kill -9 cannot be held, but then the renames done so far are whole files each). The
    signal's handler is swapped for the block, not the thread's signal mask: the compiled
    kernel's worker threads leave SIGINT unblocked, the operating system may deliver it to one
    of them, and Python would run its handler in the main thread inside the block all the
    same. Off the main thread (no handler can be set there) the block runs as it is."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    caught = []
    previous = signal.signal(signal.SIGINT, lambda signum, frame: caught.append(signum))
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)
    if caught and callable(previous):  # default_int_handler raises KeyboardInterrupt
        previous(signal.SIGINT, None)
    elif caught and previous == signal.SIG_DFL:
        raise KeyboardInterrupt


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask
