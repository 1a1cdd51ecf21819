"""Buildings from files and settings: the example file, JSON, NAME=VALUE, and every malformed
input refused with one error naming the key and what it expects."""
from __future__ import annotations

import json

import numpy as np
import pytest
import xarray as xr

import engine
from pipeline.building_file import building_from, read_building
from pipeline.errors import BuildingError
from studies import sweep as sweep_cli
from tests.helpers import PROJECT

EXAMPLE = PROJECT / "examples" / "eight_story_friction_pendulum.toml"


def test_example_file_is_the_building_it_describes():
    b = read_building(EXAMPLE)
    assert b.n_levels == 9 and b.n_stories == 8
    assert b.masses[0] == 600e3 and b.story_stiffness[-1] == 0.5e9
    assert b.isolation.law == "friction_pendulum"
    assert b.isolation.values == {"radius": 2.2, "mu_slow": 0.05, "mu_fast": 0.10,
                                  "rate": 30.0, "yield_disp": 5e-4}
    assert b.isolation_zeta == 0.0  # friction is the damping
    np.testing.assert_allclose(b.story_yield_drift[0], 8.0e6 / 1.2e9)
    # W / R + k_0, k_0 = mu_fast W / yield_disp
    weight = 9.81 * sum(b.masses)
    assert b.isolator_stiffness == pytest.approx(weight / 2.2 + 0.10 * weight / 5e-4)


def test_json_and_settings_give_the_same_building(tmp_path):
    data = {"masses": [500e3, 400e3, 300e3], "story_stiffness": [8e8, 6e8],
            "isolator": {"law": "bilinear", "k1": 150e6, "k2": 20e6, "fy_ratio": 0.08}}
    path = tmp_path / "b.json"
    path.write_text(json.dumps(data))
    from_json = read_building(path)
    assert from_json == engine.Building(masses=(500e3, 400e3, 300e3),
                                        story_stiffness=(8e8, 6e8),
                                        isolator=engine.Isolator.bilinear(150e6, 20e6, 0.08))
    from_settings = building_from(["masses=500e3,400e3,300e3", "story_stiffness=8e8,6e8",
                                   "k1=150e6", "k2=20e6", "fy_ratio=0.08"])
    assert from_settings.isolation == from_json.isolation
    # settings apply over a file
    over = building_from([str(path), "zeta_sup=0.05"])
    assert over.zeta_sup == 0.05 and over.isolation == from_json.isolation


@pytest.mark.parametrize("text, match", [
    ("masses = 5\n", r"masses must be a list of numbers, one per level .* in kg, got 5"),
    ('masses = ["heavy", 2]\nstory_stiffness = [1e9]\n', r"masses must be a list .* kg"),
    ("mases = [1e5, 1e5]\n", r"unknown key\(s\) \['mases'\]; a building has masses"),
    ("masses = [1e5, 1e5]\nstory_stiffness = [1e9, 1e9]\n",
     r"story_stiffness must be 1 positive values in N/m"),
    ("zeta_sup = [0.02]\n", r"zeta_sup must be a number, got \[0.02\]"),
    ('[isolator]\nlaw = "lead_rubber"\n', r"isolator law 'lead_rubber' is not one of "
                                          r"bilinear, friction_pendulum"),
    ('[isolator]\nlaw = "friction_pendulum"\nradius = 2.0\n', r"mu_slow is required"),
    ('[isolator]\nlaw = "friction_pendulum"\nradius = "2 m"\nmu_slow = 0.05\nmu_fast = 0.1\n'
     'rate = 30\n', r"isolator radius must be a number in m, got '2 m'"),
    ('[isolator]\nlaw = "friction_pendulum"\nradius = 2\nmu_slow = 0.2\nmu_fast = 0.1\n'
     'rate = 30\n', r"mu_slow <= mu_fast"),
    ("masses = [1e5, \n", r"not valid TOML"),
])
def test_malformed_files_are_one_clear_error(tmp_path, text, match):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    with pytest.raises(BuildingError, match=match):
        read_building(path)


def test_bad_settings_and_paths(tmp_path):
    with pytest.raises(BuildingError, match="does not exist"):
        read_building(tmp_path / "missing.toml")
    with pytest.raises(BuildingError, match=r"give a \.toml or \.json file"):
        (tmp_path / "b.yaml").write_text("x: 1")
        read_building(tmp_path / "b.yaml")
    with pytest.raises(BuildingError, match="NAME must be one of"):
        building_from(["stiffness=1e9"])
    with pytest.raises(BuildingError, match="k1 must be a number in N m-1: 'stiff' is not a"):
        building_from(["k1=stiff"])


