"""tools/variables_page.py and docs/variables.md: the page is what the declarations write, and
it names every variable a sweep's archive holds, with the archive's own unit."""
import importlib.util
import re
from pathlib import Path

import pipeline
from tests.pipeline.small_sweep import RECORDS, SMALL

PROJECT = Path(__file__).resolve().parents[1]
spec = importlib.util.spec_from_file_location("variables_page",
                                              PROJECT / "tools" / "variables_page.py")
variables_page = importlib.util.module_from_spec(spec)
spec.loader.exec_module(variables_page)


def test_the_page_is_what_the_declarations_write():
    assert (PROJECT / "docs" / "variables.md").read_text() == variables_page.page(), \
        "docs/variables.md: run python tools/variables_page.py --write"


def test_the_page_names_every_variable_of_a_sweep_with_its_unit():
    ds = pipeline.sweep(RECORDS[:1], **SMALL, baseline=True, unconstrained=True, quiet=True)
    listed = dict(re.findall(r"^\| `(\w+)` \| `([^`]*)` \|", variables_page.page(), re.M))
    for name, variable in ds.data_vars.items():
        own = re.sub(r"^(baseline|unconstrained)_", "", name)
        assert own in listed, f"{name} is not on docs/variables.md"
        assert variable.attrs["units"] == listed[own], name
    for name in SMALL:
        if name in ds.coords and name != "dt":
            assert ds[name].attrs["units"] == listed[name], name
