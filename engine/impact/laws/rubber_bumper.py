"""The paper's nonlinear hysteretic rubber-bumper impact law (Eq. 4, 6, 9, 11, 12, 14).

Approach (delta_dot > 0), Eq. 4 and 14:
    F_A = k_imp delta^n                                 for delta < delta_u
    F_A = k_imp delta_u^n + k_w (delta - delta_u)       beyond (crushed rubber on the wall)
Restitution (delta_dot <= 0), Eq. 6:  F = F_A(delta) (1 + C_imp delta_dot), floored at 0.
Eq. 9 (SI, s/m): C_imp = 1.55 (1 - COR^2) / (COR^0.7076 m_eff^0.0025 v_imp^0.9755).
Alternative "calibrated" rule: C_imp = chi / v_imp with chi solved so that the pure power law
realises the target COR exactly (calibration.py). Either way C_imp = c_imp_coef /
v_imp^c_imp_exponent, the two constants a Contact holds.

Bumper stiffness, Eq. 11-12: k_st = A K_r / t^n, k_imp = alpha k_st, and bumpers on one side
act in parallel. With the paper's material (K_r = 55,835 kN/m^2, n = 2.65, alpha = 2.25) one
150 x 150 x 50 mm bumper gives 0.089 kN/mm^2.65.

The pad's shape (beyond the paper; issue 27, point 7). Eq. 11 makes the stress a function of
the strain alone, sigma = K_r (delta / t)^n, whatever the pad's shape: true of the pad K_r and n
were fitted on (Kajita et al. 2006, 40 x 40 x 10 mm), not of others. A bonded rubber block
compresses with the modulus E_c = E (1 + 2 k S^2): Gent & Lindley 1959 ("The compression of
bonded rubber blocks", Proc. Instn Mech. Engrs 173, 111-122) give E_c = E (1 + beta S^2) for
a block of square, circular or moderately rectangular section, beta = 2 for unfilled rubber
and somewhat less for rubber filled with carbon black; the design handbooks (Lindley,
"Engineering design with natural rubber", MRPRA; Gent, "Engineering with Rubber") write
it 1 + 2 k S^2 with a hardness-dependent factor k (k = 1: beta = 2; one such table gives k 0.54
at 65 and 0.52 at 75 Shore A for SRF-black natural rubber). S is the shape factor: loaded area
over the area free to bulge, side / (4 t) for a square pad (the law's bumpers are square: S =
sqrt(A) / (4 t)). Taken as scaling the whole power law by the same factor, the static
stiffness of a pad of shape factor S is

    k_st(S) = A K_r / t^n x (1 + 2 k S^2) / (1 + 2 k S_cal^2)              (shape_ratio)

S_cal the shape factor of the pad K_r was fitted on (`shape_factor_cal`, 1.0: Kajita's 40 x 40
x 10 mm pad) and k the rubber's factor (`shape_k`). Bulk compressibility, 1 / E_c = 1 / (E (1
+ 2 k S^2)) + 1 / B (Gent & Lindley 1959; Kelly & Konstantinidis 2011), is negligible
at these shape factors: E_c <= 5.5 E for S <= 1.5, a few MPa, against B ~ 2000 MPa.
- `shape_k` defaults to 0: no shape effect, the paper's Eq. 11 as published (as for a pad whose
  faces slip freely), so that the paper's recipes, whose pads have S 0.75 (the bumpers), 1.0
  (Kajita's test pad) and 1.25 (damping_calibration's block), keep their numbers bit for bit:
  the ratio is then 1 / 1 = 1.0 exactly. GENT_LINDLEY_K (1.0, beta = 2) is the published
  value for unfilled rubber, the one studies.design uses; the rubber of Kajita et al. is not
  characterised beyond its fit (its hardness is not given), and 1.0 is the upper end of the
  handbooks' range (about 0.5-1; a softer pad at low S, a stiffer one at high S than any
  filled rubber): UNVERIFIED for this rubber.
- Where S computes to S_cal the ratio is exactly 1.0 for any k (numerator and denominator are
  the same float): Kajita's pad (sqrt(0.04^2) / (4 x 0.01) = 1.0) keeps its 0.2 kN/mm^2.65
  whatever k.

Geometry (SPEC section 2): bumpers of thickness t are fixed to the wall, set into a cavity of
depth c_d (0 by default), so they protrude t - c_d and the clear gap is gap - (t - c_d); they
are crushed at delta_u = min(strain t, t - c_d), past which the slab bears on the wall (k_w).

Decisions where the paper is silent (each checked against an independent solution in
tests/engine/impact/test_contact.py):
- Past the crush limit, restitution damps the whole F_A, the wall term k_w (delta - delta_u)
  included: Eq. 6 multiplies F_A, and Eq. 14 defines F_A past delta_u. The realised COR then
  does not depend on crushing or k_w at all (a closed-form solve of the restitution phase
  gives the same 0.4381 for COR 0.45 at k_w 1500 and 200 kN/mm); damping the rubber term only
  would give 0.73 and 0.63.
- A contact lasts while delta > 0, not while F > 0. The law is continuous in the rate: as
  delta_dot -> 0- the restitution force tends to F_A(delta). So a slab whose restitution force
  was floored at zero (fast separation) and that turns back before delta reaches 0 reloads
  continuously through F_A (1 + C_imp delta_dot), with the same v_imp; the engine converges
  on such an event as dt shrinks.
- Grazing contacts (v_imp -> 0): C_imp grows without bound, but the restitution factor
  (1 + C_imp delta_dot) is clipped to [0, 1], so the force stays between 0 and F_A(delta):
  bounded, and dt-convergent (a 0.1 mm graze at v_imp 0.036 m/s). No floor on v_imp is needed.
"""
import numpy as np

