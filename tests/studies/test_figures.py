"""Figures read right without the paper: record labels join the paper's names to the keys the
command line and the archives use (and show a scale factor), restitution's legend shows the
line styles the lines are drawn with, gap_size's caption says what is plotted; and figures a
journal would print (issue 30): a one-line title at most (the rest in the recipe's
caption(ds), kept as the archive's figure_caption), panel letters on every multi-panel
figure, one y-scale across the panels compared. Each figure is drawn from a small Dataset
built here (no simulation), and checked through its artists. A group file (TESTED_IN of
tests/test_layout.py): several recipes' figures, and the drawing helpers they share
(studies.common.plot, studies.common.peaks_vs_gap)."""
from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from engine import Building
from engine.units import CM, G
from pipeline.provenance import building_attributes
from studies import gap_size, practical_example, restitution, thickness
from studies.common.plot import PANEL_LETTER_GID, plt, record_label

SCALED = "San Fernando 1971 (pacoima) \u00d71.5"  # the label of pacoima*1.5


@pytest.fixture(autouse=True)
def close_figures():
    yield
    plt.close("all")


def records(names, scales=None, found_in=None) -> dict:
    """Record coordinates as an archive has them: name, scale factor, where it came from."""
    scales = [1.0] * len(names) if scales is None else scales
    found_in = ["library"] * len(names) if found_in is None else found_in
    return {"record": ("record", names), "record_scale": ("record", scales),
            "record_found_in": ("record", found_in)}


def levels(n_stories: int = 4) -> dict:
    return {"floor": ("floor", np.arange(n_stories + 1)),
            "story": ("story", np.arange(1, n_stories + 1))}


def peaks(dims: tuple[str, ...], sizes: dict, seed: int) -> tuple:
    """Distinct positive values over `dims`, as an xarray (dims, values) pair."""
    rng = np.random.default_rng(seed)
    return dims, 1.0 + rng.random([sizes[d] for d in dims])


# --------------------------------------------------------------------------- record labels


def test_record_label_joins_the_paper_name_and_the_key():
    ds = xr.Dataset(coords=records(["kobe", "pacoima", "Kobe-NishiAkashi-000"]))
    assert [record_label(ds, r) for r in ds.record.values.tolist()] == [
        "Kobe 1995 (kobe)", "San Fernando 1971 (pacoima)", "Kobe-NishiAkashi-000"]


def test_record_label_shows_the_scale_factor():
    ds = xr.Dataset(coords=records(["pacoima*1.5", "Kobe-NishiAkashi-000*2"], [1.5, 2.0]))
    assert record_label(ds, "pacoima*1.5") == SCALED
    assert record_label(ds, "Kobe-NishiAkashi-000*2") == "Kobe-NishiAkashi-000 \u00d72"
    # an archive without record_scale: the factor read from the name
    bare = xr.Dataset(coords={"record": ("record", ["pacoima*1.5"])})
    assert record_label(bare, "pacoima*1.5") == SCALED
    # a factor every record shares, stored without the record dimension (concat_records)
    shared = xr.Dataset(coords={"record": ("record", ["kobe*1.5", "pacoima*1.5"]),
                                "record_scale": 1.5, "record_found_in": "library"})
    assert record_label(shared, "pacoima*1.5") == SCALED


def test_record_label_names_a_stand_in():
    ds = xr.Dataset(coords=records(["kobe*1.5"], [1.5], ["stand-in"]),
                    attrs={"records": '[{"name": "kobe*1.5", '
                                      '"record_name": "Kobe-NishiAkashi-000*1.5"}]'})
    assert record_label(ds, "kobe*1.5") == \
        "Kobe 1995 (kobe) \u00d71.5\n[stand-in: Kobe-NishiAkashi-000*1.5]"


def test_peaks_vs_gap_columns_are_titled_with_key_and_factor():
    """Figs. 16-21 (thickness, strain, n_bumpers, wall_stiffness share the figure)."""
    names = ["sylmar_converter", "pacoima*1.5"]
    sizes = {"record": 2, "gap": 2, "thickness": 3, "floor": 5, "story": 4}
    ds = xr.Dataset(
        {"peak_total_accel": peaks(("record", "gap", "thickness", "floor"), sizes, 1),
         "baseline_peak_total_accel": peaks(("record", "gap", "floor"), sizes, 2),
         "peak_interstory_drift": peaks(("record", "gap", "thickness", "story"), sizes, 3),
         "baseline_peak_interstory_drift": peaks(("record", "gap", "story"), sizes, 4)},
        coords={**records(names, [1.0, 1.5]), **levels(), "gap": ("gap", [0.15, 0.25]),
                "thickness": ("thickness", [0.03, 0.05, 0.08])})
    fig = thickness.plot(ds)
    titles = [ax.get_title() for ax in fig.axes if ax.get_title()]
    assert titles == ["Northridge 1994 (sylmar_converter)", SCALED]


