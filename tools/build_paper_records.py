"""Build pipeline/data/paper_records.nc: the paper's two records that no package ships.

Kobe 1995 KJMA 000 (RSN 1106) and Northridge 1994 Sylmar Converter Sta 142 (RSN 1084) are
read from their PEER AT2 files with ``pipeline.records.read_at2`` and stored as numbers only:
the samples in g exactly as parsed from the files (float64, zlib-compressed, no rounding), with
CF metadata and their provenance (file name, sha256, where it was published, its licence, the
PEER attribution). The AT2 files themselves, and their text, never enter the project.

Run from the project root after ``pip install -e .``::

    python tools/build_paper_records.py                # AT2 files in ../shared/records
    python tools/build_paper_records.py --records /path/to/records --output /tmp/x.nc

The file is checked after writing: its records must equal ``read_at2`` of the AT2 files.
"""

from __future__ import annotations

import argparse
import datetime
import hashlib
import sys
from pathlib import Path

import numpy as np

from pipeline import records as R

ROOT = Path(__file__).resolve().parents[1]
SCRIPT = "tools/build_paper_records.py"

# Where each file was published, from ../shared/records/SOURCES.md; names as in NGA-West2.
CATALOGUE = {
    "kobe": {
        "file": "RSN1106_KOBE_KJM000.AT2",
        "event": "Kobe, Japan",
        "station": "KJMA",
        "event_date_utc": "1995-01-16",
        "peer_database": "PEER NGA-West2 (NGA-West2 processing)",
        "recorded_by": "JMA (Japan Meteorological Agency)",
        "attribution": "data: PEER Ground Motion Database, recorded by JMA",
        "source_repository": "GitHub ChairOfStructuralMechanicsTUM/Mechanics_Apps",
        "source_path": "Dynamic_seismic_threeDof_structure/Time_domain_signals/Kobe_new/"
                       "RSN1106_KOBE_KJM000.AT2",
        "source_commit": "62f4189fd4a2825521a13dabe3092e6abed4705c",
        "source_licence": "MIT (the licence of the repository that published the file)",
        "pga_g": 0.8342,  # SOURCES.md, parsed from the file
    },
    "sylmar_converter": {
        "file": "SCS142.AT2",
        "event": "Northridge-01",
        "station": "Sylmar - Converter Sta",
        "event_date_utc": "1994-01-17 12:31",
        "peer_database": "PEER Strong Motion Database (2000, pre-NGA; processing by DWP)",
        "recorded_by": "DWP (Los Angeles Department of Water and Power), station 74",
        "attribution": "data: PEER Ground Motion Database, recorded by DWP",
        "source_repository": "GitHub claudioperez/OpenSeesRT",
        "source_path": "EXAMPLES/WikiScripts/Bearings/SCS142.AT2",
        "source_commit": "8c148ea37827402be1ab98b5322be3e0bb4c4005",
        "source_licence": "BSD-2-Clause (the licence of the repository that published the "
                          "file)",
        "pga_g": 0.8972,
    },
}


def _read(key: str, records: Path) -> tuple[np.ndarray, dict]:
    """The samples in g as parsed, and the variable's attributes; checks them against the spec."""
    meta = CATALOGUE[key]
    spec = R.PAPER_RECORDS[key]
    path = records / meta["file"]
    rec = R.read_at2(path)
    parsed = R.parse_at2(path)
    if parsed.units != "g":
        raise SystemExit(f"{path}: values in {parsed.units}, expected g")
    values = parsed.values
    if not np.array_equal(values * R.G, rec.accel):
        raise SystemExit(f"{path}: parsed samples disagree with read_at2")
    if not spec.matches(rec.event, rec.station, rec.component):
        raise SystemExit(f"{path}: header says {rec.event}, {rec.station}, {rec.component}; "
                         f"expected {spec.title}")
    pga_g = float(np.max(np.abs(values)))
    if abs(pga_g - meta["pga_g"]) > 5e-5:
        raise SystemExit(f"{path}: PGA {pga_g:.4f} g, SOURCES.md says {meta['pga_g']} g")
    raw = path.read_bytes()
    title = f"{meta['event']} ({meta['event_date_utc'][:4]}), {meta['station']}, component " \
            f"{spec.component}"
    attrs = {
        "long_name": f"horizontal ground acceleration, {title}, in units of g "
                     f"(g = {R.G} m s-2)",
        "units": R.BUILTIN_UNITS,
        "units_note": f"UDUNITS-2 reads '{R.BUILTIN_UNITS}' as g with g = {R.G} m/s^2, the "
                      "value bumpers converts g with (pipeline.records.G); 'g' alone would be "
                      "grams there",
        "comment": "sample i is at t = i * dt s, i = 0 .. npts - 1; values exactly as in the "
                   "AT2 file (parsed to float64, stored without rounding)",
        "dt": rec.dt,
        "dt_units": "s",
        "npts": np.int32(rec.npts),
        "pga": pga_g,
        "pga_units": R.BUILTIN_UNITS,
        "rsn": np.int32(spec.rsn),
        "event": meta["event"],
        "event_date_utc": meta["event_date_utc"],
        "station": meta["station"],
        "component": spec.component,
        "peer_database": meta["peer_database"],
        "recorded_by": meta["recorded_by"],
        "attribution": meta["attribution"],
        "source_file": meta["file"],
        "source_sha256": hashlib.sha256(raw).hexdigest(),
        "source_bytes": np.int32(len(raw)),
        "source_repository": meta["source_repository"],
        "source_path": meta["source_path"],
        "source_commit": meta["source_commit"],
        "source_licence": meta["source_licence"],
        "values_sha256": R.values_sha256(values),
    }
    return values, attrs


