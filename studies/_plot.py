"""Shared figure style: labels, print-size fonts, PNG + PDF output (figures use the paper's
cm, g and kN: engine.units)."""
from __future__ import annotations

import json
from pathlib import Path

import matplotlib
import numpy as np

matplotlib.use("Agg")  # recipes draw files, never windows
import matplotlib.pyplot as plt  # noqa: E402

from pipeline.records import paper_label  # noqa: E402


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
    """Readable name of a record coordinate value; a stand-in names the record used."""
    label = paper_label(record)
    if ds.attrs.get(f"record_{record}_found_in") == "stand-in":
        used = {r["name"]: r.get("record_name", "?") for r in json.loads(ds.attrs["records"])}
        label += f"\n[stand-in: {used.get(record, '?')}]"
    return label


def save_figure(fig, stem: Path) -> list[Path]:
    """Write stem.png and stem.pdf; return the paths."""
    paths = [Path(f"{stem}.png"), Path(f"{stem}.pdf")]
    for path in paths:
        fig.savefig(path)
    plt.close(fig)
    return paths