from ...errors import EngineError
from ...layout import columns
from ...parameters import Declaration, Option, Parameter
from ..calibration import hunt_crossley_chi
from ..parameters import GAP, M_EFF

C_IMP_RULES = ("eq9", "calibrated")
EQ9_COEFFICIENT = 1.55
EQ9_COR_EXPONENT = 0.7076
EQ9_MASS_EXPONENT = 0.0025
EQ9_VELOCITY_EXPONENT = 0.9755

NAME = "bumper"
"""The law's name in Contact.of, sweeps and archives."""
ORDER = 4
"""Its place among the laws of the paper's section 2 (listings follow it)."""

PARAMETERS = Declaration(
    GAP,
    # plausible: a rubber pad thinner than 5 mm is a sheet, not a bumper (the paper's test pad
    # is 10 mm); thicker than 2 m, a block.
    Parameter("thickness", "m", "bumper thickness t", 0.05, "(0, inf)", equation="Eq. 11",
              sweep="thickness", plausible="[0.005, 2]"),
    Parameter("cavity", "m", "depth c_d of the wall cavity holding each bumper", 0.0,
              "[0, inf)", equation="section 5.3", sweep="cavity", plausible="[0, 2]"),
    Parameter("strain", "1", "ultimate compressive strain of the bumper rubber", 0.8,
              "(0, 1]", equation="Eq. 14", sweep="strain"),
    Parameter("n_bumpers", "1", "number of bumpers on each side, acting in parallel", 4,
              "[1, inf)", integer=True, equation="Eq. 12", sweep="n_bumpers"),
    Parameter("k_w", "N m-1", "moat wall stiffness k_w behind the crushed bumpers", 1.5e9,
              "(0, inf)", equation="Eq. 14", sweep="wall_k", plausible="[1e6, 1e13]"),
    # 0.45: the paper's rubber, section 3.4 (SPEC decision).
    Parameter("cor", "1", "coefficient of restitution of the bumper impacts", 0.45, "(0, 1]",
              equation="Eq. 9", sweep="cor"),
    M_EFF,
    Parameter("area", "m2", "contact area A of one bumper (150 x 150 mm)", 0.150 * 0.150,
              "(0, inf)", equation="Eq. 11"),
    Parameter("k_r", "Pa", "rubber stiffness K_r (55,835 kN/m^2, Kajita et al. static test)",
              55_835e3, "(0, inf)", equation="Eq. 11"),
    Parameter("n", "1", "exponent n of the rubber's power law", 2.65, "[1, inf)",
              equation="Eq. 4"),
    Parameter("alpha", "1", "impact-to-static stiffness ratio alpha", 2.25, "(0, inf)",
              equation="Eq. 12"),
    # 0: the paper's Eq. 11 (no shape effect); GENT_LINDLEY_K = 1 for unfilled rubber, about
    # 0.5-1 for filled ones by hardness (module docstring).
    Parameter("shape_k", "1", "Gent-Lindley factor k of the rubber's compression modulus E (1 + "
              "2 k S^2) scaling k_st with the pad's shape factor S = sqrt(A) / (4 t) (0: none, "
              "the paper's Eq. 11)", 0.0, "[0, inf)", equation="Eq. 11, Gent & Lindley 1959",
              plausible="[0, 1]"),
    Parameter("shape_factor_cal", "1", "shape factor S of the pad K_r and n were fitted on "
              "(Kajita et al.'s 40 x 40 x 10 mm: 1.0)", 1.0, "(0, inf)",
              equation="Eq. 11, Gent & Lindley 1959", plausible="[0.05, 20]"),
    Option("c_imp_rule", C_IMP_RULES, "eq9",
           "impact damping coefficient C_imp: the paper's Eq. 9, or calibrated to realise "
           "the COR exactly"),
    Parameter("c_imp", "s m-1", "a fixed C_imp instead of the rule's, the same at every "
              "impact velocity (to re-derive Eq. 9, section 3.2)", None, "(0, inf)",
              equation="Eq. 8"),
)

