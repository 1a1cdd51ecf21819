"""Independent model of the paper's building pounding on its moat wall, for cross-checking
the engine. A test helper, not a test file: it uses no code from ``engine/`` (only, if a test
wishes, the numbers held by an ``engine.Contact``, which are input data).

What it models (SPEC sections 1 and 2, written from the SPEC, not from the engine):

* 5 lumped masses (320, 320, 320, 320, 250 t), levels 0 (isolation slab) .. 4 (roof), one
  horizontal DOF each, displacements u and velocities v relative to the ground.
* Stories 1..4: k = 600 MN/m in parallel with a dashpot c_s = 2 zeta_s k / omega_1
  (zeta_s = 2 %, omega_1 the first circular frequency of the fixed-base superstructure).
* Isolator (ground -> level 0): K2 = 25 MN/m in parallel with an elastic-perfectly-plastic
  spring of stiffness K1 - K2 = 175 MN/m that yields at (K1 - K2) u_y, u_y = Fy / K1,
  Fy = 0.1 g M_tot; plus the isolation dashpot c_b = 2 zeta_b sqrt(K1 M_tot), zeta_b = 5 %.
* Ground acceleration a_g(t) linearly interpolated between record samples.
* Moat wall on both sides of level 0 at clear gap g: indentation delta = |u_0| - g on the
  side the slab moves towards; the impact velocity v_imp is the indentation rate at first
  touch, kept until the indentation returns to 0.
* Wall laws (`Wall`): the paper's rubber bumper (Eq. 4, 6, 9, 14) and Hertzdamp
  (Muthukumar & DesRoches 2006).

How it is integrated (a different scheme from the engine's central differences): an
event-driven hybrid integration with ``scipy.integrate.solve_ivp`` (DOP853, rtol 1e-9 by
default). The right-hand side is kept smooth inside every solve_ivp call, and every place
where it is not smooth ends the call exactly there:

* the record's samples (a_g is linear between them);
* the plastic spring's force is not a state: in its elastic mode it is f_a + (K1 - K2)
  (u_0 - u_a) from the anchor (u_a, f_a) where the mode began, in its plastic mode exactly
  +-f_yield. Events switch elastic -> plastic when the force reaches +-f_yield and plastic ->
  elastic when u_0' changes sign, so the force stays exactly on the yield surface;
* the wall contact: touch (delta = 0 rising, v_imp stored), release (delta = 0 falling), and
  inside the contact every kink of the law: the rate changing sign (approach / restitution),
  the crush limit delta_u, and the damping factor 1 + C delta' crossing 0 (the floor at zero
  force). Each branch of the law is extended smoothly past its kink; the event truncates it.

Events that one instant sets off together (u_0' = 0 both unloads the isolator and turns a
contact) are all applied; after every call the armed events are checked on the sampled grid,
and a switch missed between two solver steps raises an error.

Peaks are taken on a uniform grid of about `sample_dt` (0.1 ms, a divisor of the record's
step, so every record sample is on it) evaluated from the dense output, plus every event
instant. Solver steps are at most `max_step_contact` (1e-4 s) in contact; since the law's
kinks are events, that bound does not set the accuracy (Kobe, 9 impacts: 1e-4, 2.5e-4 and
1e-3 s give the same peaks to 5e-10). Own error, measured by halving the contact step and the
sampling step with rtol / 10 (Pacoima, bumper and Hertzdamp): 4e-6 at most (sampling of the
acceleration peaks); against the engine without a wall, 2e-5.

`two_body` solves the scalar impact m_eff delta'' = -F with the same contact branches.
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
M_TOT = float(sum(MASSES))
F_Y = 0.1 * G * M_TOT  # N, characteristic strength
U_Y = F_Y / K1  # m, 7.50 mm
K_PLASTIC = K1 - K2  # N/m
F_PLASTIC_YIELD = K_PLASTIC * U_Y  # N
ZETA_B = 0.05
ZETA_S = 0.02


def fixed_base_omega1() -> float:
    """First circular frequency (rad/s) of levels 1..4 with level 0 held fixed."""
    k = np.zeros((4, 4))
    for j in range(4):  # story j + 1 joins level j (fixed when j == 0) to level j + 1
        k[j, j] += K_STORY
        if j > 0:
            k[j - 1, j - 1] += K_STORY
            k[j - 1, j] -= K_STORY
            k[j, j - 1] -= K_STORY
    return float(math.sqrt(eigh(k, np.diag(MASSES[1:]), eigvals_only=True)[0]))


OMEGA_1 = fixed_base_omega1()
C_BASE = 2 * ZETA_B * math.sqrt(K1 * M_TOT)  # N s/m, 1.749 MN s/m
C_STORY = 2 * ZETA_S * K_STORY / OMEGA_1  # N s/m


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


@dataclass
class _Isolator:
    """Plastic spring mode: 0 elastic from the anchor (u_a, f_a), +-1 plastic at +-f_yield."""

    mode: int = 0
    u_a: float = 0.0
    f_a: float = 0.0

    def force(self, u0):
        """Force of the elastic-perfectly-plastic spring (N); floats or arrays."""
        if self.mode:
            return self.mode * F_PLASTIC_YIELD + 0.0 * u0
        return self.f_a + K_PLASTIC * (u0 - self.u_a)

    def events(self):
        """[(name, g(t, y), direction)], g dimensionless or in m/s, that end this mode."""
        if self.mode == 0:
            return [("yield+", lambda t, y: self.force(y[0]) / F_PLASTIC_YIELD - 1, 1),
                    ("yield-", lambda t, y: self.force(y[0]) / F_PLASTIC_YIELD + 1, -1)]
        return [("unload", lambda t, y: y[5], -self.mode)]


def _wall_events(wall, branch, side):
    """[(name, g(t, y), direction)] of the wall: touch on either side when free, the
    branch's kinks and release in contact. g in m, m/s or dimensionless."""
    gap = wall.clear_gap
    if branch is None:
        return [("touch+", lambda t, y: y[0] - gap, 1),
                ("touch-", lambda t, y: -y[0] - gap, 1)]
    return [(name, (lambda t, y, g=g: g(side * y[0] - gap, side * y[5])), direction)
            for name, g, direction in branch.events()]


