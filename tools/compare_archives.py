"""Compare two folders of archives bit for bit: the check that a change of structure changed no
number.

    git worktree add ../before HEAD      # the code before the change
    (cd ../before && python -m studies.gap_size --out /tmp/before)   # every recipe, both sides
    python -m studies.gap_size --out /tmp/after
    python tools/compare_archives.py /tmp/before /tmp/after [NAME ...]
    python tools/compare_archives.py /tmp/before /tmp/after --renamed OLD=NEW ... \
        --renamed-text OLD=NEW ...

For every archive NAME.nc (or NAME.zarr) of BEFORE (or those named): every variable and
coordinate of BEFORE must be in AFTER with the same dims, dtype, attributes and bytes;
variables and global attributes AFTER adds are listed, global attributes that differ are
shown (those that say when and from which commit a run was made are not compared). Exit
status 1 when anything of BEFORE differs or is missing. --renamed OLD=NEW compares BEFORE's
name OLD (a variable, a dimension or a global attribute) with AFTER's NEW, --renamed-text
OLD=NEW a quoted key inside a text attribute (the sweep's arguments as JSON): a change that
renames a label and must change no number says so, and the rest is compared bit for bit.
"""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np
import xarray as xr

VOLATILE = frozenset({"date_created", "git_commit", "engine_fingerprint", "configuration_key"})
"""Global attributes that say when and from what a run was made, not what it computed."""


def open_archive(path: Path, renamed: dict[str, str] | None = None,
                 renamed_text: dict[str, str] | None = None) -> xr.Dataset:
    """The archive at path, loaded; renamed: OLD -> NEW names given to its variables,
    dimensions and global attributes, renamed_text: to the quoted keys inside its text
    attributes (BEFORE's, to be compared under AFTER's names)."""
    opener = xr.open_zarr if path.suffix == ".zarr" else xr.open_dataset
    with opener(path, decode_times=False) as ds:
        ds = ds.load()
    renamed, renamed_text = renamed or {}, renamed_text or {}
    ds = ds.rename({old: new for old, new in renamed.items()
                    if old in ds.variables or old in ds.dims})
    ds.attrs = {renamed.get(key, key): _renamed_text(value, renamed_text)
                for key, value in ds.attrs.items()}
    return ds


def _renamed_text(value, renamed: dict[str, str]):
    """A text attribute holding JSON (the sweep's arguments) with its keys OLD renamed NEW and
    written again with sorted keys, so that a renamed key compares wherever it sorts; any
    other value as it is. Applied to both sides when a text rename is asked for."""
    if not renamed or not isinstance(value, str):
        return value
    try:
        data = json.loads(value)
    except ValueError:
        return value

    def rename(item):
        if isinstance(item, dict):
            return {renamed.get(k, k): rename(v) for k, v in item.items()}
        return [rename(v) for v in item] if isinstance(item, list) else item

    return json.dumps(rename(data), sort_keys=True)


def differences(before: xr.Dataset, after: xr.Dataset) -> tuple[list[str], list[str]]:
    """(what differs or is missing, what AFTER adds)."""
    issues = []
    for name, old in before.variables.items():
        if name not in after.variables:
            issues.append(f"missing {name}")
            continue
        new = after[name].variable
        if old.dims != new.dims or old.dtype != new.dtype:
            issues.append(f"{name}: {old.dims} {old.dtype} -> {new.dims} {new.dtype}")
        elif np.asarray(old.values).tobytes() != np.asarray(new.values).tobytes():
            issues.append(f"{name}: values differ")
        # as text: an attribute may be an array (flag_values), which != does not reduce
        changed = sorted(k for k in {*old.attrs, *new.attrs}
                         if str(old.attrs.get(k)) != str(new.attrs.get(k)))
        if changed:
            issues.append(f"{name}: attributes {', '.join(changed)} differ")
    added = [name for name in after.variables if name not in before.variables]
    for key in sorted({*before.attrs, *after.attrs} - VOLATILE):
        if key not in after.attrs:
            issues.append(f"global attribute {key} missing")
        elif key not in before.attrs:
            added.append(f"@{key}")
        elif str(before.attrs[key]) != str(after.attrs[key]):
            issues.append(f"global attribute {key}: {str(before.attrs[key])[:120]!r} -> "
                          f"{str(after.attrs[key])[:120]!r}")
    return issues, added


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("before", type=Path, help="folder of the archives before the change")
    parser.add_argument("after", type=Path, help="folder of the archives after it")
    parser.add_argument("names", nargs="*", help="archive stems (default: every one of BEFORE)")
    parser.add_argument("--renamed", nargs="+", default=[], metavar="OLD=NEW",
                        help="BEFORE's name OLD is AFTER's NEW (a variable, a dimension or a "
                             "global attribute renamed on purpose)")
    parser.add_argument("--renamed-text", nargs="+", default=[], metavar="OLD=NEW",
                        help='a quoted "OLD" inside BEFORE\'s text attributes is AFTER\'s "NEW"')
    args = parser.parse_args(argv)
    renamed = dict(pair.split("=", 1) for pair in args.renamed)
    renamed_text = dict(pair.split("=", 1) for pair in args.renamed_text)
    names = args.names or sorted({p.stem for p in args.before.iterdir()
                                  if p.suffix in (".nc", ".zarr")})
    failed = 0
    for name in names:
        paths = [next((folder / f"{name}{s}" for s in (".nc", ".zarr")
                       if (folder / f"{name}{s}").exists()), None)
                 for folder in (args.before, args.after)]
        if None in paths:
            print(f"{name}: no archive in {args.before if paths[0] is None else args.after}")
            failed += 1
            continue
        issues, added = differences(
            open_archive(paths[0], renamed, renamed_text),
            open_archive(paths[1], renamed_text={new: new for new in renamed_text.values()}))
        print(f"{name}: {'differs' if issues else 'equal'}"
              + (f" (added: {', '.join(added)})" if added else ""))
        for line in issues:
            print(f"    {line}")
        failed += bool(issues)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