def build(records: Path, output: Path) -> Path:
    """Write ``output`` from the AT2 files in ``records``; returns the path."""
    import xarray as xr

    now = datetime.datetime.now(datetime.timezone.utc).replace(microsecond=0).isoformat()
    ds = xr.Dataset()
    encoding = {}
    for key in R.BUILTIN_KEYS:
        values, attrs = _read(key, records)
        ds[key] = xr.DataArray(values, dims=(f"{key}_sample",), attrs=attrs)
        encoding[key] = {"dtype": "float64", "zlib": True, "complevel": 9, "shuffle": True,
                         "fletcher32": True, "_FillValue": None}
    files = " and ".join(CATALOGUE[k]["file"] for k in R.BUILTIN_KEYS)
    ds.attrs = {
        "Conventions": "CF-1.10",
        "title": "bumpers built-in ground motions: the paper's Table 1 records that no "
                 "package ships",
        "summary": "Horizontal ground acceleration of Kobe 1995 KJMA 000 (RSN 1106) and "
                   "Northridge 1994 Sylmar Converter Sta 142 (RSN 1084), one variable each, "
                   "the samples exactly as in the PEER AT2 files",
        "source": "PEER Ground Motion Database (NGA-West2; PEER Strong Motion Database); "
                  "see each variable's attribution and source_* attributes",
        "references": "PEER Ground Motion Database, Pacific Earthquake Engineering Research "
                      "Center, https://ngawest2.berkeley.edu",
        "licence_note": "The samples are PEER strong-motion data. Each file was published "
                        "in a repository under the licence given in source_licence; cite "
                        "PEER and the recording agency as in attribution",
        "date_created": now,
        "creator_script": SCRIPT,
        "history": f"{now}: built by {SCRIPT} from {files} (read with "
                   "pipeline.records.read_at2)",
    }
    output.parent.mkdir(parents=True, exist_ok=True)
    tmp = output.with_name(output.name + ".tmp")
    ds.to_netcdf(tmp, engine="netcdf4", format="NETCDF4", encoding=encoding)
    _check(tmp, records)
    tmp.replace(output)
    return output


def _check(path: Path, records: Path):
    """The written file must give back read_at2 of the AT2 files exactly."""
    built = R.read_builtin(path)
    for key in R.BUILTIN_KEYS:
        rec = R.read_at2(records / CATALOGUE[key]["file"])
        if not (np.array_equal(built[key].accel, rec.accel) and built[key].dt == rec.dt):
            raise SystemExit(f"{path}: {key} does not read back equal to {rec.source}")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python tools/build_paper_records.py",
        description="Build pipeline/data/paper_records.nc (Kobe KJMA 000, Sylmar Converter "
                    "Sta 142) from the PEER AT2 files, storing their numbers and provenance "
                    "only.")
    parser.add_argument("--records", type=Path, default=ROOT.parent / "shared" / "records",
                        help="folder with RSN1106_KOBE_KJM000.AT2 and SCS142.AT2 (default: "
                             "../shared/records relative to the project root)")
    parser.add_argument("--output", type=Path,
                        default=ROOT / "pipeline" / "data" / "paper_records.nc",
                        help="file to write (default: pipeline/data/paper_records.nc)")
    args = parser.parse_args(argv)
    missing = [CATALOGUE[k]["file"] for k in R.BUILTIN_KEYS
               if not (args.records / CATALOGUE[k]["file"]).is_file()]
    if missing:
        parser.error(f"{args.records}: missing {', '.join(missing)}")
    try:
        out = build(args.records, args.output)
    except R.RecordError as exc:
        parser.error(str(exc))
    print(f"wrote {out} ({out.stat().st_size} bytes)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
