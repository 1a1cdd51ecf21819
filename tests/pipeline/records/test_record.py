"""A record (pipeline/records/record.py): bad arrays refused, the RSN read from a file name."""

import numpy as np
import pytest

from pipeline import records as R
from pipeline.records import RecordError
from tests.pipeline.records.at2_writer import simple_at2


def test_rsn_from_file_name(tmp_path):
    path = simple_at2(tmp_path, name="RSN1106_KOBE_KJM000.AT2")
    rec = R.read_at2(path)
    assert rec.rsn == 1106 and rec.event == "Kobe Japan"
    assert R.read_at2(simple_at2(tmp_path, name="SCS142.AT2")).rsn is None


def test_record_rejects_bad_arrays():
    kwargs = dict(name="x", rsn=None, event="", station="", component="", source="test")
    with pytest.raises(RecordError, match="not finite|NaN"):
        R.Record(dt=0.01, accel=np.array([0.0, np.nan]), **kwargs)
    with pytest.raises(RecordError, match="DT must be"):
        R.Record(dt=0.0, accel=np.zeros(3), **kwargs)
    with pytest.raises(RecordError, match="non-empty"):
        R.Record(dt=0.01, accel=np.zeros(0), **kwargs)
