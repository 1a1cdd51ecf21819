"""A lead-rubber bearing designed for a target effective period: the bilinear isolator
(engine.Isolator.bilinear) whose effective period at the design displacement is the target,
its characteristic strength a share of the weight and its elastic stiffness a multiple of its
post-yield one, its displacement capacity beyond the total maximum displacement by a stated
margin. The design the `--isolators designed-lrb` option of the studies runs
(pipeline.motions.designed_isolation settles it against the code's D_M and D_TM).

The relations (ASCE 7-22 chapter 17's effective stiffness, section 17.2; T_M at D_M, section
17.5.3): k_eff = (W / g) (2 pi / T_M)^2 at D_M, and for a bilinear backbone of characteristic
strength Q_d and post-yield stiffness K_d, k_eff = K_d + Q_d / D_M (past yield), so
K_d = k_eff - Q_d / D_M. The bearing's yield force is Q_d / (1 - K_d / K_1).

Units: SI (N, m, s); the weight W in N.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from engine.units import G

STRENGTH_RATIO = 0.06
"""Q_d / W: the characteristic strength as a share of the weight on the bearings, a stated
choice within the 3-10% of lead-rubber designs (Naeim & Kelly 1999, Design of Seismic
Isolated Structures; not checked against a manufacturer's range): about 17% of critical
damping at D_M for T_M 3 s at the default site."""
STIFFNESS_RATIO = 10.0
"""K_1 / K_d: the elastic stiffness over the post-yield one, the usual bilinear model of a
lead-rubber bearing (a stated choice after Naeim & Kelly 1999; not a measured bearing's)."""
CAPACITY_MARGIN = 0.10
"""The bearing's displacement capacity (its rubber's, where it fails) beyond D_TM: (1 + margin)
D_TM, a stated choice; ASCE 7-22 asks the bearings to be stable at D_TM (their prototype
tests, section 17.8; the clause not checked against the 2022 text)."""


@dataclass(frozen=True)
class LeadRubberDesign:
    """A lead-rubber bearing set (the building's isolators together): k1 and k2 (N/m), the
    characteristic strength q_d (N) and weight (N), capacity (m), and what it was designed
    for: target_period (s) at design_displacement D_M (m), total_displacement D_TM (m)."""

    k1: float
    k2: float
    q_d: float
    weight: float
    capacity: float
    target_period: float
    design_displacement: float
    total_displacement: float

    @property
    def yield_force(self) -> float:
        """F_y = Q_d / (1 - K_2 / K_1), N."""
        return self.q_d / (1.0 - self.k2 / self.k1)

    def isolator(self):
        """The engine.Isolator of the design (the bilinear law's constructor, its checks
        applied)."""
        import engine

        return engine.Isolator.bilinear(k1=self.k1, k2=self.k2,
                                        fy_ratio=self.yield_force / self.weight,
                                        capacity=self.capacity)

    def effective_period(self, displacement: float, g: float = G) -> float:
        """2 pi sqrt(M / k_eff) (s) at a displacement amplitude (m) past yield: k_eff =
        K_2 + Q_d / D (ASCE 7-22 section 17.2's effective stiffness on the backbone)."""
        k_eff = self.k2 + self.q_d / displacement
        return 2.0 * math.pi * math.sqrt(self.weight / g / k_eff)

    def describe(self) -> str:
        """One line: the stiffnesses, the strength, T_M at D_M, the capacity."""
        return (f"lead-rubber bearings K1 {self.k1 / 1e6:.4g} MN/m, K2 {self.k2 / 1e6:.4g} "
                f"MN/m, Q_d {self.q_d / self.weight:.3g} W: T_M "
                f"{self.effective_period(self.design_displacement):.3g} s at D_M "
                f"{self.design_displacement:.3g} m; capacity {self.capacity:.3g} m (D_TM "
                f"{self.total_displacement:.3g} m + {100 * CAPACITY_MARGIN:.0f}%)")


def design_lead_rubber(target_period: float, design_displacement: float,
                       total_displacement: float, weight: float, *,
                       strength_ratio: float = STRENGTH_RATIO,
                       stiffness_ratio: float = STIFFNESS_RATIO,
                       margin: float = CAPACITY_MARGIN, g: float = G) -> LeadRubberDesign:
    """The lead-rubber bearings (all of them, on `weight` N) with effective period
    target_period T_M (s) at design_displacement D_M (m), Q_d = strength_ratio W,
    K_1 = stiffness_ratio K_d, capacity (1 + margin) total_displacement D_TM (m). ValueError,
    in one line, where Q_d alone is stiffer than the target at D_M (K_d <= 0: a longer
    period needs a smaller strength ratio) or the bearing would not yield before D_M."""
    if not (target_period > 0 and design_displacement > 0 and weight > 0):
        raise ValueError("a lead-rubber design needs a positive period, displacement and "
                         "weight")
    q_d = strength_ratio * weight
    k_eff = weight / g * (2.0 * math.pi / target_period) ** 2
    k2 = k_eff - q_d / design_displacement
    if k2 <= 0:
        raise ValueError(f"a lead-rubber bearing of Q_d {strength_ratio:g} W is stiffer than "
                         f"T_M {target_period:g} s at D_M {design_displacement:.3g} m: target "
                         "a shorter period")
    k1 = stiffness_ratio * k2
    if q_d / (k1 - k2) >= design_displacement:
        raise ValueError(f"the lead-rubber bearing would not yield before D_M "
                         f"{design_displacement:.3g} m: target a shorter period")
    total = max(total_displacement, design_displacement)
    return LeadRubberDesign(k1, k2, q_d, weight, (1.0 + margin) * total, float(target_period),
                            float(design_displacement), float(total))