# An armed event's function may not be on its far side anywhere on the sampled grid by more
# than this (m, m/s or 1): a check that no switch went unnoticed between two solver steps.
_MISSED_EVENT_TOL = 1e-7


def simulate(accel, accel_dt, wall: Wall | None = None, t_end=None, rtol=1e-9,
             max_step_contact=1e-4, sample_dt=1e-4) -> dict:
    """Integrate the building under ground acceleration `accel` (m/s^2 every accel_dt s) over
    [0, t_end] (default: the whole record), pounding on `wall` (None: no wall).

    rtol: solve_ivp's relative tolerance (absolute: 1e-12 m, 1e-10 m/s); max_step_contact:
    the largest solver step in contact (s); sample_dt: about the step of the grid on which
    peaks are taken (s).
    Returns peak_total_accel (5,) m/s^2, peak_interstory_drift (4,) m, peak_isolator_disp m,
    max_indentation m, max_impact_force N, n_impacts, n_solver_steps, and impacts: one dict
    per contact, t (touch, s), v_imp (m/s), max_indentation (m), max_force (N), kinks: the
    law's kinks met, [(t s, name)], name "crush" (delta_u crossed either way), "turn" (the
    rate changed sign) or "floor" (the restitution force reached 0, or left 0: a reload).
    """
    accel = np.asarray(accel, dtype=float)
    duration = (accel.size - 1) * accel_dt
    t_end = duration if t_end is None else min(float(t_end), duration)
    h = accel_dt / max(1, round(accel_dt / sample_dt))  # every record sample is on the grid
    m = np.asarray(MASSES)
    atol = np.r_[np.full(5, 1e-12), np.full(5, 1e-10)]

    iso = _Isolator()
    branch: _ContactBranch | None = None
    side = 0.0
    t = 0.0
    y = np.zeros(10)
    peak_acc, peak_drift, peak_iso = np.zeros(5), np.zeros(4), 0.0
    impacts: list[dict] = []
    n_steps = 0
    first_step = None

    while t < t_end - 1e-12:
        i = min(int(math.floor(t / accel_dt + 1e-9)), accel.size - 2)
        t_i = i * accel_dt
        t_stop = min((i + 1) * accel_dt, t_end)
        a_i = accel[i]
        slope = (accel[i + 1] - accel[i]) / accel_dt

        def rhs(tt, yy, a_i=a_i, slope=slope, t_i=t_i, branch=branch, side=side):
            u0, u1, u2, u3, u4, v0, v1, v2, v3, v4 = yy.tolist()
            ag = a_i + slope * (tt - t_i)
            f_0 = K2 * u0 + iso.force(u0) + C_BASE * v0
            if branch is not None:
                f_0 += side * float(branch.force(side * u0 - wall.clear_gap, side * v0))
            s1 = K_STORY * (u1 - u0) + C_STORY * (v1 - v0)
            s2 = K_STORY * (u2 - u1) + C_STORY * (v2 - v1)
            s3 = K_STORY * (u3 - u2) + C_STORY * (v3 - v2)
            s4 = K_STORY * (u4 - u3) + C_STORY * (v4 - v3)
            return np.array([v0, v1, v2, v3, v4,
                             (s1 - f_0) / m[0] - ag, (s2 - s1) / m[1] - ag,
                             (s3 - s2) / m[2] - ag, (s4 - s3) / m[3] - ag, -s4 / m[4] - ag])

        armed = iso.events() + ([] if wall is None else _wall_events(wall, branch, side))
        events = [_event(g, direction) for _, g, direction in armed]
        max_step = max_step_contact if branch is not None else np.inf
        step0 = None if first_step is None else min(first_step, t_stop - t, max_step)
        sol = solve_ivp(rhs, (t, t_stop), y, method="DOP853", rtol=rtol, atol=atol,
                        max_step=max_step, first_step=step0, events=events,
                        dense_output=True)
        if sol.status < 0:
            raise RuntimeError(f"solve_ivp failed at t = {t}: {sol.message}")
        n_steps += sol.t.size - 1
        if sol.t.size > 2:
            first_step = sol.t[-2] - sol.t[-3] if sol.status == 1 else sol.t[-1] - sol.t[-2]
        t_new = float(sol.t[-1])

        # Peaks on the grid points of [t, t_new] and at its ends.
        k0, k1 = math.ceil(t / h - 1e-9), math.floor(t_new / h + 1e-9)
        grid = np.unique(np.r_[t, np.arange(k0, k1 + 1) * h, t_new].clip(t, t_new))
        yy = sol.sol(grid)
        for name, g, direction in armed:
            if np.min(-direction * g(grid, yy)) < -_MISSED_EVENT_TOL:
                raise RuntimeError(f"missed event {name} between t = {t} and {t_new} s")
        u, v = yy[:5], yy[5:]
        f_0 = K2 * u[0] + iso.force(u[0]) + C_BASE * v[0]
        if branch is not None:
            delta = side * u[0] - wall.clear_gap
            force = branch.force(delta, side * v[0]) * np.ones(grid.size)
            f_0 = f_0 + side * force
            impact = impacts[-1]
            impact["max_indentation"] = max(impact["max_indentation"], float(delta.max()))
            impact["max_force"] = max(impact["max_force"], float(force.max()))
        story = K_STORY * np.diff(u, axis=0) + C_STORY * np.diff(v, axis=0)  # (4, T)
        chain = np.vstack([f_0, story, np.zeros(grid.size)])  # ground, stories, free end
        # Total acceleration = relative + a_g = (net force of the springs and dashpots) / m.
        total_acc = (chain[1:] - chain[:-1]) / m[:, None]
        peak_acc = np.maximum(peak_acc, np.abs(total_acc).max(axis=1))
        peak_drift = np.maximum(peak_drift, np.abs(np.diff(u, axis=0)).max(axis=1))
        peak_iso = max(peak_iso, float(np.abs(u[0]).max()))

        y = sol.y[:, -1].copy()
        t = t_new
        if sol.status == 1:
            # The event that ended the call, then any other armed one that the same instant
            # carries past its zero (e.g. u_0' = 0 both unloads the isolator and turns the
            # contact from approach to restitution).
            fired = next(j for j, te in enumerate(sol.t_events) if te.size)
            names = [armed[fired][0]] + [name for j, (name, g, direction) in enumerate(armed)
                                         if j != fired and -direction * g(t, y) < 0]
            for name in names:
                if name in ("yield+", "yield-"):
                    iso.mode = 1 if name == "yield+" else -1
                elif name == "unload":
                    iso.u_a, iso.f_a, iso.mode = float(y[0]), iso.mode * F_PLASTIC_YIELD, 0
                elif name in ("touch+", "touch-"):
                    side = 1.0 if name == "touch+" else -1.0
                    v_imp = side * float(y[5])
                    branch = _ContactBranch(wall, v_imp)
                    impacts.append({"t": t, "v_imp": v_imp, "max_indentation": 0.0,
                                    "max_force": 0.0, "kinks": []})
                elif name == "release":
                    branch, side = None, 0.0
                else:
                    branch.switch(name)
                    impacts[-1]["kinks"].append((t, name))

    return {"peak_total_accel": peak_acc, "peak_interstory_drift": peak_drift,
            "peak_isolator_disp": peak_iso,
            "max_indentation": max((c["max_indentation"] for c in impacts), default=0.0),
            "max_impact_force": max((c["max_force"] for c in impacts), default=0.0),
            "n_impacts": len(impacts), "impacts": impacts,
            "n_solver_steps": n_steps}


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