ROW = columns("RubberBumperRow", "k", "n", "delta_u", "k_w", "c_imp_coef", "c_imp_exponent")
"""The Contact fields force_terms reads, packed in this order into one row per member
(contact.law_rows; the NumPy loops pass a tuple of (B,) arrays, the compiled ones a row of
floats): a new constant of this law is a new name here."""


_RUBBER = {name: PARAMETERS[name].default
           for name in ("k_r", "n", "alpha", "shape_k", "shape_factor_cal")}

GENT_LINDLEY_K = 1.0
"""Gent & Lindley's (1959) factor for a bonded block of unfilled rubber, square, circular or
moderately rectangular (E_c = E (1 + 2 S^2)): the shape_k the design study uses (module
docstring; UNVERIFIED for the paper's rubber, whose hardness is not given)."""


WALL_LENGTH = 18.0
"""m: the length of moat wall one side's bumpers sit on where nothing else gives it (a planar
run has no plan; the design study's default wall): NOT the paper's, which gives no plan. Its
bumpers fit when 2 n side <= it (`most_bumpers`)."""


def most_bumpers(area, wall_length=WALL_LENGTH) -> int:
    """The most square pads of `area` (m^2, one or an array) one side's wall of `wall_length`
    (m) holds, a pad's side apart (2 n sqrt(A) <= L: the design study's rule): 60 of the
    paper's 150 mm pads on 18 m."""
    most = np.floor(wall_length / (2.0 * np.sqrt(area)) + 1e-9)
    return int(most) if np.ndim(most) == 0 else most.astype(int)


