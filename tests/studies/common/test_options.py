"""Command lines that behave: implausible inputs refused before compute, negative numbers,
one meaning of --out, common options on every recipe, --replot's report, unguarded scripts."""
from __future__ import annotations

import importlib
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from studies import sweep as sweep_cli

PROJECT = Path(__file__).resolve().parents[3]
RECIPES = ["impact_validation", "damping_calibration", "practical_example", "gap_size",
           "thickness", "strain", "n_bumpers", "wall_stiffness", "restitution", "suite",
           "design"]


@pytest.mark.parametrize("option, value, hint", [
    ("--gap", "20", "--gap-cm 20"), ("--thickness", "5", "--thickness-cm 5"),
    ("--cavity", "2.5", "--cavity-cm 2.5")])
def test_lengths_in_cm_given_as_m_are_refused(option, value, hint, tmp_path, capsys):
    argv = ["--records", "pacoima", "--out", str(tmp_path / "x.nc")]
    if option != "--gap":
        argv += ["--gap", "0.3"]
    assert sweep_cli.main([*argv, option, value]) == 2
    err = capsys.readouterr().err
    assert "implausible (outside" in err and hint in err and len(err.splitlines()) == 1
    assert not (tmp_path / "x.nc").exists() and not (tmp_path / "x.nc.work").exists()


@pytest.mark.parametrize("argv, line", [
    (["--gap-cm", "20", "--thickness-cm", "0.05"], "error: --thickness-cm 0.05 cm is 0.0005 m, "
     "implausible for thickness (outside [0.005, 2] m); did you mean --thickness-cm 5 (0.05 m)?"),
    (["--gap-cm", "20", "--strain", "80"], "error: strain must be in (0, 1], got [80.]: a ratio, "
                                           "not a percentage (80% is 0.8)"),
    (["--gap-cm", "0.2"], "error: --gap-cm 0.2 cm is 0.002 m, implausible for gap (outside "
                          "[0.01, 2] m); did you mean --gap-cm 20 (0.2 m)?"),
])
def test_slips_in_the_paper_units_and_percentages_say_what_was_meant(argv, line, tmp_path,
                                                                     capsys):
    assert sweep_cli.main(["--records", "pacoima", *argv, "--out", str(tmp_path / "x")]) == 2
    assert capsys.readouterr().err.strip() == line
    assert not (tmp_path / "x").exists()


@pytest.mark.parametrize("argv, hint", [
    (["--wall-k", "1500"], "1500 kN/mm is 1.5e+09 N m-1), or --wall-k-kn-mm 1500"),
    (["--m-eff", "320"], "320 t is 320000 kg), or --m-eff-t 320"),
    (["--k2", "25"], "25 kN/mm is 2.5e+07 N m-1), or --k2-kn-mm 25"),
    (["--impact", "linear", "--wall-k", "2.5e15"], "outside [1e6, 1e13] N m-1"),
])
def test_values_in_the_paper_units_given_as_si_are_refused(argv, hint, tmp_path, capsys):
    assert sweep_cli.main(["--records", "pacoima", "--gap", "0.3", *argv,
                           "--out", str(tmp_path / "x")]) == 2
    err = capsys.readouterr().err
    assert "implausible" in err and hint in err and len(err.splitlines()) == 1
    assert not (tmp_path / "x").exists()


@pytest.mark.parametrize("setting, hint", [
    ("masses=320,320,320,320,250", "masses 320 kg is implausible (outside [1e3, 1e9] kg): give "
                                   "kg (320 t is 320000 kg)"),
    ("story_stiffness=600,600,600,600", "600 kN/mm is 6e+08 N m-1"),
    ("k2=25", "building isolator k2 25 N m-1 is implausible"),
])
def test_implausible_building_is_refused(setting, hint, tmp_path, capsys):
    assert sweep_cli.main(["--records", "pacoima", "--gap", "0.3", "--building", setting,
                           "--out", str(tmp_path / "x")]) == 2
    err = capsys.readouterr().err
    assert hint in err and len(err.splitlines()) == 1


