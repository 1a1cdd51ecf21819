"""An archive's provenance (pipeline/provenance.py): real records, truncated to 8 s around their
peak and named by their paper keys, keep where they were found and their notes."""

import numpy as np

import pipeline
from tests.pipeline.small_sweep import (
    DT,
)


def test_paper_records_keep_their_provenance(paper_record):
    """Real records, truncated to 8 s around their peak, named by their paper keys."""
    import dataclasses

    recs = []
    for key in ("kobe", "pacoima"):
        rec = paper_record(key)
        n = int(8 / rec.dt)
        start = max(0, int(np.argmax(np.abs(rec.accel))) - n // 2)
        recs.append(dataclasses.replace(rec, accel=rec.accel[start:start + n]))
    ds = pipeline.sweep(recs, gap=0.15, dt=DT, workers=1, quiet=True)
    assert list(ds.record.values) == ["kobe", "pacoima"]
    assert ds.gap.dims == () and ds.peak_isolator_disp.dims == ("record",)
    assert ds.attrs["record_kobe_found_in"] == recs[0].found_in
    assert ds.attrs["record_kobe_note"] == recs[0].note
