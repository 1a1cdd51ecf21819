"""Records no earthquake produced are refused where a run reads them, with the unit that fits:
text and AT2 files (command line and pipeline.sweep), Record.from_array, and bare arrays."""
from pathlib import Path

import numpy as np
import pytest

import pipeline
from pipeline.errors import SweepError
from pipeline.records import G, Record, RecordError, load_record, read_at2, read_text
from pipeline.records.plausible import check_plausible, record_peaks
from studies import sweep as sweep_cli

SHARED = Path("/work/shared/records")
SHARED_AT2 = sorted(SHARED.glob("*.AT2"))
needs_shared = pytest.mark.skipif(not SHARED_AT2, reason="no records in /work/shared/records")


def pulse(pga: float, duration: float = 10.0, dt: float = 0.01) -> np.ndarray:
    """A 0.67 Hz sine under a sin^2 envelope, peaking at `pga` (in whatever unit)."""
    t = np.arange(0.0, duration, dt)
    a = np.sin(2 * np.pi * t / 1.5) * np.sin(np.pi * t / duration) ** 2
    return pga * a / np.max(np.abs(a))


# --------------------------------------------------------------------------- text records


def test_text_record_in_cm_s2_given_as_g_is_refused_with_the_cm_s2_hint(tmp_path, capsys):
    np.savetxt(tmp_path / "rec.txt", pulse(488.0))  # 488 cm/s^2 = 0.497 g
    with pytest.raises(RecordError) as err:
        load_record(tmp_path / "rec.txt", units="g", dt=0.01, check=True)
    text = str(err.value)
    assert "a PGA of 488 g is implausible (outside [0.0001, 5] g)" in text
    assert "the values look like cm/s^2 (0.497 g)" in text
    assert "--record-units cm/s^2" in text and "units='cm/s^2'" in text
    # the same file in its own units is a record
    assert load_record(tmp_path / "rec.txt", units="cm/s2", dt=0.01,
                       check=True).pga_g == pytest.approx(488 / 981, rel=1e-3)
    # the command line: one error line, exit status 2, nothing run
    code = sweep_cli.main(["--records", "rec.txt", "--records-dir", str(tmp_path),
                           "--record-units", "g", "--record-dt", "0.01", "--gap-cm", "30",
                           "--quiet", "--out", str(tmp_path / "out")])
    assert code == 2
    (line,) = capsys.readouterr().err.strip().splitlines()
    assert line.startswith("error: ") and "look like cm/s^2 (0.497 g)" in line
    assert "--record-units cm/s^2" in line
    assert not (tmp_path / "out").exists()


def test_text_record_step_in_ms_is_refused_with_the_step_in_s(tmp_path):
    np.savetxt(tmp_path / "rec.txt", pulse(0.3))
    with pytest.raises(RecordError, match=r"duration of 1e\+04 s .*is the step in ms\? 10 ms "
                                          r"is 0\.01 s; give dt 0\.01 s"):
        load_record(tmp_path / "rec.txt", units="g", dt=10, check=True)


def test_readers_and_load_record_check_only_when_asked(tmp_path):
    np.savetxt(tmp_path / "rec.txt", pulse(488.0))
    assert read_text(tmp_path / "rec.txt", "g", dt=0.01).pga_g == pytest.approx(488)
    assert load_record(tmp_path / "rec.txt", units="g", dt=0.01).pga_g == pytest.approx(488)


def test_sweep_given_a_text_path_says_how_to_give_its_units(tmp_path):
    np.savetxt(tmp_path / "rec.txt", pulse(0.3))
    path = str(tmp_path / "rec.txt")
    with pytest.raises(SweepError) as err:
        pipeline.sweep(path, gap=0.1, quiet=True)
    text = str(err.value)
    assert "\n" not in text and "pipeline.sweep does not take" in text
    assert f"pipeline.records.load_record({path!r}, units='g', dt=0.01, check=True)" in text
    assert "--record-units" in text
    # what it says to call works
    rec = load_record(path, units="g", dt=0.01, check=True)
    assert rec.pga_g == pytest.approx(0.3)


# --------------------------------------------------------------------------- AT2 files


