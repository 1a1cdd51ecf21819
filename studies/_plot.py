"""Shared figure style: labels, print-size fonts, PNG + PDF output (figures use the paper's
cm, g and kN: engine.units)."""
from __future__ import annotations

import json
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # recipes draw files, never windows
import matplotlib.pyplot as plt  # noqa: E402

from pipeline.records import paper_label  # noqa: E402

FLOOR_LABELS = ["Base (isolation level)", "1st floor", "2nd floor", "3rd floor", "Roof"]
STORY_LABELS = ["1st story", "2nd story", "3rd story", "4th story"]

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