def crowded(values) -> str | None:
    """Why members' bumper counts (values["n_bumpers"]) cannot sit on a moat wall of
    WALL_LENGTH, each with its own pads (values["area"] where given and not NaN, a listed
    table's; else the declared area), or None where they fit."""
    counts = np.asarray(values.get("n_bumpers", PARAMETERS.n_bumpers.default), dtype=float)
    area = np.asarray(values.get("area", np.nan), dtype=float)
    area = np.broadcast_to(np.where(np.isnan(area), PARAMETERS.area.default, area),
                           counts.shape)
    most = most_bumpers(area)
    over = np.flatnonzero(counts > most)
    if over.size == 0:
        return None
    n, side = float(counts[over[0]]), float(np.sqrt(area[over[0]]))
    return (f"n_bumpers {n:g}: {n:g} pads of {side * 1e3:g} mm a side, a side apart, "
            f"need {2 * n * side:g} m of moat wall; a wall is taken as {WALL_LENGTH:g} m "
            f"where no plan gives it: give at most {int(most[over[0]])} bumpers a side")


def shape_factor(area, thickness):
    """Shape factor S (-) of a square pad: loaded area over the area free to bulge,
    A / (4 sqrt(A) t) = side / (4 t) (area m^2, thickness m). The paper's 150 x 150 x 50 mm
    bumper: 0.75; Kajita et al.'s 40 x 40 x 10 mm test pad: 1.0."""
    return np.sqrt(np.asarray(area, dtype=float)) / (4 * np.asarray(thickness, dtype=float))


def compression_ratio(s, shape_k=_RUBBER["shape_k"],
                      shape_factor_cal=_RUBBER["shape_factor_cal"]):
    """(1 + 2 k S^2) / (1 + 2 k S_cal^2): the compression modulus of a pad of shape factor S
    over that of the pad K_r was fitted on, S_cal (Gent & Lindley 1959; module docstring).
    Exactly 1.0 for k = 0 and for S = S_cal. Broadcast."""
    k = np.asarray(shape_k, dtype=float)
    s = np.asarray(s, dtype=float)
    return (1 + 2 * k * s**2) / (1 + 2 * k * np.asarray(shape_factor_cal, dtype=float) ** 2)


def shape_ratio(area, thickness, shape_k=_RUBBER["shape_k"],
                shape_factor_cal=_RUBBER["shape_factor_cal"]):
    """`compression_ratio` of a square pad of area A (m^2) and thickness t (m), S = sqrt(A) /
    (4 t): what its k_st is of Eq. 11's."""
    return compression_ratio(shape_factor(area, thickness), shape_k, shape_factor_cal)


def static_stiffness(area, thickness, k_r=_RUBBER["k_r"], n=_RUBBER["n"],
                     shape_k=_RUBBER["shape_k"], shape_factor_cal=_RUBBER["shape_factor_cal"]):
    """Eq. 11 with the pad's shape: k_st = A K_r / t^n x shape_ratio in N/m^n (area m^2,
    thickness m, k_r Pa; shape_k 0, the default: the paper's Eq. 11 exactly)."""
    eq11 = area * k_r / np.asarray(thickness, dtype=float) ** n
    return eq11 * shape_ratio(area, thickness, shape_k, shape_factor_cal)


def impact_stiffness(area, thickness, k_r=_RUBBER["k_r"], n=_RUBBER["n"],
                     alpha=_RUBBER["alpha"], count=1, shape_k=_RUBBER["shape_k"],
                     shape_factor_cal=_RUBBER["shape_factor_cal"]):
    """Eq. 12 for `count` identical bumpers acting in parallel: alpha * count * k_st (N/m^n)."""
    return alpha * count * static_stiffness(area, thickness, k_r, n, shape_k, shape_factor_cal)


def damping_prefactor(cor, m_eff):
    """The part of Eq. 9 that does not depend on v_imp: C_imp * v_imp^0.9755."""
    return EQ9_COEFFICIENT * (1 - cor**2) / (cor**EQ9_COR_EXPONENT * m_eff**EQ9_MASS_EXPONENT)