def _copy_with_units(src: Path, dst: Path, units: str) -> Path:
    """A copy of a real AT2 file whose header's units line says `units` (values unchanged)."""
    lines = src.read_text(encoding="latin-1").split("\n")
    (i,) = [k for k, line in enumerate(lines[:4]) if "UNITS OF G" in line.upper()]
    lines[i] = lines[i].replace("UNITS OF G", f"UNITS OF {units}")
    dst.write_text("\n".join(lines), encoding="latin-1")
    return dst


@needs_shared
@pytest.mark.parametrize("src", SHARED_AT2, ids=lambda p: p.name)
def test_at2_with_a_cm_s2_header_over_values_in_g_is_refused(tmp_path, src):
    bad = _copy_with_units(src, tmp_path / f"CMSS_{src.name}", "CM/S/S")
    pga_g = read_at2(src).pga_g
    # read unchecked, the slip goes through: the PGA 981 times too small (~0.001 g)
    assert read_at2(bad).pga_g == pytest.approx(pga_g / 100 / G, rel=1e-12)
    with pytest.raises(RecordError) as err:
        read_at2(bad, check=True)
    text = str(err.value)
    assert "is weak (under 0.01 g) for values in cm/s^2 (the header's units)" in text
    assert f"the values look like g ({pga_g:.3g} g)" in text
    assert "correct the file's header to say 'UNITS OF G'" in text
    with pytest.raises(SweepError, match=r"records: .*look like g"):
        pipeline.sweep(str(bad), gap=0.1, quiet=True)


@needs_shared
def test_at2_slip_on_the_command_line_is_one_line(tmp_path, capsys):
    bad = _copy_with_units(SHARED_AT2[0], tmp_path / "BAD.AT2", "CM/S/S")
    assert sweep_cli.main(["--records", str(bad), "--gap-cm", "30", "--quiet",
                           "--out", str(tmp_path / "out")]) == 2
    (line,) = capsys.readouterr().err.strip().splitlines()
    assert line.startswith("error: records: ") and "'UNITS OF G'" in line


def test_at2_in_cm_s2_without_a_units_line_is_refused(tmp_path):
    values = pulse(300.0, duration=20.0, dt=0.02)  # cm/s^2, written as if in g
    rows = "\n".join(" ".join(f"{v: .7E}" for v in values[i:i + 5])
                     for i in range(0, values.size, 5))
    path = tmp_path / "NOUNITS.AT2"
    path.write_text("PEER NGA STRONG MOTION DATABASE RECORD\nSynthetic, 1/1/2000, Test, 0\n"
                    "ACCELERATION TIME SERIES\n"
                    f"NPTS= {values.size}, DT= .0200 SEC,\n{rows}\n")
    with pytest.raises(RecordError, match=r"a PGA of 300 g is implausible .*look like cm/s\^2 "
                                          r"\(0\.306 g\).*'UNITS OF CM/S/S'"):
        load_record(path, check=True)


def _at2(path: Path, values: np.ndarray, units: str = "G", dt: float = 0.01) -> Path:
    """An AT2 file of `values` under a header whose units line says `units`."""
    rows = "\n".join(" ".join(f"{v: .7E}" for v in values[i:i + 5])
                     for i in range(0, values.size, 5))
    path.write_text("PEER NGA STRONG MOTION DATABASE RECORD\nSynthetic, 1/1/2000, Test, 0\n"
                    f"ACCELERATION TIME SERIES IN UNITS OF {units}\n"
                    f"NPTS= {values.size}, DT= {dt:.4f} SEC,\n{rows}\n")
    return path


