"""tools/compare_archives.py, the check that a change of structure changed no number: equal
archives pass, a changed bit or a missing variable fails, added attributes are listed."""
import importlib.util
from pathlib import Path

import numpy as np
import xarray as xr

PROJECT = Path(__file__).resolve().parents[1]
spec = importlib.util.spec_from_file_location("compare_archives",
                                              PROJECT / "tools" / "compare_archives.py")
compare = importlib.util.module_from_spec(spec)
spec.loader.exec_module(compare)


def archive(folder: Path, values, **attrs) -> None:
    folder.mkdir(exist_ok=True)
    xr.Dataset({"x": ("n", np.asarray(values, float), {"units": "m"})},
               attrs={"date_created": str(folder), **attrs}).to_netcdf(folder / "a.nc")


def test_equal_changed_and_missing(tmp_path, capsys):
    archive(tmp_path / "before", [0.1, 0.2])
    archive(tmp_path / "same", [0.1, 0.2], provenance="added")
    archive(tmp_path / "changed", [0.1, np.nextafter(0.2, 1.0)])
    assert compare.main([str(tmp_path / "before"), str(tmp_path / "same")]) == 0
    assert "a: equal (added: @provenance)" in capsys.readouterr().out
    assert compare.main([str(tmp_path / "before"), str(tmp_path / "changed")]) == 1
    assert "x: values differ" in capsys.readouterr().out
    assert compare.main([str(tmp_path / "before"), str(tmp_path / "nowhere"), "a"]) == 1


def test_a_renamed_label_is_compared_under_its_new_name(tmp_path, capsys):
    """--renamed OLD=NEW: a label renamed on purpose (a dimension, a variable, a global
    attribute) compares its bits under the new name; a changed bit still fails."""
    before, after = tmp_path / "before", tmp_path / "after"
    archive(before, [0.1, 0.2], building_eccentricity="[0, 0]", arguments='{"x": [1]}')
    after.mkdir()
    xr.Dataset({"y": ("k", [0.1, 0.2], {"units": "m"})},
               attrs={"building_torsion_mass_offset": "[0, 0]",
                      "arguments": '{"y": [1]}'}).to_netcdf(after / "a.nc")
    assert compare.main([str(before), str(after)]) == 1
    assert "missing x" in capsys.readouterr().out
    renamed = ["--renamed", "x=y", "n=k", "building_eccentricity=building_torsion_mass_offset",
               "--renamed-text", "x=y"]
    assert compare.main([str(before), str(after), *renamed]) == 0
    assert "a: equal" in capsys.readouterr().out
    xr.Dataset({"y": ("k", [0.1, 0.3], {"units": "m"})},
               attrs={"building_torsion_mass_offset": "[0, 0]",
                      "arguments": '{"y": [1]}'}).to_netcdf(after / "a.nc")
    assert compare.main([str(before), str(after), *renamed]) == 1


def test_array_attributes_compare_by_value(tmp_path, capsys):
    """A variable's attribute may be an array (a flag variable's flag_values): equal ones
    pass, a changed one is named (it once raised NumPy's ambiguous truth value)."""
    for name, flags in (("before", [0, 1, 2]), ("same", [0, 1, 2]), ("changed", [0, 1, 3])):
        (tmp_path / name).mkdir()
        xr.Dataset({"mode": ("n", np.array([0, 2], np.int8),
                             {"flag_values": np.array(flags, np.int8)})}
                   ).to_netcdf(tmp_path / name / "a.nc")
    assert compare.main([str(tmp_path / "before"), str(tmp_path / "same")]) == 0
    assert "a: equal" in capsys.readouterr().out
    assert compare.main([str(tmp_path / "before"), str(tmp_path / "changed")]) == 1
    assert "mode: attributes flag_values differ" in capsys.readouterr().out
