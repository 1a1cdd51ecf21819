"""Independent model of the base-isolated shear building IN PLAN (both horizontal directions)
in a CIRCULAR moat, for cross-checking the engine's runs in plan. A test helper: it uses no code
from ``engine/`` (numbers an ``engine.Contact`` holds may be passed in as input data), nor from
the OpenSees models; the building's numbers come from ``independent_building.make_building``
(the planar solve_ivp reference, which documents them), everything else is written here from
the SPEC's equations. Units SI (kg, m, s, N).

What it models
--------------
* Levels 0 (isolation slab) .. N (roof), each with two horizontal DOFs (x, y) and lumped mass
  m_j in both; displacements u_j and velocities v_j (2-vectors) relative to the ground. The
  building is isotropic: story j (level j-1 to level j) is a linear spring k_j and a dashpot
  c_j = 2 zeta_sup k_j / omega_1 acting on the drift VECTOR (the same in x and y, so a force
  along x moves nothing along y); the isolation dashpot c_iso = 2 zeta_iso sqrt(k_ref M_tot)
  likewise ("paper" damping). Yielding stories are not modelled in plan.
* Isolator: a linear spring k_lin (K2, or W / R for the friction pendulum) in parallel with a
  COUPLED slip element of stiffness k_p (K1 - K2, or k_0 = mu_fast W / yield_disp) whose force
  f (a 2-vector) obeys rate-independent perfect plasticity with a CIRCULAR yield surface
  |f| <= L and the associative flow rule, i.e. the continuous-time law of which the engine's
  radial return (and OpenSees' elastomericBearingPlasticity / flatSliderBearing) is the
  backward-Euler discretisation:
      f' = k_p (u_0' - lambda n),  n = f / |f|,  lambda >= 0,  lambda (|f| - L) = 0.
  The radial return cannot be written as an ODE on its own (it is a map per step); this flow
  rule is the ODE it converges to as dt -> 0, written in two phases with a switch:
  - elastic, |f| < L: f = f_a + k_p (u_0 - u_a) from the anchor (u_a, f_a) where the phase
    began (no state); it ends when |f| reaches L ("yield"; the friction pendulum's slip);
  - plastic, |f| = L: f = L n(phi), n = (cos phi, sin phi), the angle phi an ODE state:
    consistency gives lambda = n . u_0' - L' / k_p and the tangential part
    phi' = k_p (t . u_0') / L, t = (-sin phi, cos phi): the force rides the circle, turning
    towards the sliding direction. The phase ends when lambda falls through 0 ("unload";
    bilinear, L constant: n . u_0' = 0; friction pendulum, its stick: n . u_0' = L' / k_0).
  Bilinear: L = (K1 - K2) u_y = Fy (1 - K2 / K1), Fy = fy_ratio g M_tot. Friction pendulum:
  L = W mu(|v_0|), mu(s) = mu_fast - (mu_fast - mu_slow) exp(-rate s) (Constantinou et al.
  1990), |v_0| the slab's sliding SPEED (an isotropic law), W constant; in sliding
  L' = W (mu_fast - mu_slow) rate exp(-rate |v_0|) (v_0 . v_0') / |v_0|, v_0' from the
  equations of motion. A motion along x alone gives the planar reference's law (phi = 0 or
  pi; "unload" becomes its unload, or its stop and stick: at v_0 = 0, where L' jumps, the
  event function jumps through 0).
* Circular moat: one wall at clear gap g from the centre, pushing along the radius. Radial
  indentation delta = |u_0| - g, its rate delta' = n_r . v_0, n_r = u_0 / |u_0|; the contact
  force F >= 0 acts on the slab along -n_r. The impact velocity v_imp is delta' at first
  touch, kept until delta returns to 0 ("a contact lasts while delta > 0"). Laws
  (`RadialWall`), written from the SPEC's equations:
  - "linear" (Eq. 1-2, Kelvin-Voigt): F = max(k delta + c delta', 0), c = 2 xi sqrt(k m_eff),
    xi the damping ratio for which the no-tension contact realises the COR: separation happens
    when the force (the acceleration) vanishes, which for m x'' + c x' + k x = 0 from x = 0,
    x' = v gives (derived in `cor_no_tension`) COR = exp(-r (pi - 2 atan r)),
    r = xi / sqrt(1 - xi^2); inverted numerically;
  - "bumper" (the paper's Eq. 4, 6, 9, 11, 12, 14): F_A = k_imp delta^n up to the crush limit
    delta_u, + k_w (delta - delta_u) beyond; approach (delta' > 0) F = F_A; restitution
    F = F_A (1 + C_imp delta'), floored at 0, the whole F_A damped; C_imp = 1.55 (1 - COR^2)
    / (COR^0.7076 m_eff^0.0025 v_imp^0.9755); k_imp = alpha n_bumpers A K_r / t^n; clear gap
    g - (t - cavity); delta_u = min(strain t, t - cavity).
* Ground acceleration a_g(t) (2-vector), each component linear between record samples; total
  acceleration = relative + a_g, taken as the net force on a level over its mass.

How it is integrated (the scheme of independent_building.py, in plan): event-driven
``solve_ivp`` (DOP853, rtol 1e-9), the right-hand side smooth inside every call, every call
ended exactly where it is not: the record's samples; the isolator's switches (yield,
unload); the wall's touch (|u_0| = g rising) and release (delta = 0 falling) and, in
contact, every kink of its law (linear: the force k delta + c delta' reaching 0 or leaving it;
bumper: the rate changing sign, the crush limit, the damping factor 1 + C_imp delta' reaching
0 or leaving it), each branch extended smoothly past its kink until the event truncates it.
Events that one instant sets off together are all applied. After every call the armed events
are checked on the sampled grid; a switch crossed and crossed back within one solver step
makes the call be redone with steps a quarter as long (``n_retries``), down to 1e-7 s.
Nothing marks the instants where the slab's speed vanishes (the cusp of L(|v_0|), which the
planar reference ends its calls at): in plan the speed does not vanish (no retry at all in the
tests' runs), while a motion along one axis passes through v_0 = 0 at every stop, and the
retries catch the friction pendulum's switches there: the planar reference's peaks to 1e-9,
but ~10 times slower (15 s of RSN953:009 along x: 18 s, 33 retries, against 1.4 s).

Solver steps are at most `max_step_contact` (1e-3 s) in contact: since the law's kinks are
events, the step does not set the accuracy (the cases of tests/engine/test_plan_references.py
give the same peaks to 3e-9 with 1e-4 s, 1e-3 s and no bound). Own error, measured by
tightening rtol to 1e-10 and sampling every 25 us: 8e-6 at most (the linear wall's peak
acceleration), 3e-6 for the bumpers, 1.3e-6 for the friction pendulum, 7e-8 without a wall.

Peaks (the engine's PlanResult names), on a uniform grid of about `sample_dt` (0.1 ms, every
record sample on it) and at every event instant: peak_total_accel (N+1,) m/s^2,
peak_interstory_drift (N,) m, peak_isolator_disp m (resultants: peaks of |a_j|, |u_j - u_j-1|,
|u_0|), peak_total_accel_xy (N+1, 2), peak_interstory_drift_xy (N, 2), peak_isolator_disp_xy
(2,), max_indentation m, max_impact_force N, n_impacts, max_impact_force_wall (1,) N (the
circle's one wall); and n_solver_steps, n_retries, switches ({"isolator": count}), impacts (one
dict per contact: t s, v_imp m/s, max_indentation m, max_force N).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from .independent_building import make_building


def cor_no_tension(xi: float) -> float:
    """COR of the no-tension Kelvin-Voigt contact of damping ratio xi < 1.

    m x'' + c x' + k x = 0, x(0) = 0, x'(0) = v: x = (v / b) e^(-a t) sin(b t), a = xi omega,
    b = omega sqrt(1 - xi^2). The force k x + c x' = -m x'' vanishes (the bodies separate,
    the contact cannot pull) when x'' = 0, i.e. tan(b t) = 2 a b / (a^2 - b^2) = -tan(2 phi),
    r = a / b = tan(phi): b t = pi - 2 phi. There x' = v e^(-r (pi - 2 phi)) (cos(b t) -
    r sin(b t)) = -v e^(-r (pi - 2 phi)), so COR = exp(-r (pi - 2 atan r))."""
    r = xi / math.sqrt(1 - xi * xi)
    return math.exp(-r * (math.pi - 2 * math.atan(r)))


@dataclass(frozen=True)
class RadialWall:
    """The circular moat's wall law (see the module docstring).

    law "linear": F = max(k delta + dashpot delta', 0) (k N/m, dashpot N s/m); law "bumper":
    F_A = k min(delta, delta_u)^n + k_w max(delta - delta_u, 0) (k N/m^n, delta_u m, k_w N/m),
    in restitution F_A (1 + C_imp delta') floored at 0, C_imp = c_imp_coef /
    v_imp^c_imp_exponent (s/m). clear_gap: from the slab at rest to the contact surface (m).
    """

    law: str
    clear_gap: float
    k: float
    n: float = 1.0
    dashpot: float = 0.0
    delta_u: float = math.inf
    k_w: float = 0.0
    c_imp_coef: float = 0.0
    c_imp_exponent: float = 0.0

    def __post_init__(self):
        if self.law not in ("linear", "bumper"):
            raise ValueError(f"law must be 'linear' or 'bumper', got {self.law!r}")

    @classmethod
    def linear(cls, gap, k=2.5e9, cor=0.5, m_eff=320e3) -> RadialWall:
        """Eq. 1-2 with the damping ratio that realises `cor` without tension."""
        xi = 0.0 if cor >= 1 else brentq(lambda x: cor_no_tension(x) - cor, 0.0, 1 - 1e-12,
                                         xtol=1e-15)
        return cls("linear", float(gap), float(k), dashpot=2 * xi * math.sqrt(k * m_eff))

    @classmethod
    def bumper(cls, gap, thickness=0.05, strain=0.8, n_bumpers=4, k_w=1.5e9, cor=0.45,
               m_eff=320e3, cavity=0.0, area=0.15 * 0.15, k_r=55.835e6, n=2.65,
               alpha=2.25) -> RadialWall:
        """The paper's bumpers: Eq. 11-12 for k_imp, Eq. 9 for C_imp, section 2's geometry."""
        protrusion = thickness - cavity
        k_imp = alpha * n_bumpers * area * k_r / thickness**n
        coef = 1.55 * (1 - cor**2) / (cor**0.7076 * m_eff**0.0025)
        return cls("bumper", gap - protrusion, k_imp, n, delta_u=min(strain * thickness,
                                                                     protrusion),
                   k_w=k_w, c_imp_coef=coef, c_imp_exponent=0.9755)


class _Contact:
    """One contact's discrete state (v_imp, approach / restitution, crushed, floored) and the
    smooth branch of the law it selects; delta, rate floats or arrays."""

    def __init__(self, wall: RadialWall, v_imp: float):
        self.wall, self.v_imp = wall, v_imp
        self.bumper = wall.law == "bumper"
        self.damp = wall.c_imp_coef / v_imp**wall.c_imp_exponent if self.bumper else 0.0
        self.approach, self.crushed, self.floored = True, False, False

    def force(self, delta, rate):
        """F (N) on this branch at indentation delta (m) and rate delta' (m/s)."""
        w = self.wall
        if self.floored:
            return 0.0 * delta
        if not self.bumper:
            return w.k * delta + w.dashpot * rate
        d = np.maximum(delta, 0.0)
        f_a = (w.k * w.delta_u**w.n + w.k_w * (d - w.delta_u)) if self.crushed else w.k * d**w.n
        return f_a if self.approach else f_a * (1 + self.damp * rate)

    def events(self):
        """[(name, g(delta, rate), direction)] that end this branch (g in m, m/s or 1)."""
        w = self.wall
        out = [("release", lambda d, r: d, -1)]
        if not self.bumper:
            if w.dashpot > 0:  # without a dashpot the force reaches 0 only at release
                ratio = w.dashpot / w.k  # s: the force over k, in m
                out.append(("floor", lambda d, r: d + ratio * r, 1 if self.floored else -1))
            return out
        out.append(("crush", lambda d, r: d - w.delta_u, -1 if self.crushed else 1))
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


def _split(y, n):
    """u, v (2, n, ...) from a state y (4n + 1,) or (4n + 1, T): x then y components."""
    rest = y.shape[1:]
    return y[:2 * n].reshape((2, n) + rest), y[2 * n:4 * n].reshape((2, n) + rest)


def _unit(phi):
    """(2, ...) unit vector at angle phi (rad)."""
    return np.stack([np.cos(phi), np.sin(phi)])


class _CoupledSlip:
    """The isolator's slip element (level 0) with a circular yield surface and the
    associative flow rule: elastic from the anchor (u_a, f_a), or plastic, f = L n(phi) with
    phi = y[-1]. The limit L(speed) is constant for the bilinear isolator, W mu(speed) for the
    friction pendulum (`slow_drop` > 0)."""

    label = "isolator"

    def __init__(self, n, k, limit, slow_drop=0.0, rate=0.0):
        self.n, self.k, self.l0 = n, float(k), float(limit)  # L(inf) = l0
        self.drop, self.rate = float(slow_drop), float(rate)  # L(s) = l0 (1 - drop e^-rate s)
        self.plastic = False
        self.u_a, self.f_a = np.zeros(2), np.zeros(2)

    def limit(self, speed):
        return self.l0 * (1 - self.drop * np.exp(-self.rate * speed))

    def limit_slope(self, speed):
        """dL / d speed (N s/m)."""
        return self.l0 * self.drop * self.rate * np.exp(-self.rate * speed)

    def force(self, y):
        """(2, ...) force (N) on the slab's element, resisting u_0."""
        u, v = _split(y, self.n)
        if self.plastic:
            return self.limit(np.hypot(v[0, 0], v[1, 0])) * _unit(y[-1])
        shape = (2,) + (1,) * (y.ndim - 1)
        return self.f_a.reshape(shape) + self.k * (u[:, 0] - self.u_a.reshape(shape))

    def phase_rate(self, y):
        """phi' (rad/s): the force turning on the circle; 0 in the elastic phase."""
        if not self.plastic:
            return 0.0 * y[-1]
        v0 = _split(y, self.n)[1][:, 0]
        tangential = -np.sin(y[-1]) * v0[0] + np.cos(y[-1]) * v0[1]
        return self.k * tangential / self.limit(np.hypot(v0[0], v0[1]))

    def events(self, accel):
        """[(name, g(t, y), direction)] that end this phase; accel(t, y) -> (2, n, ...) relative
        accelerations (m/s^2)."""
        n = self.n
        if not self.plastic:
            def reach(t, y):
                v0 = _split(y, n)[1][:, 0]
                f = self.force(y)
                return np.hypot(f[0], f[1]) / self.l0 - self.limit(np.hypot(v0[0], v0[1])) \
                    / self.l0
            return [("yield", reach, 1)]

        def leave(t, y):
            # lambda = n . u_0' - L' / k, L' = dL/ds (v_0 . v_0') / |v_0|: in m/s
            v0 = _split(y, n)[1][:, 0]
            along = np.cos(y[-1]) * v0[0] + np.sin(y[-1]) * v0[1]
            if not self.drop:
                return along
            a0 = accel(t, y)[:, 0]
            speed = np.hypot(v0[0], v0[1])
            rate_of_speed = (v0[0] * a0[0] + v0[1] * a0[1]) / np.maximum(speed, 1e-300)
            return along - self.limit_slope(speed) * rate_of_speed / self.k

        return [("unload", leave, -1)]

    def switch(self, name, t, y) -> None:
        """Apply an event at the state y (modified in place: phi)."""
        if name == "yield":
            f = self.force(y)
            y[-1] = math.atan2(float(f[1]), float(f[0]))
            self.plastic = True
        else:  # unload / stick: elastic from the force of this instant
            self.f_a = np.asarray(self.force(y), dtype=float).copy()
            self.u_a = _split(y, self.n)[0][:, 0].astype(float).copy()
            self.plastic = False


class _Model:
    """The equations of motion in plan: the building, its slip element, the circular wall and
    the current segment of a_g (2-vector)."""

    def __init__(self, bld, wall: RadialWall | None):
        self.n = n = bld.n_levels
        iso = bld.isolator
        self.k_lin = np.r_[iso["k_linear"], bld.story_k]  # element j joins level j-1 to j
        self.c = np.r_[bld.c_iso, bld.story_c]
        self.m = bld.masses
        if iso["kind"] == "bilinear":
            self.slip = _CoupledSlip(n, iso["k_plastic"], iso["f_plastic"])
        else:
            w = iso["weight"]
            self.slip = _CoupledSlip(n, iso["k0"], w * iso["mu_fast"],
                                     1 - iso["mu_slow"] / iso["mu_fast"], iso["rate"])
        self.wall, self.contact = wall, None
        self.a_i, self.slope, self.t_i = np.zeros(2), np.zeros(2), 0.0

    def radial(self, y):
        """Radial indentation delta (m) and its rate (m/s), and n_r (2, ...)."""
        u, v = _split(y, self.n)
        radius = np.hypot(u[0, 0], u[1, 0])
        normal = u[:, 0] / np.maximum(radius, 1e-300)
        return radius - self.wall.clear_gap, np.sum(normal * v[:, 0], axis=0), normal

    def wall_force(self, y):
        """Contact force F (N, along -n_r on the slab) on the current branch, 0 out of
        contact."""
        if self.contact is None:
            return 0.0 * y[0]
        delta, rate, _ = self.radial(y)
        return self.contact.force(delta, rate)

    def element_forces(self, y):
        """(2, n, ...) force in each element j (0: isolator, dashpot and wall; j: story j),
        positive when it resists a positive deformation."""
        u, v = _split(y, self.n)
        du, dv = u.copy(), v.copy()
        du[:, 1:] -= u[:, :-1]
        dv[:, 1:] -= v[:, :-1]
        shape = (1, self.n) + (1,) * (y.ndim - 1)
        f = self.k_lin.reshape(shape) * du + self.c.reshape(shape) * dv
        f[:, 0] += self.slip.force(y)
        if self.contact is not None:
            delta, rate, normal = self.radial(y)
            f[:, 0] += normal * self.contact.force(delta, rate)
        return f

    def total_accel(self, y):
        """(2, n, ...) total accelerations (m/s^2): net force on each level over its mass."""
        f = self.element_forces(y)
        above = np.zeros_like(f)
        above[:, :-1] = f[:, 1:]
        return (above - f) / self.m.reshape((1, self.n) + (1,) * (y.ndim - 1))

    def accel(self, t, y):
        """(2, n, ...) relative accelerations at time(s) t in the current a_g segment."""
        shape = (2, 1) + (1,) * (y.ndim - 1)
        ground = self.a_i.reshape(shape) + self.slope.reshape(shape) * (np.asarray(t) - self.t_i)
        return self.total_accel(y) - ground

    def rhs(self, t, y):
        n = self.n
        return np.concatenate([y[2 * n:4 * n], self.accel(t, y).reshape(2 * n),
                               [self.slip.phase_rate(y)]])

    def wall_events(self):
        """[(name, g(t, y), direction)] of the wall: touch when free, the branch's kinks and
        release in contact."""
        if self.contact is None:
            return [("touch", lambda t, y: self.radial(y)[0], 1)]
        return [(name, (lambda t, y, g=g: g(*self.radial(y)[:2])), direction)
                for name, g, direction in self.contact.events()]


def _event(fun, direction):
    fun.terminal = True
    fun.direction = direction
    return fun


# An armed event's function may not be on its far side anywhere on the sampled grid by more
# than this (m, m/s or 1): a check that no switch went unnoticed between two solver steps.
_MISSED_EVENT_TOL = 1e-7


def simulate(pair, pair_dt, wall: RadialWall | None = None, t_end=None, rtol=1e-9,
             max_step_contact=1e-3, sample_dt=1e-4, *, masses=None, story_k=None,
             isolator=None, zeta_iso=None, zeta_sup=0.02, max_step=np.inf) -> dict:
    """Integrate the building under the pair (T, 2) m/s^2 (x, y every pair_dt s) over
    [0, t_end] (default: the whole pair), in the circular moat `wall` (None: no wall).

    masses, story_k, isolator, zeta_iso, zeta_sup: the building, see
    ``independent_building.make_building`` (defaults: the paper's). rtol: solve_ivp's (absolute
    1e-12 m, 1e-10 m/s, 1e-12 rad); max_step_contact: the largest solver step in contact (s);
    max_step: out of contact; sample_dt: about the step of the grid on which peaks are taken.
    Returns the peaks named in the module docstring.
    """
    pair = np.asarray(pair, dtype=float)
    if pair.ndim != 2 or pair.shape[1] != 2 or pair.shape[0] < 2:
        raise ValueError(f"pair must be (T, 2) with T >= 2, got {pair.shape}")
    bld = make_building(masses, story_k, isolator, None, 0.02, zeta_iso, zeta_sup)
    model = _Model(bld, wall)
    n = model.n
    duration = (pair.shape[0] - 1) * pair_dt
    t_end = duration if t_end is None else min(float(t_end), duration)
    h = pair_dt / max(1, round(pair_dt / sample_dt))  # every record sample is on the grid
    atol = np.r_[np.full(2 * n, 1e-12), np.full(2 * n, 1e-10), 1e-12]
    peaks = _Peaks(n)
    t, y = 0.0, np.zeros(4 * n + 1)
    stats = {"n_solver_steps": 0, "n_retries": 0, "switches": {"isolator": 0}}
    stalled, first_step = 0, None
    while t < t_end - 1e-12:
        i = min(int(math.floor(t / pair_dt + 1e-9)), pair.shape[0] - 2)
        model.t_i, t_stop = i * pair_dt, min((i + 1) * pair_dt, t_end)
        model.a_i, model.slope = pair[i].copy(), (pair[i + 1] - pair[i]) / pair_dt
        armed = [(name, g, d, model.slip) for name, g, d in model.slip.events(model.accel)]
        if wall is not None:
            armed += [(name, g, d, None) for name, g, d in model.wall_events()]
        bound = max_step_contact if model.contact is not None else max_step
        sol, grid, yy = _call(model, t, t_stop, y, armed, rtol, atol, bound, first_step, h,
                              stats)
        t_new = float(sol.t[-1])
        if sol.t.size > 2:
            first_step = sol.t[-2] - sol.t[-3] if sol.status == 1 else sol.t[-1] - sol.t[-2]
        stalled = stalled + 1 if t_new - t < 1e-12 else 0
        if stalled > 20:
            raise RuntimeError(f"events chatter at t = {t} s: {[a[0] for a in armed]}")
        peaks.add(model, yy)
        y, t = sol.y[:, -1].copy(), t_new
        if sol.status == 1:
            _apply_events(model, sol, armed, t, y, peaks, stats)
    return {**peaks.result(), **stats}


def _call(model, t, t_stop, y, armed, rtol, atol, bound, first_step, h, stats):
    """One solve_ivp call from (t, y) to t_stop or the first armed event, redone with shorter
    steps while an armed switch shows crossed on the sampled grid. Returns the solution, the
    grid (s) of [t, t_end] and the states on it."""
    events = [_event(g, direction) for _, g, direction, _ in armed]
    while True:
        step0 = None if first_step is None else min(first_step, t_stop - t, bound)
        sol = solve_ivp(model.rhs, (t, t_stop), y, method="DOP853", rtol=rtol, atol=atol,
                        max_step=bound, first_step=step0, events=events, dense_output=True)
        if sol.status < 0:
            raise RuntimeError(f"solve_ivp failed at t = {t}: {sol.message}")
        t_new = float(sol.t[-1])
        k0, k1 = math.ceil(t / h - 1e-9), math.floor(t_new / h + 1e-9)
        grid = np.unique(np.r_[t, np.arange(k0, k1 + 1) * h, t_new].clip(t, t_new))
        yy = sol.sol(grid)
        missed = [name for name, g, direction, _ in armed
                  if np.min(-direction * g(grid, yy)) < -_MISSED_EVENT_TOL]
        stats["n_solver_steps"] += sol.t.size - 1
        if not missed:
            return sol, grid, yy
        bound = min(bound, float(sol.t[-1] - sol.t[0])) / 4
        stats["n_retries"] += 1
        if bound < 1e-7:
            raise RuntimeError(f"missed event {missed} between t = {t} and {t_new} s")


def _apply_events(model, sol, armed, t, y, peaks, stats):
    """The event that ended the call, then every other armed one that the same instant carries
    past its zero; one switch of the isolator per instant. y is modified in place."""
    fired = next(j for j, te in enumerate(sol.t_events) if te.size)
    todo = [armed[fired]] + [a for j, a in enumerate(armed)
                             if j != fired and -a[2] * a[1](t, y) < 0]
    switched = False
    for name, _, _, part in todo:
        if part is not None:
            if not switched:
                part.switch(name, t, y)
                stats["switches"]["isolator"] += 1
                switched = True
        elif name == "touch":
            _, rate, _ = model.radial(y)
            model.contact = _Contact(model.wall, float(rate))
            peaks.touch(t, float(rate))
        elif name == "release":
            model.contact = None
        else:
            model.contact.switch(name)


class _Peaks:
    """The running peaks of one run."""

    def __init__(self, n):
        self.accel, self.accel_xy = np.zeros(n), np.zeros((n, 2))
        self.drift, self.drift_xy = np.zeros(n - 1), np.zeros((n - 1, 2))
        self.disp, self.disp_xy = 0.0, np.zeros(2)
        self.impacts: list[dict] = []

    def touch(self, t, v_imp):
        self.impacts.append({"t": t, "v_imp": v_imp, "max_indentation": 0.0, "max_force": 0.0})

    def add(self, model, yy):
        """Raise the peaks with the states yy (4n + 1, T) of the current branch."""
        u, _ = _split(yy, model.n)
        accel = model.total_accel(yy)  # (2, n, T)
        drift = np.diff(u, axis=1)
        self.accel = np.maximum(self.accel, np.hypot(accel[0], accel[1]).max(axis=-1))
        self.accel_xy = np.maximum(self.accel_xy, np.abs(accel).max(axis=-1).T)
        self.drift = np.maximum(self.drift, np.hypot(drift[0], drift[1]).max(axis=-1))
        self.drift_xy = np.maximum(self.drift_xy, np.abs(drift).max(axis=-1).T)
        self.disp = max(self.disp, float(np.hypot(u[0, 0], u[1, 0]).max()))
        self.disp_xy = np.maximum(self.disp_xy, np.abs(u[:, 0]).max(axis=-1))
        if model.contact is not None:
            delta = model.radial(yy)[0]
            impact = self.impacts[-1]
            impact["max_indentation"] = max(impact["max_indentation"], float(delta.max()))
            impact["max_force"] = max(impact["max_force"],
                                      float(np.max(model.wall_force(yy))))

    def result(self) -> dict:
        force = max((c["max_force"] for c in self.impacts), default=0.0)
        return {"peak_total_accel": self.accel, "peak_interstory_drift": self.drift,
                "peak_isolator_disp": self.disp, "peak_total_accel_xy": self.accel_xy,
                "peak_interstory_drift_xy": self.drift_xy, "peak_isolator_disp_xy": self.disp_xy,
                "max_indentation": max((c["max_indentation"] for c in self.impacts),
                                       default=0.0),
                "max_impact_force": force, "n_impacts": len(self.impacts),
                "max_impact_force_wall": np.array([force]), "impacts": self.impacts}
