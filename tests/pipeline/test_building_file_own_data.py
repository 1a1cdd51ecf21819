"""The user's own building (issue 30): a building of the user's height needs its story
stiffnesses and says what it takes from the paper's."""
from __future__ import annotations

import pytest

from pipeline.building_file import building_from, read_building
from pipeline.errors import BuildingError


@pytest.fixture(autouse=True)
def no_records_dir_env(monkeypatch):
    monkeypatch.delenv("BUMPERS_RECORDS_DIR", raising=False)


# --------------------------------------------------------------------------- buildings


def test_building_file_with_masses_and_no_story_stiffness_is_refused(tmp_path):
    path = tmp_path / "b.toml"
    path.write_text("masses = [400e3, 300e3, 300e3]\n")
    with pytest.raises(BuildingError) as err:
        read_building(path)
    message = str(err.value)
    assert "\n" not in message and "story_stiffness is missing" in message
    assert "N/m" in message and "2 values" in message and "600" not in message


@pytest.mark.parametrize("settings, named, not_named", [
    (["masses=320e3,320e3"], ["story_stiffness is missing", "N/m", "1 value",
                              "masses gives 2 levels"], ["600", "(600e6"]),
    (["story_stiffness=5e8,5e8"], ["masses is missing", "kg", "3 values"], ["320"]),
    (["story_height=3,3"], ["masses and story_stiffness are missing", "story_height gives 2"],
     ["600", "320"]),
])
def test_building_settings_name_only_what_was_given(settings, named, not_named):
    with pytest.raises(BuildingError) as err:
        building_from(settings)
    message = str(err.value)
    assert "\n" not in message
    for part in named:
        assert part in message, part
    for part in not_named:
        assert part not in message, part


def test_paper_values_taken_are_one_notice(capsys):
    b = building_from(["masses=400e3,300e3,300e3", "story_stiffness=8e8,6e8"])
    assert b.n_stories == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("note: --building: not given, so the paper's")
    assert "bilinear isolator k1 200e6 N/m" in err and "masses" not in err.split("paper's")[1]
    building_from(["story_stiffness=5e8,5e8,5e8,5e8"])  # the paper's height: masses noted
    assert "masses 320e3, 320e3, 320e3, 320e3, 250e3 kg" in capsys.readouterr().err
    building_from(["k1=150e6"])  # the paper's building, one isolator value changed: no note
    building_from([])
    assert capsys.readouterr().err == ""