def test_practical_example_peaks_title_keeps_key_and_factor():
    """Figs. 12-13's title used to cut the label at its first parenthesis."""
    sizes = {"record": 1, "configuration": 3, "floor": 5, "story": 4}
    ds = xr.Dataset(
        {"peak_total_accel": peaks(("record", "configuration", "floor"), sizes, 5),
         "peak_interstory_drift": peaks(("record", "configuration", "story"), sizes, 6)},
        coords={**records(["pacoima*1.5"], [1.5]), **levels(),
                "configuration": ("configuration", list(practical_example.CONFIG_LABELS))})
    fig, (ax_accel, ax_drift) = plt.subplots(1, 2)
    practical_example._plot_peaks(ax_accel, ax_drift, ds, "pacoima*1.5", fig_number=13)
    assert ax_accel.get_title(loc="left") == f"Fig. 13: {SCALED}"


# --------------------------------------------------------------------------- gap_size


def gap_size_dataset(building=None) -> xr.Dataset:
    """What gap_size.plot reads: amplifications per record, gap and level, the bumpers, the
    building's attributes."""
    sizes = {"record": 2, "gap": 3, "floor": 5, "story": 4}
    return xr.Dataset(
        {"amplification_total_accel": peaks(("record", "gap", "floor"), sizes, 7),
         "amplification_interstory_drift": peaks(("record", "gap", "story"), sizes, 8)},
        coords={**records(["kobe", "pacoima*1.5"], [1.0, 1.5]), **levels(),
                "gap": ("gap", [0.15, 0.25, 0.35]), "thickness": 0.05, "n_bumpers": 4},
        attrs=building_attributes(building or Building()))


def test_gap_size_caption_says_what_is_plotted():
    ds = gap_size_dataset()
    gap_size.plot(ds)
    title = ds.attrs["figure_caption"]  # stored by plot, so a new archive keeps it
    assert title == gap_size.caption(ds)
    flat = " ".join(title.split())
    for part in ("Amplification by rubber bumpers", "peak floor accelerations (top)",
                 "interstory deflections (bottom)", "against the seismic gap",
                 "4 bumpers of 5 cm per side", "bare moat wall",
                 "the paper's 4-story isolated building", "2 records (legend)",
                 "paper Figs. 14-15"):
        assert part in flat, part
    assert not title.startswith("Figs.")  # the figure number is a subtitle, not the title


def test_gap_size_caption_names_another_building():
    taller = Building(masses=(500e3, 400e3, 400e3, 400e3, 300e3))
    flat = " ".join(gap_size.caption(gap_size_dataset(taller)).split())
    assert "an isolated building of 4 stories (--building)" in flat and "paper's" not in flat


def test_gap_size_legend_names_records_by_label_key_and_factor():
    fig = gap_size.plot(gap_size_dataset())
    (legend,) = [ax.get_legend() for ax in fig.axes if ax.get_legend() is not None]
    assert [t.get_text() for t in legend.get_texts()] == ["Kobe 1995 (kobe)", SCALED]


# --------------------------------------------------------------------------- restitution


@pytest.fixture
def restitution_figure():
    sizes = {"record": 1, "gap": 2, "cor": 3, "floor": 5, "story": 4}
    ds = xr.Dataset(
        {"peak_total_accel": peaks(("record", "gap", "cor", "floor"), sizes, 9),
         "peak_interstory_drift": peaks(("record", "gap", "cor", "story"), sizes, 10)},
        coords={**records(["sylmar_converter"]), **levels(), "gap": ("gap", [0.285, 0.295]),
                "cor": ("cor", [0.3, 0.6, 1.0]), "thickness": 0.05,
                "gap_source": ("gap", ["the paper's", "0.9 x unconstrained peak"])})
    return ds, restitution.plot(ds)


def legend_entries(fig) -> list[tuple[str, object]]:
    """(text, handle) of every legend of the figure, its axes' and its own."""
    legends = [ax.get_legend() for ax in fig.axes if ax.get_legend() is not None]
    return [(text.get_text(), handle) for legend in [*legends, *fig.legends]
            for text, handle in zip(legend.get_texts(), legend.legend_handles, strict=True)]


def style(line) -> tuple:
    return line.get_linestyle(), line.get_marker()


def test_restitution_legend_shows_each_gaps_line_style(restitution_figure):
    ds, fig = restitution_figure
    entries = legend_entries(fig)
    for gap in ds.gap.values:
        # the lines drawn for this gap, told by their data
        values = [ds.peak_total_accel.sel(gap=gap, floor=f).values.ravel() / G
                  for f in ds.floor.values]
        drawn = {style(line) for line in fig.axes[0].lines
                 if any(np.allclose(line.get_ydata(), v) for v in values)}
        assert len(drawn) == 1, f"gap {gap}: drawn in several styles {drawn}"
        shown = [style(handle) for text, handle in entries if f"{gap / CM:.1f} cm" in text]
        assert shown == list(drawn), f"gap {gap}: legend {shown}, lines {drawn}"