@pytest.mark.parametrize("pga_g", [0.6, 1.2, 1.8])
def test_at2_in_m_s2_under_a_g_header_is_refused_and_the_advice_runs_it(tmp_path, capsys,
                                                                          pga_g):
    """Issue 40: values in m/s^2 under 'UNITS OF G' were refused with the advice 'CM/S/S',
    which then ran the record at 0.012 g. The advice is now the unit whose PGA is nearest a
    strong motion's (plausible.STRONG_PGA_G): m/s^2. On the command line: exit 2, one line,
    nothing written; the header corrected as told, the record runs at its PGA."""
    values = pulse(pga_g * G)  # m/s^2, the header saying g
    bad = _at2(tmp_path / "MSS.AT2", values)
    with pytest.raises(RecordError) as err:
        read_at2(bad, check=True)
    assert "correct the file's header to say 'UNITS OF M/S/S'" in str(err.value)
    assert f"m/s^2 ({pga_g:.3g} g)" in str(err.value).split(" or ")[0]
    out = tmp_path / "out"
    argv = ["--gap-cm", "30", "--quiet"]
    assert sweep_cli.main(["--records", str(bad), *argv, "--out", str(out / "a.nc")]) == 2
    (line,) = capsys.readouterr().err.strip().splitlines()
    assert "'UNITS OF M/S/S'" in line and not out.exists()
    fixed = _at2(tmp_path / "FIXED.AT2", values, units="M/S/S")  # the advice followed
    assert read_at2(fixed, check=True).pga_g == pytest.approx(pga_g, rel=1e-6)
    assert sweep_cli.main(["--records", str(fixed), *argv, "--out", str(out / "b.nc")]) == 0


def test_a_spike_is_refused_as_a_bad_sample_not_a_unit(tmp_path):
    """Issue 40: one sample of 50 g in a record of 0.5 g was refused with the advice that the
    values were in cm/s^2 (0.051 g), which would have run the whole record 981 times too
    weak. It is now named a spike, at its time; the sample removed, the record runs."""
    values = pulse(0.5)
    values[400] = 50.0  # t = 4 s
    bad = _at2(tmp_path / "SPIKE.AT2", values)
    with pytest.raises(RecordError) as err:
        read_at2(bad, check=True)
    text = str(err.value)
    assert "it is a spike, one sample at t = 4 s" in text and "remove it" in text
    assert "look like" not in text and "UNITS OF" not in text
    values[400] = 0.5 * values[399] + 0.5 * values[401]  # the advice followed
    assert read_at2(_at2(tmp_path / "MENDED.AT2", values), check=True).pga_g == \
        pytest.approx(0.5, rel=1e-6)


@needs_shared
@pytest.mark.parametrize("src", SHARED_AT2, ids=lambda p: p.name)
def test_real_records_pass(src):
    rec = read_at2(src, check=True)
    assert load_record(src, check=True).npts == rec.npts
    pga, pgv, duration = record_peaks(rec.accel, rec.dt)
    assert 0.5 < pga / G < 1.5 and 0.5 < pgv < 1.5 and 30 <= duration <= 150


def test_library_and_paper_records_pass():
    from pipeline.records import library_index, paper_records

    for rec in [*map(lambda e: load_record(e.name), library_index()), *paper_records()]:
        check_plausible(rec.accel, rec.dt, "g", rec.name)  # raises if refused


# --------------------------------------------------------------------------- arrays


def test_from_array_converts_units():
    g = pulse(0.3)
    a = Record.from_array(g, 0.01, units="g", name="mine")
    b = Record.from_array(g * 9.81, 0.01, units="m/s2")
    c = Record.from_array(g * 981, 0.01, units="cm/s2")
    d = Record.from_array(g * 981, 0.01, units="gal")
    np.testing.assert_allclose(a.accel, g * G, rtol=1e-12)
    for other in (b, c, d):
        np.testing.assert_allclose(other.accel, a.accel, rtol=1e-12)
    assert (a.name, a.dt, a.npts, a.rsn, a.scale) == ("mine", 0.01, g.size, None, 1.0)
    assert a.pga_g == pytest.approx(0.3) and not a.accel.flags.writeable
    # a record like any other: scaled, and run by a sweep
    assert a.scaled(2).pga_g == pytest.approx(0.6)


def test_from_array_refuses_implausible_records_with_the_hint():
    with pytest.raises(RecordError, match=r"a PGA of 488 g is implausible .*look like cm/s\^2 "
                                          r"\(0\.497 g\); give units='cm/s\^2'"):
        Record.from_array(pulse(488.0), 0.01, units="g")
    with pytest.raises(RecordError, match=r"weak .*look like g \(0\.8 g\)"):
        Record.from_array(pulse(0.8), 0.01, units="cm/s^2")
    with pytest.raises(RecordError, match=r"duration of 0\.05 s"):
        Record.from_array(pulse(0.3, duration=0.05), 0.01, units="g")
    with pytest.raises(RecordError, match="units None not understood"):
        Record.from_array(pulse(0.3), 0.01, units=None)
    with pytest.raises(TypeError):
        Record.from_array(pulse(0.3), 0.01)  # units are required
    with pytest.raises(RecordError, match="units 'ft/s2' not understood"):
        Record.from_array(pulse(0.3), 0.01, units="ft/s2")


