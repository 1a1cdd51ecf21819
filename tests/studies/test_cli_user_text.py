"""What a user reads (issue 30): the bumpers command named as typed, help texts with units in
the paper's spelling and no internal references. (The program named as it was run:
tests/studies/common/test_program.py; the progress line:
tests/pipeline/test_progress.py.)"""
from __future__ import annotations

from engine.parameters import unit_text, user_text
from studies import cli

INTERNAL = ("SPEC", "tests/", "../shared", "^(-")
"""What no help text may show: the project's specification, test files, shared folders, and
units in UDUNITS' spelling of a fractional power (N m^(-1.5): the paper writes N/m^1.5)."""


SLIPS = ("%%", "(default: )", "paper beyond the paper", "force=True")
"""What no help text may show either: a percent sign doubled outside argparse's formatting, an
empty default, a study beyond the paper called the paper's, a Python keyword argument."""


def _help(capsys, *argv: str) -> str:
    assert cli.main(list(argv)) == 0
    return capsys.readouterr().out


def test_bumpers_names_the_command_as_typed(capsys):
    assert _help(capsys, "sweep", "--help").startswith("usage: bumpers sweep")
    assert _help(capsys, "gap_size", "--help").startswith("usage: bumpers gap_size")
    assert cli.main(["sweep", "--bogus"]) == 2
    assert capsys.readouterr().err.startswith("bumpers sweep: error:")
    # the name holds while bumpers runs the command only
    assert cli.program("studies.sweep") == "python -m studies.sweep"


def test_no_help_text_shows_internal_references_or_raw_units(capsys):
    texts = {"bumpers": _help(capsys, "--help")}
    for command in cli.commands():
        texts[command.name] = _help(capsys, command.name, "--help")
    for name, text in texts.items():
        found = [word for word in INTERNAL + SLIPS if word in text]
        assert not found, f"bumpers {name} --help shows {found}"
    sweep = texts["sweep"]
    assert "N/m^1.5" in sweep and "N m-1" not in sweep and "N/m," in sweep
    assert "N/m^1.5, N/m^1.5" not in sweep  # a unit said once


def test_units_in_the_papers_spelling():
    assert unit_text("N m-1") == "N/m"
    assert unit_text("N m^(-1.5)") == "N/m^1.5"
    assert unit_text("m s-2") == "m/s^2"
    assert unit_text("s m-1") == "s/m"
    assert unit_text("1") == "" and unit_text("kN/mm") == "kN/mm"
    assert user_text("stiffness beta, N m^(-1.5)") == "stiffness beta, N/m^1.5"
    # words and record names are not units
    for text in ("RSN<n>:H1, A.AT2+B.AT2", "ASCE 7-22 ch. 17, Figs. 9-13", "16-84% band"):
        assert user_text(text) == text


def test_internal_references_in_plain_words():
    assert user_text("against an immovable wall (SPEC decision)") == \
        "against an immovable wall (a value chosen here: the paper does not state it)"
    assert user_text("SPEC section 1") == ""  # a reference to it alone: dropped
    assert user_text("(halving it moves no peak by 0.5%; tests/engine/test_x.py): peaks") == \
        "(halving it moves no peak by 0.5%): peaks"
    assert user_text("Eq. 11") == "Eq. 11" and user_text("ASCE 7-22 17.3") == "ASCE 7-22 17.3"


def test_bumpers_records_names_itself_so(capsys):
    assert cli.main(["records", "--help"]) == 0
    assert capsys.readouterr().out.startswith("usage: bumpers records")
    import os

    assert "BUMPERS_PROGRAM" not in os.environ  # set only while the command runs