def test_restitution_level_entries_match_their_lines(restitution_figure):
    _, fig = restitution_figure
    for ax in fig.axes:
        legend = ax.get_legend()
        for text, handle in zip(legend.get_texts(), legend.legend_handles, strict=True):
            (line,) = [line for line in ax.lines if line.get_label() == text.get_text()]
            assert style(handle) == style(line) and handle.get_color() == line.get_color()


# --------------------------------------------------------------------------- issue 30


def thickness_dataset() -> xr.Dataset:
    sizes = {"record": 2, "gap": 2, "thickness": 3, "floor": 5, "story": 4}
    return xr.Dataset(
        {"peak_total_accel": peaks(("record", "gap", "thickness", "floor"), sizes, 1),
         "baseline_peak_total_accel": peaks(("record", "gap", "floor"), sizes, 2),
         "peak_interstory_drift": peaks(("record", "gap", "thickness", "story"), sizes, 3),
         "baseline_peak_interstory_drift": peaks(("record", "gap", "story"), sizes, 4)},
        coords={**records(["kobe", "pacoima*1.5"], [1.0, 1.5]), **levels(),
                "gap": ("gap", [0.15, 0.25]), "thickness": ("thickness", [0.03, 0.05, 0.08])})


def figures():
    """(name, module, Dataset) of the figures drawn here."""
    restitution_ds = xr.Dataset(
        {"peak_total_accel": peaks(("record", "gap", "cor", "floor"),
                                   {"record": 1, "gap": 2, "cor": 3, "floor": 5}, 9),
         "peak_interstory_drift": peaks(("record", "gap", "cor", "story"),
                                        {"record": 1, "gap": 2, "cor": 3, "story": 4}, 10)},
        coords={**records(["sylmar_converter"]), **levels(), "gap": ("gap", [0.285, 0.295]),
                "cor": ("cor", [0.3, 0.6, 1.0]), "thickness": 0.05,
                "gap_source": ("gap", ["the paper's", "0.9 x unconstrained peak"])})
    return [("gap_size", gap_size, gap_size_dataset()),
            ("thickness", thickness, thickness_dataset()),
            ("restitution", restitution, restitution_ds)]


def letters(ax) -> list[str]:
    return [t.get_text() for t in ax.texts if t.get_gid() == PANEL_LETTER_GID]


@pytest.mark.parametrize("name", ["gap_size", "thickness", "restitution"])
def test_a_figure_has_a_one_line_title_and_its_caption_apart(name):
    (module, ds), = [(m, d) for n, m, d in figures() if n == name]
    fig = module.plot(ds)
    title = fig._suptitle.get_text() if fig._suptitle is not None else ""
    assert "\n" not in title and len(title) <= 100, title
    assert ds.attrs["figure_caption"] == module.caption(ds)
    assert len(module.caption(ds)) > len(title)  # the long text went to the caption


@pytest.mark.parametrize("name", ["gap_size", "thickness", "restitution"])
def test_every_panel_of_a_multi_panel_figure_has_its_letter(name):
    (module, ds), = [(m, d) for n, m, d in figures() if n == name]
    fig = module.plot(ds)
    panels = [ax for ax in fig.axes if ax.axison]
    assert len(panels) > 1
    found = [letters(ax) for ax in panels]
    assert all(len(f) == 1 for f in found), found
    assert [f[0] for f in found] == [f"({chr(ord('a') + i)})" for i in range(len(panels))]


def test_gap_size_compared_panels_share_their_y_limits():
    """Each row (floors; stories) shows one quantity: its panels on one scale."""
    fig = gap_size.plot(gap_size_dataset())
    axes = np.array(fig.axes).reshape(2, 5)
    fig.canvas.draw()
    for row in (axes[0], axes[1, :4]):
        limits = {ax.get_ylim() for ax in row}
        assert len(limits) == 1, limits


def test_peaks_vs_gap_rows_share_their_y_limits_over_every_record():
    """A row's shared scale covers every record's lines, not only the first column's."""
    ds = thickness_dataset()
    ds["peak_total_accel"].loc[{"record": "pacoima*1.5"}] *= 10  # the second column larger
    fig = thickness.plot(ds)
    fig.canvas.draw()
    first, second = fig.axes[0], fig.axes[1]
    assert first.get_ylim() == second.get_ylim()
    assert second.get_ylim()[1] >= float(ds.peak_total_accel.max()) / G
