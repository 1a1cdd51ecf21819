"""Independent model of a base-isolated shear building pounding on its moat wall, for
cross-checking the engine. A test helper, not a test file: it uses no code from ``engine/``
(only, if a test wishes, the numbers held by an ``engine.Contact``, which are input data),
nor from ``opensees_reference.py`` (the other reference). Units SI (kg, m, s, N).

What it models (SPEC sections 1 and 2, written from the SPEC, not from the engine; defaults:
the paper's building):

* Levels 0 (isolation slab) .. N (roof), 1 <= N <= 30, one horizontal DOF each with lumped
  masses m_0..m_N (default 320, 320, 320, 320, 250 t), displacements u and velocities v
  relative to the ground; story i joins level i-1 to level i with stiffness k_i (default
  600 MN/m).
* Story dashpots c_i = 2 zeta_sup k_i / omega_1 in parallel with each story (zeta_sup = 2 %,
  omega_1 the first circular frequency of the fixed-base superstructure, levels 1..N with
  level 0 held fixed).
* Yielding stories (``story_yield`` = F_1..F_N, np.inf for an elastic story; ``story_b`` = b,
  default 0.02): bilinear kinematic hardening written as its parallel-spring form, elastic
  b k_i in parallel with an elastic-perfectly-plastic spring of stiffness (1 - b) k_i and limit
  (1 - b) F_i (yield drift d_y,i = F_i / k_i). Peak story ductility = peak |drift| / d_y,i.
* Isolator ``{"kind": "bilinear", "K1", "K2", "fy_ratio"}`` (default the paper's 200 MN/m,
  25 MN/m, 0.1): K2 in parallel with an elastic-perfectly-plastic spring of stiffness K1 - K2
  that yields at (K1 - K2) u_y, u_y = Fy / K1, Fy = fy_ratio g M_tot (g = 9.81, M_tot the sum
  of all masses).
* Isolator ``{"kind": "friction_pendulum", "radius": R, "mu_slow", "mu_fast", "rate",
  "yield_disp" (default 0.5 mm), "weight" (default W = g M_tot)}``: F = (W / R) u_0 + F_f,
  F_f elastic-perfectly-plastic with the constant pre-slip stiffness k_0 = mu_fast W /
  yield_disp and the limit L(|v_0|) = mu(|v_0|) W, mu(v) = mu_fast - (mu_fast - mu_slow)
  exp(-rate |v|) (Constantinou et al. 1990), v_0 the slab's (relative) sliding velocity; the
  weight is constant (no vertical motion). The plastic spring under a moving limit is the
  limit of the return map F_f(n+1) = clip(F_f(n) + k_0 du, +-L(|v(n+1)|)) as the step goes to
  0: inside the limit F_f' = k_0 v_0; on it (F_f = s L, s = +-1)
  s F_f' = min(k_0 s v_0, L'), i.e. the force rides the limit while the limit moves slower
  than elastic loading would, and leaves it (sticks) when the limit outruns it.
* Isolation dashpot c_iso = 2 zeta_iso sqrt(k_ref M_tot), k_ref = K1 (bilinear) or
  k_0 + W / R (friction pendulum); zeta_iso 5 % (bilinear), 0 (friction pendulum).
* Ground acceleration a_g(t) linearly interpolated between record samples; total acceleration
  = relative + a_g, taken as the net force of the springs and dashpots on a level over its
  mass.
* Moat wall on both sides of level 0 at clear gap g: indentation delta = |u_0| - g on the
  side the slab moves towards; the impact velocity v_imp is the indentation rate at first
  touch, kept until the indentation returns to 0.
* Wall laws (`Wall`): the paper's rubber bumper (Eq. 4, 6, 9, 14) and Hertzdamp
  (Muthukumar & DesRoches 2006).

How it is integrated (a different scheme from the engine's central differences, and from
OpenSees' Newmark): an event-driven hybrid integration with ``scipy.integrate.solve_ivp``
(DOP853, rtol 1e-9 by default). The right-hand side is kept smooth inside every solve_ivp
call, and every place where it is not smooth ends the call exactly there:

* the record's samples (a_g is linear between them);
* every plastic spring (isolator, yielding stories) has no force state: in its elastic mode
  its force is f_a + k_p (d - d_a) from the anchor (d_a, f_a) where the mode began (d its
  deformation), in its plastic mode exactly +-limit. Events switch elastic -> plastic when
  the force reaches +-limit and plastic -> elastic when the deformation rate changes sign,
  so the force stays exactly on the yield surface;
* the friction pendulum's F_f likewise: elastic from an anchor, "slip+-" when it reaches
  +-L(|v_0|); sliding, F_f = s L(|v_0|) exactly (a smooth function of the state away from
  v_0 = 0), ended by "stop" (v_0 = 0) or "stick" (k_0 s v_0 - L' falls through 0, L' =
  dL/dt = W (mu_fast - mu_slow) rate exp(-rate |v_0|) sign(v_0) v_0', with v_0' from the
  equations of motion), both back to elastic from the force of that instant. In the elastic
  mode v_0 = 0 ends the call too (a marker, no switch): L(|v_0|) has its cusp there, and a
  slip just before it would otherwise hide inside one solver step;
* the wall contact: touch (delta = 0 rising, v_imp stored), release (delta = 0 falling), and
  inside the contact every kink of the law: the rate changing sign (approach / restitution),
  the crush limit delta_u, and the damping factor 1 + C delta' crossing 0 (the floor at zero
  force). Each branch of the law is extended smoothly past its kink; the event truncates it.

Events that one instant sets off together (u_0' = 0 both unloads the isolator and turns a
contact) are all applied; after every call the armed events are checked on the sampled grid.
solve_ivp only sees a sign change between two of its steps, so a switch crossed and crossed
back within one step (the friction pendulum's stick-slip, now and then) goes unseen: the
grid catches it, and the call is redone with steps a quarter as long (``n_retries`` counts
this), down to 1e-7 s, below which it raises an error.

Peaks are taken on a uniform grid of about `sample_dt` (0.1 ms, a divisor of the record's
step, so every record sample is on it) evaluated from the dense output, plus every event
instant. Solver steps are at most `max_step_contact` (1e-4 s) in contact; since the law's
kinks are events, that bound does not set the accuracy (Kobe, 9 impacts: 1e-4, 2.5e-4 and
1e-3 s give the same peaks to 5e-10). Own error, measured by halving the contact step and the
sampling step with rtol / 10 (Pacoima, bumper and Hertzdamp): 4e-6 at most (sampling of the
acceleration peaks); against the engine without a wall, 2e-5. The yielding stories and the
friction pendulum, measured the same way (tests/reference/test_references.py): see there.

`two_body` solves the scalar impact m_eff delta'' = -F with the same contact branches.
`friction_loop` and `story_loop` drive this module's friction pendulum and yielding story
along an imposed path (for checking them against closed forms).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp, trapezoid
from scipy.linalg import eigh

G = 9.81
MASSES = (320e3, 320e3, 320e3, 320e3, 250e3)  # kg, levels 0..4
K_STORY = 600e6  # N/m
K1 = 200e6  # N/m
K2 = 25e6  # N/m
FY_RATIO = 0.1
M_TOT = float(sum(MASSES))
F_Y = FY_RATIO * G * M_TOT  # N, characteristic strength
U_Y = F_Y / K1  # m, 7.50 mm
K_PLASTIC = K1 - K2  # N/m
F_PLASTIC_YIELD = K_PLASTIC * U_Y  # N
ZETA_B = 0.05
ZETA_S = 0.02
STORY_B = 0.02
YIELD_DISP = 5e-4  # m, the friction pendulum's pre-slip displacement
MAX_STORIES = 30


def fixed_base_omega1(masses=MASSES, story_k=K_STORY) -> float:
    """First circular frequency (rad/s) of levels 1..N with level 0 held fixed (masses
    m_0..m_N, m_0 unused; story_k: k_1..k_N or one value for all)."""
    m = np.asarray(masses, dtype=float)[1:]
    n = m.size
    ks = np.broadcast_to(np.asarray(story_k, dtype=float), (n,))
    k = np.zeros((n, n))
    for j in range(n):  # story j + 1 joins level j (fixed when j == 0) to level j + 1
        k[j, j] += ks[j]
        if j > 0:
            k[j - 1, j - 1] += ks[j]
            k[j - 1, j] -= ks[j]
            k[j, j - 1] -= ks[j]
    return float(math.sqrt(eigh(k, np.diag(m), eigvals_only=True)[0]))


OMEGA_1 = fixed_base_omega1()
C_BASE = 2 * ZETA_B * math.sqrt(K1 * M_TOT)  # N s/m, 1.749 MN s/m
C_STORY = 2 * ZETA_S * K_STORY / OMEGA_1  # N s/m


@dataclass(frozen=True)
class Building:
    """Every number of one building (made by `make_building`); arrays indexed by level
    (0..N) or by story (1..N at index 0..N-1)."""

    masses: np.ndarray  # (N + 1,) kg
    story_k: np.ndarray  # (N,) N/m
    story_c: np.ndarray  # (N,) N s/m
    story_yield: np.ndarray  # (N,) N, inf: elastic
    story_b: np.ndarray  # (N,)
    isolator: dict  # resolved: kind and its numbers
    c_iso: float  # N s/m
    omega1: float  # rad/s

    @property
    def n_levels(self) -> int:
        return self.masses.size

    @property
    def yielding(self) -> bool:
        return bool(np.any(np.isfinite(self.story_yield)))


def make_building(masses=None, story_k=None, isolator=None, story_yield=None,
                  story_b=STORY_B, zeta_iso=None, zeta_sup=ZETA_S) -> Building:
    """The building from its inputs (defaults: the paper's).

    masses: m_0..m_N kg; story_k: k_1..k_N N/m (or one value); isolator: None (the paper's
    bilinear isolator), ``{"kind": "bilinear", "K1", "K2", "fy_ratio"}`` or
    ``{"kind": "friction_pendulum", "radius", "mu_slow", "mu_fast", "rate", "yield_disp",
    "weight"}`` (see the module docstring); story_yield: F_1..F_N N (np.inf: elastic) or None;
    story_b: post-yield ratio (one value or per story); zeta_iso: default 0.05 (bilinear), 0
    (friction pendulum); zeta_sup: story damping ratio."""
    m = np.array(MASSES if masses is None else masses, dtype=float).ravel()
    n = m.size - 1
    if not 1 <= n <= MAX_STORIES or np.any(m <= 0):
        raise ValueError(f"need 2 to {MAX_STORIES + 1} positive masses, got {m}")
    k = np.broadcast_to(np.asarray(K_STORY if story_k is None else story_k, dtype=float),
                        (n,)).copy()
    if np.any(k <= 0):
        raise ValueError("story stiffnesses must be positive")
    m_tot = float(m.sum())
    iso = {"kind": "bilinear"} if isolator is None else dict(isolator)
    kind = iso.setdefault("kind", "bilinear")
    if kind == "bilinear":
        k1, k2 = float(iso.setdefault("K1", K1)), float(iso.setdefault("K2", K2))
        if not 0 < k2 < k1:
            raise ValueError("need 0 < K2 < K1")
        fy = float(iso.setdefault("fy_ratio", FY_RATIO)) * G * m_tot
        iso.update(k_linear=k2, k_plastic=k1 - k2, f_plastic=(k1 - k2) * fy / k1)
        k_ref, zeta = k1, ZETA_B
    elif kind == "friction_pendulum":
        missing = {"radius", "mu_slow", "mu_fast", "rate"} - set(iso)
        if missing:
            raise ValueError(f"the friction pendulum needs {sorted(missing)}")
        w = float(iso.setdefault("weight", G * m_tot))
        if not 0 < iso["mu_slow"] <= iso["mu_fast"]:
            raise ValueError("need 0 < mu_slow <= mu_fast")
        k0 = iso["mu_fast"] * w / float(iso.setdefault("yield_disp", YIELD_DISP))
        iso.update(k_linear=w / iso["radius"], k0=k0)
        k_ref, zeta = k0 + w / iso["radius"], 0.0
    else:
        raise ValueError(f"unknown isolator kind {kind!r}")
    zeta = zeta if zeta_iso is None else float(zeta_iso)
    f_y = np.full(n, np.inf) if story_yield is None else np.broadcast_to(
        np.asarray(story_yield, dtype=float), (n,)).copy()
    b = np.broadcast_to(np.asarray(story_b, dtype=float), (n,)).copy()
    if np.any(f_y <= 0) or np.any((b < 0) | (b >= 1)):
        raise ValueError("story yield forces must be > 0 and story_b in [0, 1)")
    omega1 = fixed_base_omega1(m, k)
    return Building(m, k, 2 * float(zeta_sup) * k / omega1, f_y, b, iso,
                    2 * zeta * math.sqrt(k_ref * m_tot), omega1)


@dataclass(frozen=True)
class Wall:
    """One moat wall law (both sides alike).

    law: "bumper" (F_A = k delta^n up to delta_u, + k_w (delta - delta_u) beyond; in
    restitution F_A (1 + C_imp delta'), floored at 0; C_imp = c_imp_coef / v_imp^c_imp_exponent)
    or "hertzdamp" (F = k delta^n (1 + chi delta' / v_imp), floored at 0).
    clear_gap m; k N/m^n; n; delta_u m; k_w N/m; c_imp_coef s/m (m/s)^c_imp_exponent; chi.
    restitution (bumper only): "whole" damps the whole F_A in restitution, wall term
    included (Eq. 6 applied to the F_A of Eq. 14); "rubber" damps the rubber term only,
    F = max(k min(delta, delta_u)^n (1 + C_imp delta'), 0) + k_w max(delta - delta_u, 0).
    """

    law: str
    clear_gap: float
    k: float
    n: float
    delta_u: float = math.inf
    k_w: float = 0.0
    c_imp_coef: float = 0.0
    c_imp_exponent: float = 0.0
    chi: float = 0.0
    restitution: str = "whole"

    def __post_init__(self):
        if self.law not in ("bumper", "hertzdamp"):
            raise ValueError(f"law must be 'bumper' or 'hertzdamp', got {self.law!r}")
        if self.restitution not in ("whole", "rubber"):
            raise ValueError(f"restitution must be 'whole' or 'rubber', got {self.restitution!r}")

    @classmethod
    def bumper(cls, gap, thickness=0.05, strain=0.8, n_bumpers=4, k_w=1.5e9, cor=0.45,
               m_eff=320e3, cavity=0.0, area=0.15 * 0.15, k_r=55.835e6, n=2.65, alpha=2.25,
               restitution="whole") -> Wall:
        """The SPEC's bumper wall: Eq. 11-12 for k_imp, Eq. 9 for C_imp, section 2 geometry."""
        protrusion = thickness - cavity
        k_imp = alpha * n_bumpers * area * k_r / thickness**n
        coef = 1.55 * (1 - cor**2) / (cor**0.7076 * m_eff**0.0025)
        return cls("bumper", gap - protrusion, k_imp, n, min(strain * thickness, protrusion),
                   k_w, coef, 0.9755, restitution=restitution)

    @classmethod
    def hertzdamp(cls, gap, k, n=1.5, cor=0.5) -> Wall:
        """Hertzdamp with the published chi = 3 (1 - COR^2) / 4."""
        return cls("hertzdamp", gap, k, n, chi=0.75 * (1 - cor**2))

    @classmethod
    def from_contact(cls, contact, member=0, restitution="whole") -> Wall:
        """The same wall from the numbers an engine.Contact holds (input data only)."""
        law = {3: "hertzdamp", 4: "bumper"}[int(contact.law[member])]

        def get(name):
            return float(getattr(contact, name)[member])

        if law == "hertzdamp":
            return cls(law, get("clear_gap"), get("k"), get("n"), chi=get("chi"))
        return cls(law, get("clear_gap"), get("k"), get("n"), get("delta_u"), get("k_w"),
                   get("c_imp_coef"), get("c_imp_exponent"), restitution=restitution)

    def elastic(self, delta):
        """F_A(delta), N (arrays or floats): the approach force, the bound of every force."""
        d = np.maximum(delta, 0.0)
        if self.law == "hertzdamp":
            return self.k * d**self.n
        return (self.k * np.minimum(d, self.delta_u) ** self.n
                + self.k_w * np.maximum(d - self.delta_u, 0.0))


class _ContactBranch:
    """The discrete state of one contact (v_imp, phase, crushed, floored) and the smooth
    branch of its law that this state selects."""

    def __init__(self, wall: Wall, v_imp: float):
        self.wall = wall
        self.v_imp = v_imp
        self.bumper = wall.law == "bumper"
        if self.bumper:
            self.damp = wall.c_imp_coef / v_imp**wall.c_imp_exponent  # C_imp, s/m
        else:
            self.damp = wall.chi / v_imp
        self.approach = self.bumper  # Hertzdamp is damped in both phases
        self.crushed = False
        self.floored = False

    def force(self, delta, rate):
        """Contact force (N) on this branch at indentation delta (m), rate (m/s); floats or
        arrays (floats take a faster path: this is evaluated in every right-hand side)."""
        w = self.wall
        if isinstance(delta, float):
            d = delta if delta > 0.0 else 0.0
        else:
            d = np.maximum(delta, 0.0)
        wall_term = 0.0
        if self.crushed:
            rubber = w.k * w.delta_u**w.n
            wall_term = w.k_w * (d - w.delta_u)
        else:
            rubber = w.k * d**w.n
        if not self.bumper or w.restitution == "whole":
            rubber, wall_term = rubber + wall_term, 0.0
        if self.floored:
            return rubber * 0.0 + wall_term
        if self.approach:
            return rubber + wall_term
        return rubber * (1 + self.damp * rate) + wall_term

    def events(self):
        """[(name, g(delta, rate), direction)] that end this branch."""
        out = [("release", lambda d, r: d, -1)]
        if self.bumper:
            du = self.wall.delta_u
            out.append(("crush", lambda d, r: d - du, -1 if self.crushed else 1))
            out.append(("turn", lambda d, r: r, -1 if self.approach else 1))
        if not self.approach:
            damp = self.damp
            out.append(("floor", lambda d, r: 1 + damp * r, 1 if self.floored else -1))
        return out

    def switch(self, name):
        if name == "crush":
            self.crushed = not self.crushed
        elif name == "turn":
            self.approach = not self.approach
        elif name == "floor":
            self.floored = not self.floored


def _event(fun, direction):
    fun.terminal = True
    fun.direction = direction
    return fun


def _deformation(y, n, j):
    """Deformation (m) and its rate (m/s) of the element between level j - 1 (the ground
    when j == 0) and level j; y is a state (2n,) or states (2n, T)."""
    if j == 0:
        return y[0], y[n]
    return y[j] - y[j - 1], y[n + j] - y[n + j - 1]


class _Plastic:
    """Elastic-perfectly-plastic spring (stiffness k, limit f_lim) between level j - 1 and
    level j. mode 0: elastic from the anchor (d_a, f_a); +-1: plastic at +-f_lim."""

    def __init__(self, j, n, k, f_lim, label):
        self.j, self.n, self.k, self.f_lim, self.label = j, n, float(k), float(f_lim), label
        self.mode, self.d_a, self.f_a = 0, 0.0, 0.0

    def force(self, y):
        """Force (N), positive when it resists a positive deformation; y (2n,) or (2n, T)."""
        d = _deformation(y, self.n, self.j)[0]
        if self.mode:
            return self.mode * self.f_lim + 0.0 * d
        return self.f_a + self.k * (d - self.d_a)

    def events(self, accel, t, y):
        """[(name, g(t, y), direction)] that end this mode; g dimensionless or in m/s."""
        if self.mode == 0:
            return [("yield+", lambda t, y: self.force(y) / self.f_lim - 1, 1),
                    ("yield-", lambda t, y: self.force(y) / self.f_lim + 1, -1)]
        return [("unload", lambda t, y: _deformation(y, self.n, self.j)[1], -self.mode)]

    def switch(self, name, t, y) -> bool:
        if name in ("yield+", "yield-"):
            self.mode = 1 if name == "yield+" else -1
        else:  # unload
            self.d_a = float(_deformation(y, self.n, self.j)[0])
            self.f_a, self.mode = self.mode * self.f_lim, 0
        return True


_V_MARK = 1e-13  # m/s


class _Friction:
    """The friction pendulum's F_f (level 0): elastic-perfectly-plastic with stiffness k0 and
    the moving limit L(|v_0|) = W mu(|v_0|). mode 0: elastic from the anchor (u_a, f_a);
    +-1: sliding, F_f = +-L(|v_0|)."""

    j = 0
    label = "friction"

    def __init__(self, n, k0, weight, mu_slow, mu_fast, rate):
        self.n, self.k0, self.w = n, float(k0), float(weight)
        self.mu_fast, self.d_mu, self.rate = float(mu_fast), float(mu_fast - mu_slow), float(rate)
        self.tau = self.w * self.d_mu * self.rate / self.k0  # s: L' / (k0 v0') at v0 = 0
        self.mode, self.u_a, self.f_a, self.sense = 0, 0.0, 0.0, 1.0

    def limit(self, speed):
        return self.w * (self.mu_fast - self.d_mu * np.exp(-self.rate * speed))

    def force(self, y):
        if self.mode:
            return self.mode * self.limit(self.sense * y[self.n])
        return self.f_a + self.k0 * (y[0] - self.u_a)

    def events(self, accel, t, y):
        """[(name, g(t, y), direction)] that end this mode, armed at the state (t, y);
        g dimensionless or in m/s. accel(t, y): the levels' relative accelerations."""
        n = self.n
        if self.mode == 0:
            # "v0 = 0" switches nothing: it ends the call at the cusp of L(|v0|). Within the
            # call |v0| = side v0, side the sign of v0 (or, right after a crossing, where
            # v0 ~ 1e-15 m/s, the sign it is heading for), extended smoothly past the cusp:
            # the solver's last step may overshoot it, and a slip just before the cusp must
            # still show as a sign change over that step. The marker sits _V_MARK beyond 0,
            # so that a call never starts on it.
            side = float(np.sign(y[n] + 1e-9 * accel(t, y)[0])) or 1.0
            return [("slip+", lambda t, y: (self.force(y) - self.limit(side * y[n])) / self.w, 1),
                    ("slip-", lambda t, y: (self.force(y) + self.limit(side * y[n])) / self.w, -1),
                    ("v0 = 0", lambda t, y: y[n] + side * _V_MARK, -side)]

        def stick(t, y):
            # (k0 s v0 - L') / k0, L' = W d_mu rate exp(-rate |v0|) sign(v0) v0'
            v0 = y[n]
            return (self.mode * v0 - self.tau * np.exp(-self.rate * self.sense * v0)
                    * self.sense * accel(t, y)[0])

        return [("stop", lambda t, y: y[n], -self.sense), ("stick", stick, -1)]

    def switch(self, name, t, y) -> bool:
        """Apply an event; False if it changes nothing (the cusp marker)."""
        if name == "v0 = 0":
            return False
        if name in ("slip+", "slip-"):
            self.mode = 1 if name == "slip+" else -1
            # sign(v0) for the whole slide ("stop" ends it where v0 changes sign), so that
            # |v0| = sense v0 is smooth up to and past that end: normally the slip's own
            # sign; the other one when a shrinking limit caught the force while it unloaded.
            self.sense = float(np.sign(y[self.n])) or float(self.mode)
        else:  # stop, stick: elastic from the force of this instant
            self.f_a, self.u_a = float(self.force(y)), float(y[0])
            self.mode = 0
        return True


def _wall_events(wall, branch, side, n):
    """[(name, g(t, y), direction)] of the wall: touch on either side when free, the
    branch's kinks and release in contact. g in m, m/s or dimensionless."""
    gap = wall.clear_gap
    if branch is None:
        return [("touch+", lambda t, y: y[0] - gap, 1),
                ("touch-", lambda t, y: -y[0] - gap, 1)]
    return [(name, (lambda t, y, g=g: g(side * y[0] - gap, side * y[n])), direction)
            for name, g, direction in branch.events()]


class _Model:
    """The equations of motion of one building, its plastic parts, the wall and the current
    segment of a_g."""

    def __init__(self, bld: Building, wall: Wall | None):
        self.bld = bld
        self.n = n = bld.n_levels
        iso = bld.isolator
        elastic = np.where(np.isfinite(bld.story_yield), bld.story_b * bld.story_k,
                           bld.story_k)
        self.k_lin = np.r_[iso["k_linear"], elastic]  # element j joins level j-1 to j
        self.c = np.r_[bld.c_iso, bld.story_c]
        self.m = bld.masses
        if iso["kind"] == "bilinear":
            self.parts = [_Plastic(0, n, iso["k_plastic"], iso["f_plastic"], "isolator")]
        else:
            self.parts = [_Friction(n, iso["k0"], iso["weight"], iso["mu_slow"],
                                    iso["mu_fast"], iso["rate"])]
        for s in np.flatnonzero(np.isfinite(bld.story_yield)) + 1:
            b, k, f = bld.story_b[s - 1], bld.story_k[s - 1], bld.story_yield[s - 1]
            self.parts.append(_Plastic(s, n, (1 - b) * k, (1 - b) * f, f"story {s}"))
        self.wall, self.branch, self.side = wall, None, 0.0
        self.a_i, self.slope, self.t_i = 0.0, 0.0, 0.0

    def element_forces(self, y):
        """Force (N) in each element j = 0..N (0: the isolator with its dashpot and the wall;
        j: story j), positive in tension; y (2n,) or (2n, T)."""
        n = self.n
        u, v = y[:n], y[n:]
        du, dv = u.copy(), v.copy()
        du[1:] -= u[:-1]
        dv[1:] -= v[:-1]
        shape = (n,) + (1,) * (u.ndim - 1)
        f = self.k_lin.reshape(shape) * du + self.c.reshape(shape) * dv
        for part in self.parts:
            f[part.j] += part.force(y)
        if self.branch is not None:
            f[0] += self.side * self.branch.force(self.side * u[0] - self.wall.clear_gap,
                                                  self.side * v[0])
        return f

    def total_accel(self, y):
        """Total accelerations (m/s^2): the net force on each level over its mass."""
        f = self.element_forces(y)
        above = np.zeros_like(f)
        above[:-1] = f[1:]
        return (above - f) / self.m.reshape((self.n,) + (1,) * (f.ndim - 1))

    def accel(self, t, y):
        """Relative accelerations (m/s^2) at time(s) t in the current a_g segment."""
        return self.total_accel(y) - (self.a_i + self.slope * (t - self.t_i))

    def rhs(self, t, y):
        return np.concatenate([y[self.n:], self.accel(t, y)])


# An armed event's function may not be on its far side anywhere on the sampled grid by more
# than this (m, m/s or 1): a check that no switch went unnoticed between two solver steps.
_MISSED_EVENT_TOL = 1e-7


def simulate(accel, accel_dt, wall: Wall | None = None, t_end=None, rtol=1e-9,
             max_step_contact=1e-4, sample_dt=1e-4, *, masses=None, story_k=None,
             isolator=None, story_yield=None, story_b=STORY_B, zeta_iso=None,
             zeta_sup=ZETA_S, max_step=np.inf) -> dict:
    """Integrate the building under ground acceleration `accel` (m/s^2 every accel_dt s) over
    [0, t_end] (default: the whole record), pounding on `wall` (None: no wall).

    masses, story_k, isolator, story_yield, story_b, zeta_iso, zeta_sup: the building, see
    `make_building` (defaults: the paper's). rtol: solve_ivp's relative tolerance (absolute:
    1e-12 m, 1e-10 m/s); max_step_contact: the largest solver step in contact (s); max_step:
    out of contact; sample_dt: about the step of the grid on which peaks are taken (s).
    Returns peak_total_accel (N+1,) m/s^2, peak_interstory_drift (N,) m, peak_isolator_disp m,
    max_indentation m, max_impact_force N, n_impacts, n_solver_steps, n_retries (calls redone
    with shorter steps, see the module docstring), switches (how many times each plastic part
    changed mode: {label: count}, labels "isolator" or "friction" and "story i"),
    peak_story_ductility (N,) when
    story_yield is given (0 for an elastic story), and impacts: one dict per contact,
    t (touch, s), v_imp (m/s), max_indentation (m), max_force (N), kinks: the law's kinks
    met, [(t s, name)], name "crush" (delta_u crossed either way), "turn" (the rate changed
    sign) or "floor" (the restitution force reached 0, or left 0: a reload).
    """
    bld = make_building(masses, story_k, isolator, story_yield, story_b, zeta_iso, zeta_sup)
    model = _Model(bld, wall)
    n = model.n
    accel = np.asarray(accel, dtype=float)
    duration = (accel.size - 1) * accel_dt
    t_end = duration if t_end is None else min(float(t_end), duration)
    h = accel_dt / max(1, round(accel_dt / sample_dt))  # every record sample is on the grid
    atol = np.r_[np.full(n, 1e-12), np.full(n, 1e-10)]

    t = 0.0
    y = np.zeros(2 * n)
    peak_acc, peak_drift, peak_iso = np.zeros(n), np.zeros(n - 1), 0.0
    impacts: list[dict] = []
    switches = {part.label: 0 for part in model.parts}
    n_steps, stalled, n_retries = 0, 0, 0
    first_step = None

    while t < t_end - 1e-12:
        i = min(int(math.floor(t / accel_dt + 1e-9)), accel.size - 2)
        model.t_i = i * accel_dt
        t_stop = min((i + 1) * accel_dt, t_end)
        model.a_i = accel[i]
        model.slope = (accel[i + 1] - accel[i]) / accel_dt

        armed = [(name, g, direction, part) for part in model.parts
                 for name, g, direction in part.events(model.accel, t, y)]
        if wall is not None:
            armed += [(name, g, direction, None)
                      for name, g, direction in _wall_events(wall, model.branch, model.side, n)]
        events = [_event(g, direction) for _, g, direction, _ in armed]
        step_bound = max_step_contact if model.branch is not None else max_step
        while True:
            step0 = None if first_step is None else min(first_step, t_stop - t, step_bound)
            sol = solve_ivp(model.rhs, (t, t_stop), y, method="DOP853", rtol=rtol, atol=atol,
                            max_step=step_bound, first_step=step0, events=events,
                            dense_output=True)
            if sol.status < 0:
                raise RuntimeError(f"solve_ivp failed at t = {t}: {sol.message}")
            t_new = float(sol.t[-1])
            # Peaks on the grid points of [t, t_new] and at its ends.
            k0, k1 = math.ceil(t / h - 1e-9), math.floor(t_new / h + 1e-9)
            grid = np.unique(np.r_[t, np.arange(k0, k1 + 1) * h, t_new].clip(t, t_new))
            yy = sol.sol(grid)
            missed = [name for name, g, direction, _ in armed
                      if np.min(-direction * g(grid, yy)) < -_MISSED_EVENT_TOL]
            if not missed:
                break
            # A switch crossed and recrossed within one solver step (stick-slip of the
            # friction pendulum): the same call again with steps a quarter as long.
            step_bound = min(step_bound, float(sol.t[-1] - sol.t[0])) / 4
            n_retries += 1
            if step_bound < 1e-7:
                raise RuntimeError(f"missed event {missed} between t = {t} and {t_new} s")
        n_steps += sol.t.size - 1
        if sol.t.size > 2:
            first_step = sol.t[-2] - sol.t[-3] if sol.status == 1 else sol.t[-1] - sol.t[-2]
        stalled = stalled + 1 if t_new - t < 1e-12 else 0
        if stalled > 20:
            raise RuntimeError(f"events chatter at t = {t} s: {[a[0] for a in armed]}")

        u = yy[:n]
        if model.branch is not None:
            delta = model.side * u[0] - wall.clear_gap
            force = model.branch.force(delta, model.side * yy[n]) * np.ones(grid.size)
            impact = impacts[-1]
            impact["max_indentation"] = max(impact["max_indentation"], float(delta.max()))
            impact["max_force"] = max(impact["max_force"], float(force.max()))
        # Total acceleration = relative + a_g = (net force of the springs and dashpots) / m.
        peak_acc = np.maximum(peak_acc, np.abs(model.total_accel(yy)).max(axis=1))
        peak_drift = np.maximum(peak_drift, np.abs(np.diff(u, axis=0)).max(axis=1))
        peak_iso = max(peak_iso, float(np.abs(u[0]).max()))

        y = sol.y[:, -1].copy()
        t = t_new
        if sol.status == 1:
            # The event that ended the call, then any other armed one that the same instant
            # carries past its zero (e.g. u_0' = 0 both unloads the isolator and turns the
            # contact from approach to restitution); one switch per part.
            fired = next(j for j, te in enumerate(sol.t_events) if te.size)
            todo = [armed[fired]] + [a for j, a in enumerate(armed)
                                     if j != fired and -a[2] * a[1](t, y) < 0]
            done = set()
            for name, _, _, part in todo:
                if part is not None:
                    if id(part) not in done and part.switch(name, t, y):
                        done.add(id(part))
                        switches[part.label] += 1
                elif name in ("touch+", "touch-"):
                    model.side = 1.0 if name == "touch+" else -1.0
                    v_imp = model.side * float(y[n])
                    model.branch = _ContactBranch(wall, v_imp)
                    impacts.append({"t": t, "v_imp": v_imp, "max_indentation": 0.0,
                                    "max_force": 0.0, "kinks": []})
                elif name == "release":
                    model.branch, model.side = None, 0.0
                else:
                    model.branch.switch(name)
                    impacts[-1]["kinks"].append((t, name))

    out = {"peak_total_accel": peak_acc, "peak_interstory_drift": peak_drift,
           "peak_isolator_disp": peak_iso,
           "max_indentation": max((c["max_indentation"] for c in impacts), default=0.0),
           "max_impact_force": max((c["max_force"] for c in impacts), default=0.0),
           "n_impacts": len(impacts), "impacts": impacts, "n_solver_steps": n_steps,
           "switches": switches, "n_retries": n_retries}
    if story_yield is not None:
        out["peak_story_ductility"] = peak_drift / (bld.story_yield / bld.story_k)
    return out


def _drive(part, t, path, log=None) -> np.ndarray:
    """Force of one plastic part (n = 1: its deformation is y[0], its rate y[1]) along an
    imposed motion: path(t) -> (deformation, rate, rate') at the times t (s, increasing,
    from the unloaded state at t[0]); every switch located by brentq between two times and,
    if `log` is a list, appended to it as (t, name)."""
    from scipy.optimize import brentq

    def state(tt):
        d, r, _ = path(tt)
        return np.array([d, r], dtype=float)

    def accel(tt, yy):
        return np.atleast_1d(path(tt)[2])

    out = np.empty(len(t))
    out[0] = float(part.force(state(t[0])))
    for i in range(1, len(t)):
        a, b = float(t[i - 1]), float(t[i])
        for _ in range(100):  # switches within [a, b]
            hit = None
            for name, g, direction in part.events(accel, a, state(a)):
                ga, gb = float(g(a, state(a))), float(g(b, state(b)))
                if (direction >= 0 and ga < 0 <= gb) or (direction <= 0 and ga > 0 >= gb):
                    root = brentq(lambda tt, g=g: float(g(tt, state(tt))), a, b, xtol=1e-15,
                                  rtol=1e-15)
                    if hit is None or root < hit[0]:
                        hit = (root, name)
            if hit is None:
                break
            part.switch(hit[1], hit[0], state(hit[0]))
            if log is not None:
                log.append(hit)
            a = hit[0]
        out[i] = float(part.force(state(b)))
    return out


def friction_loop(t, path, *, radius, mu_slow, mu_fast, rate, weight,
                  yield_disp=YIELD_DISP, log=None) -> np.ndarray:
    """Horizontal force (N) of this module's friction pendulum, (W / R) u + F_f, at the times
    t along the imposed slider motion path(t) -> (u m, v m/s, v' m/s^2) (no inertia). log: a
    list to which every switch of F_f is appended as (t, name), name "slip+", "slip-",
    "stop", "stick" or "v0 = 0" (a marker)."""
    part = _Friction(1, mu_fast * weight / yield_disp, weight, mu_slow, mu_fast, rate)
    u = np.array([path(tt)[0] for tt in t], dtype=float)
    return _drive(part, t, path, log) + weight / radius * u


def story_loop(t, path, *, k, f_y, b=STORY_B) -> np.ndarray:
    """Force (N) of this module's yielding story (b k in parallel with the
    elastic-perfectly-plastic (1 - b) k, limit (1 - b) f_y) at the times t along the imposed
    drift path(t) -> (drift m, drift rate m/s, its rate m/s^2)."""
    part = _Plastic(0, 1, (1 - b) * k, (1 - b) * f_y, "story")
    d = np.array([path(tt)[0] for tt in t], dtype=float)
    return _drive(part, t, path) + b * k * d


def two_body(m_eff, v, wall: Wall, rtol=1e-11, samples_per_segment=400) -> dict:
    """Two free bodies colliding at relative velocity v (m/s) through `wall`'s law (its gap
    ignored): m_eff delta'' = -F(delta, delta'), delta(0) = 0, delta'(0) = v, until delta
    returns to 0.

    Returns cor (v_out / v), peak_force N, peak_indentation m, dissipated_energy J
    (1/2 m_eff (v^2 - v_out^2)), hysteresis_area J (integral of F d delta, a check of the
    same number) and events: the law's kinks met, in order.
    """
    branch = _ContactBranch(wall, v)
    t, y = 0.0, np.array([0.0, float(v)])
    # Time scale: the undamped power-law contact's peak indentation over v.
    scale = ((wall.n + 1) * m_eff * v**2 / (2 * wall.k)) ** (1 / (wall.n + 1)) / v
    peak_force, peak_indent, area, met = 0.0, 0.0, 0.0, []
    for _ in range(100):
        def rhs(tt, yy, branch=branch):
            return [yy[1], -float(branch.force(yy[0], yy[1])) / m_eff]

        names, events = [], []
        for name, g, direction in branch.events():
            events.append(_event(lambda tt, yy, g=g: g(yy[0], yy[1]), direction))
            names.append(name)
        sol = solve_ivp(rhs, (t, t + 100 * scale), y, method="DOP853", rtol=rtol,
                        atol=[1e-14 * scale * v, 1e-14 * v], events=events, dense_output=True)
        if sol.status != 1:
            raise RuntimeError(f"two_body: no event within the time span ({sol.message})")
        grid = np.linspace(t, sol.t[-1], samples_per_segment)
        d, r = sol.sol(grid)
        f = branch.force(d, r) * np.ones(grid.size)
        peak_force = max(peak_force, float(f.max()))
        peak_indent = max(peak_indent, float(d.max()))
        area += float(trapezoid(f * r, grid))
        t, y = float(sol.t[-1]), sol.y[:, -1].copy()
        name = next(names[j] for j, te in enumerate(sol.t_events) if te.size)
        met.append(name)
        if name == "release":
            break
        branch.switch(name)
    else:
        raise RuntimeError("two_body: contact did not end")
    v_out = -float(y[1])
    return {"cor": v_out / v, "peak_force": peak_force, "peak_indentation": peak_indent,
            "dissipated_energy": 0.5 * m_eff * (v**2 - v_out**2), "hysteresis_area": area,
            "events": met}
