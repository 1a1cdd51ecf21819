"""The superstructure's lateral system, declared once: what ASCE 7-22 Table 12.2-1 gives the
designer of it (R, Omega_0) and what the story model needs that the standard does not give
(the story's yield drift ratio, the deteriorating backbone's plastic and post-capping drift
ratios), read by the superstructure's design (superstructure.py), the studies'
--lateral-system and the archives.

A system's stories are designed as an engineer proportions them: each story's strength
Omega_0 times its design shear (the overstrength a designed frame of that system has, taken
as the standard's factor: FEMA P695 would measure it by pushover), its stiffness that strength
over the system's yield drift (the drift ratio at which such a story yields), so that stiffness
and strength agree; the fixed-base period and the forces' vertical distribution then follow
from those stiffnesses (superstructure.py iterates them to a fixed point).

What is and is not checked: R and Omega_0 are Table 12.2-1's for the rows named (from memory
of the 2022 table; the text was not at hand: not checked against it). The yield drifts and the
backbone's drift ratios are stated choices, typical of the literature cited beside each, not
values of the standard, and not checked against their sources' tables.
"""
from __future__ import annotations

from dataclasses import dataclass

R_I_CAP = 2.0
"""The largest R_I: 3/8 R, at most 2 (ASCE 7-22 17.5.4.2)."""


@dataclass(frozen=True)
class LateralSystem:
    """A lateral system: name (the --lateral-system choice), title, table_row (where ASCE 7-22
    Table 12.2-1 lists it; empty for the building's own stories), r (R; NaN where the system
    is not one of the table's), omega_0 (its overstrength factor, the story strength over the
    design shear), yield_drift_ratio (drift / story height at which a story yields; None: the
    building's own story stiffnesses kept), plastic_drift_ratio and post_capping_drift_ratio
    (theta_p / h and theta_pc / h of the deteriorating story law's backbone), source (where
    the stated values come from)."""

    name: str
    title: str
    table_row: str
    r: float
    omega_0: float
    yield_drift_ratio: float | None
    plastic_drift_ratio: float
    post_capping_drift_ratio: float
    source: str

    @property
    def r_i(self) -> float:
        """The largest R_I the system allows: 3/8 R, at most 2 (ASCE 7-22 17.5.4.2); 2 for
        the building's own stories (R not known)."""
        return R_I_CAP if self.r != self.r else min(3.0 * self.r / 8.0, R_I_CAP)

    def attributes(self) -> dict:
        """The archive's record of the system (SI; a yield drift ratio of NaN: the building's
        own stiffnesses)."""
        return {"lateral_system": self.name, "lateral_system_title": self.title,
                "lateral_system_table_row": self.table_row or "none",
                "lateral_system_R": self.r, "lateral_system_omega_0": self.omega_0,
                "story_yield_drift_ratio": float("nan") if self.yield_drift_ratio is None
                else self.yield_drift_ratio,
                "story_plastic_drift_ratio": self.plastic_drift_ratio,
                "story_post_capping_drift_ratio": self.post_capping_drift_ratio,
                "lateral_system_source": self.source}


_MOMENT_FRAME_BACKBONE = "theta_p 0.025 h and theta_pc 0.10 h: a steel moment frame's story " \
    "capping at about 3% drift (stated choices after Lignos & Krawinkler 2011's beams, " \
    "not checked)"

SYSTEMS = {system.name: system for system in (
    LateralSystem(
        "given", "the building's own story stiffnesses", "", float("nan"), 2.0, None, 0.025,
        0.10, "the building's stiffnesses; overstrength 2 (a stated choice, a steel SCBF's "
        "Omega_0) and " + _MOMENT_FRAME_BACKBONE),
    LateralSystem(
        "steel-smf", "steel special moment frames",
        "ASCE 7-22 Table 12.2-1 C.1 (R 8, Omega_0 3, C_d 5.5)", 8.0, 3.0, 0.01, 0.025, 0.10,
        "yield drift 1% of the height (a stated choice: the story yield drift of steel moment "
        "frame archetypes' pushovers, FEMA P695 / NIST GCR 10-917-8, not checked); "
        + _MOMENT_FRAME_BACKBONE),
    LateralSystem(
        "steel-scbf", "steel special concentrically braced frames",
        "ASCE 7-22 Table 12.2-1 B.2 (R 6, Omega_0 2, C_d 5)", 6.0, 2.0, 0.004, 0.01, 0.03,
        "yield drift 0.4% of the height, the drift at which a brace buckles; theta_p 0.01 h "
        "and theta_pc 0.03 h, the braces fracturing at 2-4% drift (stated choices after "
        "NIST GCR 13-917-24 and Hsiao, Lehman & Roeder 2013, not checked)"),
)}
"""The systems by name: the building's own stories (the default: its stiffnesses kept) and
two steel systems of ASCE 7-22 Table 12.2-1 whose stiffness follows their strength."""
DEFAULT = "given"


def system(name: str) -> LateralSystem:
    """The system called `name` (ValueError naming the choices otherwise)."""
    try:
        return SYSTEMS[name]
    except KeyError:
        raise ValueError(f"unknown lateral system {name!r}; choose one of "
                         f"{', '.join(SYSTEMS)}") from None