def test_step_coarser_than_the_converged_one_is_announced(tmp_path, capsys):
    assert sweep_cli.main(["--records", "pacoima", "--gap", "0.3", "--dt", "0.004", "--quiet",
                           "--out", str(tmp_path)]) == 0
    err = capsys.readouterr().err
    assert "warning: dt = 0.004 s is 8 x the converged step 0.0005 s" in err
    assert len(err.splitlines()) == 1


@pytest.mark.parametrize("value", ["-1e9", "-5", "-0.5", "-.5E+3"])
def test_negative_numbers_reach_the_range_check(value, tmp_path, capsys):
    assert sweep_cli.main(["--records", "pacoima", "--gap", "0.3", "--wall-k", value,
                           "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert "wall_k must be in (0, inf)" in err and "expected" not in err


def test_out_is_a_file_or_a_folder_in_every_command(tmp_path, capsys):
    argv = ["--records", "pacoima", "--gap-cm", "25", "--dt", "1e-3", "--quiet"]
    assert sweep_cli.main([*argv, "--out", str(tmp_path / "mine.nc")]) == 0
    assert sweep_cli.main([*argv, "--out", str(tmp_path / "folder")]) == 0
    with xr.open_dataset(tmp_path / "mine.nc") as a, \
            xr.open_dataset(tmp_path / "folder" / "sweep.nc") as b:
        np.testing.assert_array_equal(a.peak_total_accel, b.peak_total_accel)
    strain = importlib.import_module("studies.strain")
    assert strain.main(["--quick", "--quiet", "--records", "pacoima", "--dt", "1e-3",
                        "--out", str(tmp_path / "fig18.nc")]) == 0
    quick = tmp_path / "quick"  # beside the full run's outputs, never over them
    assert {p.name for p in quick.glob("fig18*")} == {"fig18.nc", "fig18.png", "fig18.pdf"}
    assert not list(quick.glob("*.work"))  # work folders go once the archive is written
    capsys.readouterr()
    assert strain.main(["--replot", "--quick", "--out", str(tmp_path / "fig18.nc")]) == 0
    out = capsys.readouterr().out
    assert f"redrew {quick / 'fig18.png'} {quick / 'fig18.pdf'} from " in out
    assert "wrote" not in out


@pytest.mark.parametrize("name", RECIPES)
def test_every_recipe_takes_the_common_options(name, tmp_path):
    parser = importlib.import_module(f"studies.{name}").recipe.parser()
    args = parser.parse_args(["--records-dir", str(tmp_path), "--workers", "1", "--scheduler",
                              "tcp://127.0.0.1:1", "--dt", "5e-4", "--out", str(tmp_path),
                              "--quick", "--quiet"])
    assert args.workers == 1 and args.out == tmp_path


CODE_BASED = ("suite", "fragility", "collapse", "loss", "design", "plan", "torsion")
"""The studies that run FEMA P695 pairs unless given --records."""


@pytest.mark.parametrize("name", CODE_BASED)
def test_every_code_based_study_runs_the_fema_set_chosen(name):
    """--set picks the FEMA P695 set whose pairs run (default the far-field's 22), and only
    where --records does not name them."""
    from studies.common.options import chosen_pairs

    parser = importlib.import_module(f"studies.{name}").recipe.parser()
    far, pulse = (parser.parse_args(argv) for argv in ([], ["--set", "near-field-pulse"]))
    assert far.set == "far-field"
    assert len(chosen_pairs(far, 4)[1]) == 22
    # the near-field pulse pairs: Imperial Valley's El Centro Array #6 first (RSN181), 14 in all
    names = chosen_pairs(pulse, 4)[1]
    assert len(names) == 14 and names[0] == "RSN181"
    pulse.quick = True
    assert chosen_pairs(pulse, 4)[1] == names[:4]
    assert chosen_pairs(parser.parse_args(["--set", "near-field-pulse", "--records", "RSN953"]),
                        4)[1] == ["RSN953"]


def test_output_folder_that_cannot_be_written_fails_before_compute(tmp_path, capsys):
    """A folder under a plain file cannot be made (permissions would not bind for root)."""
    blocker = tmp_path / "a_file"
    blocker.write_text("")
    gap_size = importlib.import_module("studies.gap_size")
    assert gap_size.main(["--quick", "--records", "pacoima", "--out",
                          str(blocker / "out")]) == 2
    err = capsys.readouterr().err
    assert "cannot write" in err and len(err.splitlines()) == 1


def test_unguarded_script_with_worker_processes(tmp_path):
    """A script without `if __name__ == "__main__":` that starts 2 local workers runs once,
    and gives the numbers of an in-process run."""
    script = tmp_path / "unguarded.py"
    script.write_text(textwrap.dedent("""
        import pipeline
        ds = pipeline.sweep(["pacoima"], gap=[0.2, 0.3], workers=2, dt=1e-3, quiet=True)
        print("peaks", repr(ds.peak_isolator_disp.values.tolist()))
    """))
    done = subprocess.run([sys.executable, str(script)], cwd=tmp_path, capture_output=True,
                          text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-2000:]
    lines = [line for line in done.stdout.splitlines() if line.startswith("peaks")]
    assert len(lines) == 1  # the workers did not run the script again
    import pipeline

    local = pipeline.sweep(["pacoima"], gap=[0.2, 0.3], dt=1e-3, quiet=True)
    assert lines[0] == "peaks " + repr(local.peak_isolator_disp.values.tolist())


def _text_records(folder: Path) -> None:
    """rec1.txt (one column, g, 0.01 s) and rec2.txt (time, g): the same 10 s pulse."""
    t = np.arange(0.0, 10.0, 0.01)
    accel = 0.3 * np.sin(2 * np.pi * t / 1.5) * np.sin(np.pi * t / 10) ** 2
    folder.mkdir(exist_ok=True)
    np.savetxt(folder / "rec1.txt", accel)
    np.savetxt(folder / "rec2.txt", np.column_stack([t, accel]))


def test_text_records_run_from_the_command_line(tmp_path, capsys):
    _text_records(tmp_path / "recs")
    common = ["--records-dir", str(tmp_path / "recs"), "--gap-cm", "10", "--quiet"]
    assert sweep_cli.main(["--records", "rec1.txt", "rec2.txt", "--record-units", "g",
                           "--record-dt", "0.01", *common, "--out", str(tmp_path)]) == 0
    with xr.open_dataset(tmp_path / "sweep.nc") as ds:
        assert list(ds.record.values) == ["rec1", "rec2"]
        np.testing.assert_allclose(ds.record_pga, 0.3 * 9.81 * np.max(np.abs(
            np.sin(2 * np.pi * np.arange(0, 10, 0.01) / 1.5)
            * np.sin(np.pi * np.arange(0, 10, 0.01) / 10) ** 2)), rtol=1e-12)
        # one column or two, the same record: the same numbers
        np.testing.assert_array_equal(ds.peak_total_accel[0], ds.peak_total_accel[1])
    capsys.readouterr()
    assert sweep_cli.main(["--records", "rec1.txt", *common, "--out", str(tmp_path / "x")]) == 2
    err = capsys.readouterr().err
    assert "--record-units" in err and len(err.splitlines()) == 1
    assert sweep_cli.main(["--records", "pacoima", "--record-units", "g", *common,
                           "--out", str(tmp_path / "x")]) == 2
    assert "apply to text records" in capsys.readouterr().err
    strain = importlib.import_module("studies.strain")
    assert strain.main(["--quick", "--records", str(tmp_path / "recs" / "rec2.txt"),
                        "--record-units", "g", "--dt", "1e-3", "--quiet",
                        "--out", str(tmp_path / "fig")]) == 0
    with xr.open_dataset(tmp_path / "fig" / "quick" / "strain.nc") as ds:
        assert list(ds.record.values) == ["rec2"]


@pytest.mark.parametrize("name", ["suite", "fragility", "design"])
@pytest.mark.parametrize("argv, words", [
    (["--sms-g", "-1"], "--sms-g: S_MS must be positive (g), got -1"),
    (["--sm1-g", "90"], "--sm1-g 90 g is implausible for S_M1 (above 4 g): give g (90% g is "
                        "0.9 g)"),
    (["--tl", "80"], "--tl 80 s is implausible for T_L (above 20 s)"),
])
def test_a_site_no_real_site_has_is_refused_in_one_line(name, argv, words, tmp_path, capsys):
    module = importlib.import_module(f"studies.{name}")
    assert module.main(["--quick", "--quiet", "--out", str(tmp_path), *argv]) == 2
    (line,) = capsys.readouterr().err.strip().splitlines()
    assert line == f"{name}: error: {words}"
    assert not list(tmp_path.iterdir())  # refused before any compute: nothing written


@pytest.mark.parametrize("name, argv, words", [
    ("loss", ["--lambda-max", "15"], "--lambda-max 15 is implausible (above 3"),
    ("collapse", ["--lambda-min", "0.01"], "--lambda-min 0.01 is implausible (below 0.3"),
    ("fragility", ["--overstrength", "30"], "--overstrength 30 is implausible (outside [1, 3]"),
    ("loss", ["--floor-area", "9000000"], "--floor-area 9e+06 m^2 is implausible for one "
                                         "story (outside [20, 100000] m^2)"),
    # a site and bound the code designs a 3.9 m moat for: the design named, not a unit slip of
    # a gap the user never typed (it said "give m ... or --gap-cm", an option loss lacks)
    ("design", ["--sm1-g", "3.9", "--sms-g", "4.9", "--lambda-min", "0.3"],
     "the code's design gives D_M 3.41 m and D_TM 3.92 m (T_M 2.82 s)"),
])
def test_a_design_basis_no_real_building_has_is_refused_in_one_line(name, argv, words,
                                                                    tmp_path, capsys,
                                                                    monkeypatch):
    """Issue 40, the studies' options: before, each of these ran (a property modification
    factor of 15, an overstrength of 30, a 9 km^2 floor) or gave advice naming an option the
    study does not have. The defaults the advice names run in the studies' own tests."""
    from tests.pipeline.small_sweep import no_compute

    no_compute(monkeypatch)
    module = importlib.import_module(f"studies.{name}")
    assert module.main(["--quick", "--quiet", "--out", str(tmp_path), *argv]) == 2
    (line,) = capsys.readouterr().err.strip().splitlines()
    assert line.startswith(f"{name}: error: {words}"), line
    assert not list(tmp_path.iterdir())


def test_a_malformed_option_is_one_line_and_an_unwritable_output_is_refused(tmp_path, capsys):
    import os

    from studies import fragility, sweep

    with pytest.raises(SystemExit) as stop:
        sweep.main(["--records", "kobe", "--gap-cm", "20", "--n-bumpers", "2.5",
                    "--out", str(tmp_path / "x.nc")])
    assert stop.value.code == 2
    (line,) = capsys.readouterr().err.strip().splitlines()
    assert "--n-bumpers: invalid int value: '2.5'" in line and "--help" in line
    if not os.path.ismount("/sys"):
        pytest.skip("no /sys here: a folder that says writable but takes no file")
    # a folder the permission bits allow root but no file can be created in (sysfs)
    assert fragility.main(["--quick", "--quiet", "--out", "/sys/x.nc"]) == 2
    (line,) = capsys.readouterr().err.strip().splitlines()
    assert line.startswith("fragility: error: out: cannot write to /sys")
    assert not list(tmp_path.iterdir())


SITE_STUDIES = ("suite", "fragility", "collapse", "loss", "design", "torsion")
"""The studies that scale their pairs to a site's MCE_R spectrum (site_options)."""


@pytest.mark.parametrize("name", SITE_STUDIES)
def test_every_study_with_a_site_takes_a_site_specific_spectrum(name):
    parser = importlib.import_module(f"studies.{name}").recipe.parser()
    args = parser.parse_args(["--target-spectrum", "site.csv"])
    assert args.target_spectrum == Path("site.csv") and args.sm1_g is None


def _code_spectrum_table(path: Path) -> Path:
    """The two-period spectrum of the default site (S_MS 1.5 g, S_M1 0.9 g, T_L 8 s) as a
    --target-spectrum table."""
    from pipeline.motions.target import asce7_target

    target = asce7_target(1.5, 0.9, 8.0)
    path.write_text("period_s,sa_g\n" + "".join(
        f"{float(t)!r},{float(s)!r}\n" for t, s in zip(target.periods, target.sa_g,
                                                       strict=True)))
    return path


@pytest.mark.parametrize("extra, said", [
    (["--sm1-g", "0.6"], "error: --target-spectrum is the site's whole MCE_R spectrum: give "
                         "it or --sm1-g, not both"),
    (["--tl", "6"], "give it or --tl, not both"),
])
def test_a_spectrum_beside_site_values_is_refused_and_alone_it_runs(extra, said, tmp_path,
                                                                    capsys):
    """Site values beside a site-specific spectrum: refused before compute in one line; the
    spectrum alone (the advice followed) runs, S_M1 from it by ASCE 7-22 21.4 (the code's
    spectrum as a table: 0.9 g, its S_M1), the archive naming the table."""
    from studies import suite

    table = _code_spectrum_table(tmp_path / "site.csv")
    out = tmp_path / "out"
    assert suite.main(["--quick", "--target-spectrum", str(table), *extra,
                       "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and said in err and not out.exists()
    if extra[0] != "--sm1-g":
        return
    assert suite.main(["--quick", "--target-spectrum", str(table), "--quiet",
                       "--out", str(out)]) == 0
    with xr.open_dataset(out / "quick" / "suite.nc") as ds:
        assert ds.attrs["S_M1_g"] == pytest.approx(0.9, rel=1e-12)
        assert np.isnan(ds.attrs["T_L"]) and "site.csv" in ds.attrs["target"]


def test_a_spectrum_table_the_code_cannot_use_is_refused_in_one_line(tmp_path, capsys):
    from studies import suite

    table = tmp_path / "short.csv"
    table.write_text("period_s,sa_g\n0.5,1.0\n1.0,0.9\n3.0,0.3\n")
    assert suite.main(["--quick", "--target-spectrum", str(table), "--out",
                       str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "covers 0.5 to 3 s" in err
    assert "need 0.2 to 5 s at least (ASCE 7-22 section 21.4)" in err


@pytest.mark.parametrize("name", ["collapse", "loss"])
def test_the_collapse_and_loss_studies_run_a_designed_isolation_system_when_asked(name):
    """--isolators designed-tfp: the building's masses and stories on triple friction
    pendulums designed for the site and --t-m (pipeline.motions.designed_isolation), or
    designed-lrb on lead-rubber bearings; given keeps the building's own isolators; a period
    the friction forbids is one line."""
    from pipeline.building_file import building_from
    from pipeline.errors import SweepError
    from pipeline.motions.designed_isolation import designed_isolation
    from studies.common.options import isolated_building, property_factors, scaled_suite

    parser = importlib.import_module(f"studies.{name}").recipe.parser()

    def parsed(*argv):
        args = parser.parse_args(list(argv))
        args.building = building_from(args.building)  # as Recipe.main resolves it
        return args

    assert parsed().isolators == "designed-tfp"  # these studies' default (collapse_ida)
    given = parsed("--isolators", "given")
    assert isolated_building(given, None, property_factors(given)) is given.building
    args = parsed("--isolators", "designed-tfp", "--t-m", "2.5", "--sm1-g", "0.9")
    building = isolated_building(args, None, property_factors(args))
    expected = designed_isolation(0.9, args.building, 2.5, property_factors(args)).building
    assert building.isolator.law == "triple_friction_pendulum"
    assert building.isolator.values == expected.isolator.values
    # --isolators designed-lrb: lead-rubber bearings for the same target
    lrb = parsed("--isolators", "designed-lrb", "--t-m", "2.5", "--sm1-g", "0.9")
    bearing = isolated_building(lrb, None, property_factors(lrb)).isolator
    expected = designed_isolation(0.9, lrb.building, 2.5, property_factors(lrb),
                                  kind="designed-lrb").building.isolator
    assert bearing.law == "bilinear" and bearing.values == expected.values
    with pytest.raises(SweepError, match="cannot be reached"):
        scaled_suite(parsed("--isolators", "designed-tfp", "--t-m", "6", "--sm1-g", "0.1"), [],
                     [])


def test_the_lateral_system_designs_the_stories_a_study_runs():
    """--lateral-system steel-smf (the collapse study's default): its suite runs the stories
    the code designs for steel special moment frames (their Omega_0 3 the overstrength, each
    story yielding at 1% drift); --overstrength overrides Omega_0; given keeps the building's
    own stiffnesses, the default of the studies that test the paper's conclusions."""
    import engine
    from pipeline.building_file import building_from
    from pipeline.checks import resolve_pairs
    from studies.common.options import scaled_suite

    parser = importlib.import_module("studies.collapse").recipe.parser()
    pairs, _ = resolve_pairs(["RSN953"])

    def suite(*argv):
        args = parser.parse_args(list(argv))
        args.building = building_from(args.building)
        return scaled_suite(args, pairs, ["RSN953"]).superstructure

    smf = suite("--isolators", "given")
    assert smf.lateral_system.name == "steel-smf" and smf.overstrength == 3.0
    np.testing.assert_allclose(smf.strength / smf.stiffness, 0.01 * smf.story_height)
    for name in ("suite", "fragility", "design"):
        study = importlib.import_module(f"studies.{name}").recipe.parser()
        assert study.parse_args([]).lateral_system == "given", name
    assert suite("--isolators", "given", "--overstrength", "2.5").overstrength == 2.5
    given = suite("--isolators", "given", "--lateral-system", "given")
    assert given.lateral_system.name == "given" and given.overstrength == 2.0
    assert given.building.story_stiffness == engine.Building().story_stiffness


def test_the_collapse_drift_is_the_designed_stories_and_a_percent_is_refused():
    """--collapse-drift 0.05 (Kitayama & Constantinou 2018's limit): the designed building
    collapses at 5% of its story height; 5 (a percent typed as a ratio) is refused in one line
    that gives the ratio."""
    from pipeline.building_file import building_from
    from pipeline.checks import resolve_pairs
    from pipeline.errors import SweepError
    from studies.common.options import scaled_suite

    parser = importlib.import_module("studies.collapse").recipe.parser()
    pairs, _ = resolve_pairs(["RSN953"])

    def suite(*argv):
        args = parser.parse_args(list(argv))
        args.building = building_from(args.building)
        return scaled_suite(args, pairs, ["RSN953"])

    assert suite("--isolators", "given").building.collapse_drift_ratio == 0.10
    assert suite("--isolators", "given", "--collapse-drift", "0.05").building \
        .collapse_drift_ratio == 0.05
    with pytest.raises(SweepError, match=r"--collapse-drift 5 is implausible .*: give a ratio "
                                         r"\(5% is 0.05\)"):
        suite("--isolators", "given", "--collapse-drift", "5")
