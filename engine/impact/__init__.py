"""Moat-wall impact laws, one module each, and `Contact`: the per-member wall description.

Every law is affine in the indentation rate at a given indentation and phase, so each module
offers the same pure functions over (B,) arrays:
    force_terms(delta, delta_dot, v_imp, p) -> (elastic force N, dashpot N*s/m)
        with F = max(elastic + dashpot * delta_dot, 0); delta_dot only selects the phase;
    max_tangent_stiffness(p, indentation_bound) -> N/m
where p is a `Contact` (or a slice of one) holding that law's members. Integrators put the
dashpot on the central velocity (see integrate.py); `force` evaluates a law directly.
"""
from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np

from ..errors import EngineError
from . import hertzdamp, jankowski, linear_viscoelastic, rubber_bumper

NONE, LINEAR, JANKOWSKI, HERTZDAMP, BUMPER = range(5)
LAW_NAMES = {NONE: "none", LINEAR: "linear", JANKOWSKI: "jankowski", HERTZDAMP: "hertzdamp",
             BUMPER: "bumper"}
LAW_MODULES = {LINEAR: linear_viscoelastic, JANKOWSKI: jankowski, HERTZDAMP: hertzdamp,
               BUMPER: rubber_bumper}

DEFAULT_M_EFF = 320e3  # kg: the base slab against an immovable wall (SPEC decision)


