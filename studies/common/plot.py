"""Shared figure style: labels, print-size fonts, PNG + PDF output (figures use the paper's
cm, g and kN: engine.units)."""
from __future__ import annotations

import json
import re

import matplotlib
import numpy as np

matplotlib.use("Agg")  # recipes draw files, never windows
import matplotlib.pyplot as plt  # noqa: E402

from pipeline.records import PAPER_KEYS, paper_label  # noqa: E402


def ordinal(n: int) -> str:
    """'1st', '2nd', '3rd', '4th', ..., '11th', '21st'."""
    suffix = "th" if 10 <= n % 100 <= 20 else {1: "st", 2: "nd", 3: "rd"}.get(n % 10, "th")
    return f"{n}{suffix}"


def floor_labels(n_levels: int) -> list[str]:
    """Labels of levels 0..n_levels-1: the base (isolation level), the floors, the roof."""
    return (["Base (isolation level)"] + [f"{ordinal(i)} floor" for i in range(1, n_levels - 1)]
            + ["Roof"])


def shown(count: int, panels: int) -> list[int]:
    """Positions 0..count-1 a figure with `panels` panels shows: all when they fit, else the
    first, the last and evenly spread ones between (the base and the roof always)."""
    if count <= panels:
        return list(range(count))
    return sorted({int(round(x)) for x in np.linspace(0, count - 1, panels)})


def story_labels(n_stories: int) -> list[str]:
    """Labels of stories 1..n_stories."""
    return [f"{ordinal(i)} story" for i in range(1, n_stories + 1)]

plt.rcParams.update({
    "font.size": 8, "axes.titlesize": 8, "axes.labelsize": 8, "legend.fontsize": 7,
    "xtick.labelsize": 7, "ytick.labelsize": 7, "lines.linewidth": 1.2, "lines.markersize": 3,
    "axes.grid": True, "grid.alpha": 0.3, "figure.dpi": 100, "savefig.dpi": 200,
    "savefig.bbox": "tight",
})


def record_label(ds, record: str) -> str:
    """Readable name of a record coordinate value that also shows the key the command line and
    the archive use: "San Fernando 1971 (pacoima)"; a scaled record with its factor
    ("San Fernando 1971 (pacoima) ×1.5"); a stand-in names the record used, on a second
    line."""
    label = key_label(record.split("*")[0]) + scale_text(record_scale(ds, record))
    if found_in(ds, record) == "stand-in":
        used = {r["name"]: r.get("record_name", "?") for r in json.loads(ds.attrs["records"])}
        label += f"\n[stand-in: {used.get(record, '?')}]"
    return label


def key_label(key: str) -> str:
    """A paper record's event and year with its key ("Kobe 1995 (kobe)"); any other record's
    name (a library name, which is its key) as is."""
    if key not in PAPER_KEYS:
        return key
    # paper_label reads "Event Year (station component)"; the key names the station already
    return f"{paper_label(key).split(' (')[0]} ({key})"


def record_scale(ds, record: str) -> float:
    """The factor a record was scaled by: the archive's record_scale, else the ``*factor``
    parts of its name (``pacoima*1.5``), else 1."""
    if "record_scale" in ds:
        return float(per_record(ds, "record_scale", record))
    scale = 1.0
    for factor in record.split("*")[1:]:
        try:
            scale *= float(factor)
        except ValueError:  # not a factor after all: a name with a '*' in it
            return 1.0
    return scale


def per_record(ds, name: str, record: str):
    """A record's value of a record coordinate; one stored without the record dimension is
    every record's (pipeline.histories.concat_records keeps values all records share so)."""
    value = ds[name]
    return value.sel(record=record) if "record" in value.dims else value


def scale_text(scale: float) -> str:
    """The suffix that marks a scaled record (" ×1.5"); "" for an unscaled one."""
    return "" if scale == 1 else f" ×{scale:g}"


def found_in(ds, record: str) -> str | None:
    """Where a record came from (records_dir, built-in, library, stand-in, given), from the
    archive's record_found_in coordinate or its record_<name>_found_in attribute."""
    if "record_found_in" in ds:
        return str(per_record(ds, "record_found_in", record).values)
    # attribute names keep letters, digits and '_' only (pipeline.provenance)
    return ds.attrs.get(f"record_{re.sub(r'[^A-Za-z0-9_]', '_', record)}_found_in")


def building_text(ds) -> str:
    """Which building an archive ran: "the paper's 4-story isolated building", or "an
    isolated building of 8 stories (--building)" when its building_* attributes are not the
    paper's."""
    n = ds.sizes.get("story", len(np.atleast_1d(ds.attrs.get("building_masses", []))) - 1)
    return (f"the paper's {n}-story isolated building" if is_paper_building(ds)
            else f"an isolated building of {n} stories (--building)")


def is_paper_building(ds) -> bool:
    """Whether every building_* attribute of an archive is the paper's building's."""
    from engine import Building
    from pipeline.provenance import building_attributes

    for name, value in building_attributes(Building()).items():
        stored = ds.attrs.get(name)
        if isinstance(value, str) or isinstance(stored, str):
            same = stored == value
        else:
            same = stored is not None and np.array_equal(np.asarray(stored), np.asarray(value))
        if not same:
            return False
    return True


def records_text(n: int) -> str:
    """'1 record' or '4 records'."""
    return f"{n} record{'' if n == 1 else 's'}"


PANEL_LETTER_GID = "panel-letter"
"""The gid of the panel letters letter_panels draws (tests find them by it)."""


def letter_panels(axes, start: int = 0) -> None:
    """Panel letters (a), (b), ... at the top left of each visible axes, outside the frame,
    row by row (an axes switched off, as a legend holder, gets none)."""
    shown = [ax for ax in np.ravel(axes) if ax.axison]
    for i, ax in enumerate(shown, start=start):
        ax.annotate(f"({chr(ord('a') + i)})", xy=(0, 1), xycoords="axes fraction",
                    xytext=(-3, 4), textcoords="offset points", ha="right", va="bottom",
                    fontsize=9, fontweight="bold", gid=PANEL_LETTER_GID)


def short_title(fig, text: str) -> None:
    """A figure's one-line title (the long text belongs in the caption: `caption(ds)` of
    the recipe module, stored as the archive's figure_caption by store_caption)."""
    if "\n" in text:
        raise ValueError(f"a figure title is one line: {text!r}")
    fig.suptitle(text, fontsize=9)


def store_caption(ds, text: str) -> str:
    """Keep a figure's caption with its archive: the attribute figure_caption (a recipe's
    plot runs before a new archive is written, so it is saved with it; a --replot leaves the
    archive as it was). Returns the text."""
    ds.attrs["figure_caption"] = text
    return text