def damping_constants(cor, m_eff, n, rule="eq9"):
    """(c_imp_coef, c_imp_exponent) with C_imp = c_imp_coef / v_imp^c_imp_exponent for the
    chosen rule, (B,) each."""
    cor = np.asarray(cor, dtype=float)
    if rule == "eq9":
        return damping_prefactor(cor, m_eff), np.full(cor.shape, EQ9_VELOCITY_EXPONENT)
    return hunt_crossley_chi(cor, n, restitution_only=True), np.ones(cor.shape)


def _first(bad: np.ndarray, **values) -> str:
    """The values (m) by name of the first member where `bad` (B,) holds, and how many
    members it holds for: a refusal names one member's values, not a million members'."""
    i = int(np.flatnonzero(bad)[0])
    said = ", ".join(f"{name} {value[i]:g} m" for name, value in values.items())
    return said + (f" ({np.count_nonzero(bad)} of {bad.size} members)" if bad.size > 1 else "")


def contact_fields(gap, thickness, strain, n_bumpers, k_w, cor, m_eff, cavity, c_imp_rule,
                   c_imp, **pad):
    """The Contact fields of this law from its checked, broadcast (B,) parameters; `pad`: the
    pad's and its rubber's (area, k_r, n, alpha, shape_k, shape_factor_cal)."""
    n = pad["n"]
    if np.any(cavity >= thickness):
        raise EngineError("cavity must be smaller than thickness, got " + _first(
            cavity >= thickness, cavity=cavity, thickness=thickness))
    protrusion = thickness - cavity
    if np.any(protrusion >= gap):
        raise EngineError("thickness - cavity must be smaller than gap: the bumpers would "
                          "close the gap, " + _first(protrusion >= gap, gap=gap,
                                                     thickness=thickness, cavity=cavity))
    if c_imp is None:
        c_imp_coef, c_imp_exponent = damping_constants(cor, m_eff, n, c_imp_rule)
    else:
        c_imp_coef, c_imp_exponent = c_imp, 0.0
    return {"clear_gap": gap - protrusion,
            "k": impact_stiffness(pad["area"], thickness, pad["k_r"], n, pad["alpha"], n_bumpers,
                                  pad["shape_k"], pad["shape_factor_cal"]),
            "n": n, "delta_u": np.minimum(strain * thickness, protrusion), "k_w": k_w,
            "c_imp_coef": c_imp_coef, "c_imp_exponent": c_imp_exponent}


def force_terms(delta, delta_dot, v_imp, row):
    """(elastic force N, dashpot N*s/m): F_A on approach, F_A (1 + C_imp delta_dot) in
    restitution, i.e. a dashpot F_A C_imp that acts in restitution only.

    F_A of Eq. 4 and 14: k_imp min(delta, delta_u)^n + k_w max(delta - delta_u, 0), with
    row: ROW, k = k_imp (N/m^n), delta_u (m), k_w (N/m); C_imp = c_imp_coef /
    v_imp^c_imp_exponent (s/m). Scalars or (B,) arrays alike (a row of floats or a tuple of
    arrays), compiled as is by the kernel.
    """
    k, n, delta_u, k_w = row[ROW.k], row[ROW.n], row[ROW.delta_u], row[ROW.k_w]
    c_imp_coef, c_imp_exponent = row[ROW.c_imp_coef], row[ROW.c_imp_exponent]
    d = np.maximum(delta, 0.0)
    elastic = k * np.minimum(d, delta_u) ** n + k_w * np.maximum(d - delta_u, 0.0)
    c_imp = c_imp_coef / v_imp**c_imp_exponent
    return elastic, (delta_dot <= 0) * (elastic * c_imp)


def max_tangent_stiffness(p, indentation_bound):
    """The stiffer of the rubber's tangent at delta_u and the wall k_w (N/m)."""
    return np.maximum(p.n * p.k * p.delta_u ** (p.n - 1), p.k_w)