@dataclass(frozen=True)
class Contact:
    """Moat-wall contact for a batch of B members; every field is a (B,) array.

    law: int code (NONE, LINEAR, JANKOWSKI, HERTZDAMP, BUMPER); gap: clear gap to the contact
    surface on either side, m (inf for NONE); k: contact stiffness (N/m^n); n: exponent;
    cor: coefficient of restitution; m_eff: kg; delta_u: indentation at which the bumper is
    crushed, m (inf otherwise); k_w: wall stiffness past delta_u, N/m; coef, vexp: the law's
    damping constants (see each module).
    """

    law: np.ndarray
    gap: np.ndarray
    k: np.ndarray
    n: np.ndarray
    cor: np.ndarray
    m_eff: np.ndarray
    delta_u: np.ndarray
    k_w: np.ndarray
    coef: np.ndarray
    vexp: np.ndarray

    def __len__(self) -> int:
        return len(self.law)

    def __getitem__(self, index) -> Contact:
        if isinstance(index, (int, np.integer)):
            index = [index]
        return Contact(*(getattr(self, f.name)[index] for f in fields(self)))

    @property
    def law_names(self) -> list[str]:
        return [LAW_NAMES[int(c)] for c in self.law]

    @classmethod
    def concat(cls, parts) -> Contact:
        parts = list(parts)
        if not parts:
            raise EngineError("Contact.concat needs at least one Contact")
        return cls(*(np.concatenate([getattr(p, f.name) for p in parts]) for f in fields(cls)))

    @classmethod
    def _build(cls, law, **values) -> Contact:
        arrays = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in values.values()))
        shape = arrays[0].shape
        if len(shape) > 1:
            raise EngineError(
                f"contact parameters must be scalars or 1-D arrays, got shape {shape}")
        arrays = [np.atleast_1d(a).copy() for a in arrays]
        named = dict(zip(values, arrays, strict=True))
        for name, a in named.items():
            if np.any(np.isnan(a)):
                raise EngineError(f"{name} contains NaN")
        return cls(law=np.full(arrays[0].shape, law, dtype=np.int8), **named)

    @classmethod
    def none(cls, size: int = 1) -> Contact:
        """No moat wall: the unconstrained building."""
        inf, zero, one = np.full(size, np.inf), np.zeros(size), np.ones(size)
        return cls(law=np.full(size, NONE, dtype=np.int8), gap=inf, k=zero, n=one, cor=one,
                   m_eff=one, delta_u=inf, k_w=zero, coef=zero, vexp=one)

    @classmethod
    def linear(cls, gap, k=2.5e9, cor=0.5, m_eff=DEFAULT_M_EFF, xi_rule="no_tension") -> Contact:
        """Linear viscoelastic wall, Eq. 1-3: gap m, k N/m (paper: 2500 kN/mm), COR 0.5."""
        _check_rule("xi_rule", xi_rule, linear_viscoelastic.XI_RULES)
        _check_positive(gap=gap, k=k, m_eff=m_eff)
        _check_cor(cor)
        c = cls._build(LINEAR, gap=gap, k=k, n=1.0, cor=cor, m_eff=m_eff, delta_u=np.inf,
                       k_w=0.0, coef=0.0, vexp=0.0)
        coef = linear_viscoelastic.damping_coefficient(c.k, c.cor, c.m_eff, xi_rule)
        return _replace(c, coef=coef)

    @classmethod
    def jankowski(cls, gap, beta, cor=0.5, m_eff=DEFAULT_M_EFF) -> Contact:
        """Nonlinear viscoelastic wall (Jankowski 2005): gap m, beta N/m^1.5."""
        _check_positive(gap=gap, beta=beta, m_eff=m_eff)
        _check_cor(cor)
        c = cls._build(JANKOWSKI, gap=gap, k=beta, n=jankowski.EXPONENT, cor=cor, m_eff=m_eff,
                       delta_u=np.inf, k_w=0.0, coef=0.0, vexp=0.0)
        return _replace(c, coef=jankowski.damping_ratio(c.cor))

    @classmethod
    def hertzdamp(cls, gap, k, n=1.5, cor=0.5, m_eff=DEFAULT_M_EFF, chi_rule="lankarani"):
        """Hertzdamp wall (Muthukumar & DesRoches 2006): gap m, k N/m^n."""
        _check_rule("chi_rule", chi_rule, hertzdamp.CHI_RULES)
        _check_positive(gap=gap, k=k, m_eff=m_eff)
        _check_exponent(n)
        _check_cor(cor)
        c = cls._build(HERTZDAMP, gap=gap, k=k, n=n, cor=cor, m_eff=m_eff, delta_u=np.inf,
                       k_w=0.0, coef=0.0, vexp=1.0)
        return _replace(c, coef=hertzdamp.chi(c.cor, c.n, chi_rule))

    @classmethod
    def bumper(cls, gap, thickness=0.05, strain=0.8, n_bumpers=4, k_w=1.5e9, cor=0.45,
               m_eff=DEFAULT_M_EFF, cavity=0.0, area=rubber_bumper.BUMPER_AREA,
               k_r=rubber_bumper.K_R, n=rubber_bumper.EXPONENT, alpha=rubber_bumper.ALPHA,
               c_imp_rule="eq9", c_imp=None) -> Contact:
        """Rubber bumpers on the wall (the paper's model), SPEC section 2.

        gap: slab-to-wall clearance before bumpers (m); thickness t (m); strain: ultimate
        compressive strain; n_bumpers per side (in parallel); k_w: wall stiffness (N/m);
        cavity: depth c_d (m) of the wall recess holding each bumper; area (m^2), k_r (Pa),
        n, alpha: Eq. 11-12. The engine uses gap_eff = gap - (t - c_d) and
        delta_u = min(strain t, t - c_d). c_imp_rule: "eq9" (the paper's C_imp) or
        "calibrated" (realises the COR exactly); c_imp: a fixed C_imp in s/m instead, the
        same at every impact velocity (for re-deriving Eq. 9, section 3.2).
        """
        _check_rule("c_imp_rule", c_imp_rule, rubber_bumper.C_IMP_RULES)
        _check_positive(gap=gap, thickness=thickness, k_w=k_w, m_eff=m_eff, area=area, k_r=k_r,
                        alpha=alpha)
        _check_exponent(n)
        _check_cor(cor)
        strain, n_bumpers, cavity = (np.asarray(x, dtype=float)
                                     for x in (strain, n_bumpers, cavity))
        if np.any((strain <= 0) | (strain > 1)):
            raise EngineError(f"strain must be in (0, 1], got {strain}")
        if np.any(n_bumpers < 1) or np.any(n_bumpers != np.round(n_bumpers)):
            raise EngineError(f"n_bumpers must be a whole number >= 1, got {n_bumpers}")
        if np.any((cavity < 0) | (cavity >= thickness)):
            raise EngineError(f"cavity must be in [0, thickness), got {cavity}")
        protrusion = np.asarray(thickness) - cavity
        if np.any(protrusion >= np.asarray(gap)):
            raise EngineError("thickness - cavity must be smaller than gap: the bumpers would "
                              f"close the gap (gap {gap}, thickness {thickness}, cavity {cavity})")
        k_imp = rubber_bumper.impact_stiffness(area, thickness, k_r, n, alpha, n_bumpers)
        delta_u = np.minimum(strain * np.asarray(thickness), protrusion)
        if c_imp is not None:
            _check_positive(c_imp=c_imp)
        c = cls._build(BUMPER, gap=np.asarray(gap) - protrusion, k=k_imp, n=n, cor=cor,
                       m_eff=m_eff, delta_u=delta_u, k_w=k_w,
                       coef=0.0 if c_imp is None else c_imp, vexp=0.0)
        if c_imp is not None:
            return c
        coef, vexp = rubber_bumper.damping_constants(c.cor, c.m_eff, c.n, c_imp_rule)
        return _replace(c, coef=coef, vexp=vexp)

    def max_tangent_stiffness(self, indentation_bound: float) -> np.ndarray:
        """(B,) stiffest contact tangent (N/m) each member can reach; 0 without a wall."""
        out = np.zeros(len(self))
        for code, module in LAW_MODULES.items():
            sel = self.law == code
            if np.any(sel):
                out[sel] = module.max_tangent_stiffness(self[np.flatnonzero(sel)],
                                                        indentation_bound)
        return out



