"""tools/variables_page.py and docs/variables.md: the page is what the declarations write, and
it names every variable a sweep's archive holds, with the archive's own unit."""
import re

import pipeline
from tests.helpers import PROJECT
from tests.helpers import variables_page as load_page
from tests.pipeline.small_sweep import RECORDS, SMALL

variables_page = load_page()


def test_the_page_is_what_the_declarations_write():
    """The sweep's part is what the declarations write; the studies' part follows it (each
    study's test checks its archive against it: tests/helpers.assert_on_variables_page)."""
    text = (PROJECT / "docs" / "variables.md").read_text()
    studies = variables_page.studies_part(text)
    assert studies.startswith(variables_page.STUDIES_MARK), "the page lists no study"
    assert text == variables_page.page() + "\n" + studies, \
        "docs/variables.md: run python tools/variables_page.py --write"


def test_every_study_archive_is_listed():
    """Each archive a study writes has its section (the studies' tests check their content)."""
    listed = variables_page.listed_by_archive((PROJECT / "docs" / "variables.md").read_text())
    for name in ("collapse", "damping_calibration", "design", "fragility", "impact_validation",
                 "loss", "plan", "practical_example", "suite", "torsion"):
        assert f"{name}.nc" in listed, name
    assert listed["loss.nc"]["expected_annual_loss"] == "USD_2011 yr-1"


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
