"""The paper's fixed choices that the recipes read, in one place.

Every value here is stated by the paper (where: in its comment), not chosen by this project.
What the paper leaves open and a recipe chooses stays in that recipe, listed in its `chosen`
text (shown in --help and stored in its archive); the model's own constants (Eq. 9's
coefficients, the rubber's K_r, n and alpha) are declared by the impact law,
engine.impact.laws.rubber_bumper, and read there.

The practical bumper coincides with the bumper law's declared defaults
(engine.impact.LAWS["bumper"].PARAMETERS: thickness, strain, n_bumpers, k_w), which the law
took from the same section 4. The recipes mean "the paper's bumper", not "whatever the law
defaults to", so they read it here; tests/studies/common/test_paper.py checks that the two agree.
"""
from __future__ import annotations

# --- The practical example's bumpers (section 4), the bumpers of Figs. 14-22 where not varied.
THICKNESS = 0.05  # m: bumper thickness t, 150 x 150 x 50 mm rubber pads (section 4)
N_BUMPERS = 4  # bumpers on each side of the slab, acting in parallel (section 4)
STRAIN = 0.8  # ultimate compressive strain eps_u: crushed past 0.8 x 5 = 4 cm (section 4, Eq. 14)
WALL_K = 1.5e9  # N/m: moat-wall stiffness k_w behind the crushed rubber, 1500 kN/mm (Eq. 14)
AREA = 0.150 * 0.150  # m^2: each pad's 150 x 150 mm face (section 4)
DELTA_U = STRAIN * THICKNESS
"""m: the crush limit of the paper's bumpers, 0.8 x 5 cm (no cavity, Eq. 14)."""

# --- The gap rule (section 4, used again in 5.6).
GAP_FRACTION = 0.9  # seismic gap = 0.9 x the peak isolator displacement without moat wall

# --- The paper's own gaps and unconstrained peaks, m.
PRACTICAL_GAPS = {"kobe": 0.15, "pacoima": 0.24}  # section 4: Kobe and San Fernando
PRACTICAL_UNCONSTRAINED = {"kobe": 0.167, "pacoima": 0.268}  # section 4: peaks without wall
RESTITUTION_GAP = 0.285  # section 5.6 (Fig. 22): Sylmar Converter's gap

# --- The parametric figures (section 5).
GAP_RANGE_CM = (15, 45)  # cm: the seismic gaps of Figs. 14-21, 15 to 45 cm (before bumpers)
FIG19_COUNTS = (4, 8, 16, 32)  # Figs. 19-20: bumpers on each side
FIG21_WALL_KS = (2.5e9, 1.5e9, 5e8)  # N/m, Fig. 21: k_w 2500, 1500 and 500 kN/mm

# --- Fig. 6: the impact test of Kajita et al. (2006) the paper simulates (section 3.4).
TEST_ROD_MASS = 300.0  # kg: each of the two colliding steel rods
TEST_PAD_THICKNESS = 0.010  # m: the rubber pad, 10 mm thick
TEST_PAD_AREA = 0.040**2  # m^2: the pad's 40 x 40 mm face
TEST_K_ST_KN_MM = 0.2  # kN/mm^n: static stiffness k_st of the test's fit (Fig. 6a)
TEST_COR = 0.45  # coefficient of restitution of the test (the bumper law's default cor too)