def law_blocks(contact: Contact):
    """Order members by law so that each law runs on a contiguous view.

    Returns (order, blocks): `contact[order]` is the sorted batch and `blocks` lists
    (slice into the sorted batch, law module, that block's Contact).
    """
    order = np.argsort(contact.law, kind="stable")
    law = contact.law[order]
    blocks = []
    for code, module in LAW_MODULES.items():
        idx = np.flatnonzero(law == code)
        if idx.size:
            block = slice(idx[0], idx[-1] + 1)
            blocks.append((block, module, contact[order[block]]))
    return order, blocks


def fill_force_terms(blocks, delta, delta_dot, v_imp, elastic, dashpot):
    """Evaluate every law on its block of the sorted batch into elastic and dashpot, (B,)."""
    for block, module, params in blocks:
        elastic[block], dashpot[block] = module.force_terms(
            delta[block], delta_dot[block], v_imp[block], params)


def force(module, delta, delta_dot, v_imp, p):
    """Contact force (N, >= 0) of one law at indentation delta (m), rate delta_dot (m/s)."""
    elastic, dashpot = module.force_terms(delta, delta_dot, v_imp, p)
    return np.where(delta > 0, np.maximum(elastic + dashpot * delta_dot, 0.0), 0.0)


def implicit_force(elastic, dashpot, delta_dot_free, compliance):
    """Contact force (N, >= 0) with the dashpot on the central velocity, solved exactly.

    delta_dot_free: the central indentation rate if no contact force acted this step (m/s);
    compliance: how much one newton of contact force lowers the next half-step velocity, hence
    twice what it lowers the central rate (m/s/N). Because the
    force is affine in the rate, F = (elastic + dashpot * delta_dot_free) /
    (1 + dashpot * compliance / 2) keeps the sign of the explicit estimate, so clipping at
    zero (no tension) stays consistent.
    """
    trial = elastic + dashpot * delta_dot_free
    return np.maximum(trial / (1 + 0.5 * dashpot * compliance), 0.0)


def _replace(contact: Contact, **arrays) -> Contact:
    values = {f.name: getattr(contact, f.name) for f in fields(contact)}
    values.update({k: np.broadcast_to(np.asarray(v, float), contact.law.shape).copy()
                   for k, v in arrays.items()})
    return Contact(**values)


def _check_positive(**values):
    for name, v in values.items():
        v = np.asarray(v, dtype=float)
        if np.any(~(v > 0)):
            raise EngineError(f"{name} must be positive, got {v}")


def _check_cor(cor):
    cor = np.asarray(cor, dtype=float)
    if np.any(~((cor > 0) & (cor <= 1))):
        raise EngineError(f"cor must be in (0, 1], got {cor}")


def _check_exponent(n):
    if np.any(~(np.asarray(n, dtype=float) >= 1)):
        raise EngineError(f"exponent n must be >= 1, got {n}")


def _check_rule(name, value, allowed):
    if value not in allowed:
        raise EngineError(f"{name} must be one of {allowed}, got {value!r}")
