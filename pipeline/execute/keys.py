"""Every key of a resumable run, made here and nowhere else.

- context_key: what besides a member's own record (members.MEMBER_DTYPE) decides its result: the
  record's content and intensity factor, dt, the building, the moat in plan, the engine (its
  fingerprint) and CACHE_FORMAT;
- batch_key: one batch of members under one context (a work folder's file name; NetCDF);
- sweep_key: a whole sweep, every context and every member (a Zarr store's identity);
- region_key: one chunk region of a Zarr store.

The engine's results do not depend on the batch a member ran in, so batch sizes and worker
counts may change between runs without invalidating a key.
"""
from __future__ import annotations

import hashlib
import json

import numpy as np

from ..provenance import engine_fingerprint, record_hash

CACHE_FORMAT = 8  # bump when the work-folder layout, the member record or the peak set change


def context_key(record, dt: float, building, moat: str | None = None,
                factor: float | None = None, bumper_positions=None,
                backend: str | None = None) -> str:
    """Everything besides the member record that determines a member's result (the moat of a
    run in plan, whose record is a pair; the record's intensity factor, None for none; the
    bumpers' positions along the walls of a building that twists; a time loop asked for
    other than the compiled one, whose last bits are its own)."""
    fields = {"format": CACHE_FORMAT, "engine": engine_fingerprint(),
              "record": record_hash(record.accel, record.dt), "dt": float(dt).hex(),
              "building": repr(building), "moat": moat,
              "factor": None if factor is None else float(factor).hex()}
    if bumper_positions is not None:  # absent otherwise: the keys of earlier runs hold
        fields["bumper_positions"] = [[float(x).hex() for x in np.ravel(side)]
                                      for side in bumper_positions]
    if backend in ("numpy", "cuda"):  # absent otherwise: the compiled kernel's keys hold
        fields["backend"] = backend
    text = json.dumps(fields, sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()


def batch_key(context: str, members: np.ndarray) -> str:
    """A batch: its context and its (b,) member records."""
    digest = hashlib.sha256(context.encode())
    digest.update(np.ascontiguousarray(members).data)  # the same digest, no bytes copied
    return digest.hexdigest()


def sweep_key(members: np.ndarray, contexts: list[str]) -> str:
    """A sweep: every record's context and the (M,) member records of the grid."""
    digest = hashlib.sha256(json.dumps(contexts).encode())
    digest.update(np.ascontiguousarray(members).data)  # no copy of a large table
    return digest.hexdigest()


def region_key(sweep: str, index: int) -> str:
    """Chunk region `index` of the store of sweep `sweep`."""
    return f"{sweep[:12]}-{index}"