def test_sweep_command_runs_the_example_building(tmp_path, capsys):
    out = tmp_path / "eight.nc"
    assert sweep_cli.main(["--records", "pacoima", "--gap-cm", "20", "30", "--building",
                           str(EXAMPLE), "--baseline", "--quiet", "--out", str(out)]) == 0
    with xr.open_dataset(out) as ds:
        assert ds.floor.values.tolist() == list(range(9))
        assert ds.story.values.tolist() == list(range(1, 9))
        assert ds.peak_total_accel.dims[-1] == "floor" and ds.sizes["floor"] == 9
        assert ds.attrs["building_isolator_law"] == "friction_pendulum"
        assert ds.attrs["building_isolator_radius"] == 2.2
        assert "peak_story_ductility" in ds and "baseline_peak_story_ductility" in ds
        drift_y = np.array([8.0e6, 7.5e6, 7.0e6, 6.2e6, 5.4e6, 4.4e6, 3.3e6, 2.0e6]) / \
            np.array([1.2e9, 1.1e9, 1.0e9, 0.9e9, 0.8e9, 0.7e9, 0.6e9, 0.5e9])
        np.testing.assert_allclose(ds.peak_story_ductility.values,
                                   ds.peak_interstory_drift.values / drift_y, rtol=1e-12)


def test_sweep_command_refuses_a_malformed_building(tmp_path, capsys):
    path = tmp_path / "bad.toml"
    path.write_text("masses = 5\n")
    assert sweep_cli.main(["--records", "pacoima", "--gap-cm", "20", "--building", str(path),
                           "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "masses must be a list of numbers" in err and "kg" in err


def test_stories_heights_p_delta_and_collapse_from_a_file(tmp_path):
    path = tmp_path / "b.toml"
    path.write_text("story_height = [4.0, 3.5, 3.5, 3.5]\np_delta = true\n"
                    "collapse_drift_ratio = 0.1\n[stories]\nlaw = \"imk\"\n"
                    "yield_force = [6e6, 5e6, 4e6, 2e6]\nplastic_deformation = 0.09\n"
                    "post_capping_deformation = 0.35\n")
    b = read_building(path)
    assert b == engine.Building(
        stories=engine.Stories.imk(yield_force=(6e6, 5e6, 4e6, 2e6), plastic_deformation=0.09,
                                   post_capping_deformation=0.35),
        story_height=(4.0, 3.5, 3.5, 3.5), p_delta=True, collapse_drift_ratio=0.1)
    assert building_from([str(path), "p_delta=false"]).p_delta is False
    with pytest.raises(BuildingError, match="p_delta must be true or false"):
        building_from(["story_height=4,3.5,3.5,3.5", "p_delta=maybe"])
    with pytest.raises(BuildingError, match="stories law 'elastic' is not one of linear"):
        read_building(_written(tmp_path, "[stories]\nlaw = \"elastic\"\n"))
    with pytest.raises(BuildingError, match="stories yield_force must be a number in N"):
        read_building(_written(tmp_path, "[stories]\nlaw = \"bilinear\"\nyield_force = "
                                          "\"big\"\n"))
    with pytest.raises(BuildingError, match="need story_height"):
        building_from(["p_delta=true"])
    from pipeline.building_file import check_plausible

    with pytest.raises(BuildingError, match="story_height"):
        check_plausible(building_from(["story_height=0.035,0.035,0.035,0.035"]))


def test_a_triple_friction_pendulum_from_a_file(tmp_path):
    """Any law of the registry in the [isolator] table: the triple friction pendulum's
    parameters by their declared names, a contradiction refused naming them."""
    b = read_building(_written(tmp_path, "[isolator]\nlaw = \"triple_friction_pendulum\"\n"
                                         "L1 = 0.3\nL2 = 2.0\nL3 = 2.0\nd1 = 0.05\nd2 = 0.3\n"
                                         "d3 = 0.3\nmu1 = 0.02\nmu2 = 0.04\nmu3 = 0.08\n"))
    assert b == engine.Building(isolator=engine.Isolator.triple_friction_pendulum(
        L1=0.3, L2=2.0, L3=2.0, d1=0.05, d2=0.3, d3=0.3, mu1=0.02, mu2=0.04, mu3=0.08))
    assert b.isolation_zeta == 0.0
    with pytest.raises(BuildingError, match="mu1 <= mu2 <= mu3"):
        read_building(_written(tmp_path, "[isolator]\nlaw = \"triple_friction_pendulum\"\n"
                                         "L1 = 0.3\nL2 = 2.0\nL3 = 2.0\nd1 = 0.05\nd2 = 0.3\n"
                                         "d3 = 0.3\nmu1 = 0.05\nmu2 = 0.04\nmu3 = 0.08\n"))


def _written(folder, text):
    path = folder / "x.toml"
    path.write_text(text)
    return path