@pytest.mark.filterwarnings("ignore::pipeline.errors.PlausibilityWarning")  # dt, coarse
def test_sweep_runs_an_array_record():
    rec = Record.from_array(pulse(0.3, duration=4.0), 0.01, units="g", name="mine")
    ds = pipeline.sweep([rec], gap=[0.10], thickness=0.03, quiet=True, dt=2e-3)
    assert list(ds.record.values) == ["mine"]


@pytest.mark.parametrize("records", [np.zeros(10), [np.zeros(10)], ["kobe", np.ones(5)]])
def test_sweep_given_an_array_says_to_wrap_it(records):
    with pytest.raises(SweepError) as err:
        pipeline.sweep(records, gap=0.1, quiet=True)
    text = str(err.value)
    assert "\n" not in text
    assert text.startswith("records: a NumPy array is not a record")
    assert "Record.from_array(accel, dt, units=...)" in text


def test_sweep_in_plan_given_an_array_says_to_wrap_it():
    with pytest.raises(SweepError, match=r"not a record pair .*Record\.from_array"):
        pipeline.sweep(np.zeros(10), gap=0.1, quiet=True, moat="circular")


@pytest.mark.parametrize("spec", ["kobe*100", "kobe*1e-6"])
def test_a_record_scaled_past_any_recorded_pga_is_refused_with_the_factors_that_run(spec):
    """`kobe*100` (PGA 83 g) ran with only a flag in the archive: a scaled record's PGA is
    checked after the factor, and the factors the refusal gives (rounded inward) run."""
    with pytest.raises(RecordError, match=r"after the factor .* give a factor between") as err:
        load_record(spec)
    low, high = (float(x) for x in str(err.value).split("between ")[1].split(" and "))
    kobe = load_record("kobe").pga / G
    assert low * kobe >= 1e-4 and high * kobe <= 5.0
    assert high * kobe > 4.95 and low * kobe < 1.01e-4  # the bounds, to 3 digits
    for factor in (low, high):  # the advice followed
        assert 1e-4 <= load_record(f"kobe*{factor:g}").pga / G <= 5.0


def test_a_scaled_record_or_pair_past_any_recorded_pga_is_refused_before_compute(tmp_path, capsys):
    assert sweep_cli.main(["--records", "kobe*100", "--gap", "0.1", "--out",
                           str(tmp_path / "k.nc")]) == 2
    (line,) = capsys.readouterr().err.strip().splitlines()
    assert "kobe*100: a PGA of 83.4 g after the factor 100 is implausible" in line
    assert not list(tmp_path.iterdir())
    with pytest.raises(RecordError, match="RSN953\\*100: a PGA of 51.6 g"):
        pipeline.records.load_pair("RSN953*100")


def test_a_level_past_any_recorded_pga_is_refused_and_the_level_it_gives_runs(tmp_path,
                                                                              capsys):
    """Issue 40, the same slip by another road: `--level 50` on kobe as it is (PGA 42 g) ran.
    Refused before compute naming the largest level within 5 g, which runs; a study's levels
    multiply its suite's factors and are bounded by its design instead (not checked here)."""
    from tests.pipeline.small_sweep import no_compute

    out = ["--records", "kobe", "--gap", "0.1", "--dt", "0.002", "--quiet", "--out",
           str(tmp_path / "k.nc")]
    with pytest.MonkeyPatch.context() as nothing_runs:
        no_compute(nothing_runs)
        assert sweep_cli.main([*out, "--level", "1", "50"]) == 2
    line = capsys.readouterr().err.strip().splitlines()[-1]
    assert line.startswith("error: kobe: level 50 takes its PGA to 41.7 g, implausible")
    advised = float(line.split("levels up to ")[1])
    assert 4.95 < advised * load_record("kobe").pga / G <= 5.0 and not list(tmp_path.iterdir())
    assert sweep_cli.main([*out, "--level", "1", f"{advised:g}"]) == 0
