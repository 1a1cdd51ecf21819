"""`Contact`: the moat wall of a batch of members, as (B,) arrays the time loops read.

Built from a law's declared parameters (`Contact.of(law, ...)` or the constructor named after
the law, e.g. `Contact.bumper(gap, ...)`: one per law of the registry, its signature and
docstring generated from the law's declaration). A law's `force_terms` takes the fields named
in its ROW packed into one row (law_rows for the compiled loops, law_arguments for the NumPy
loops), so that one call signature serves every law whatever constants it needs.
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass, fields

import numpy as np

from ..errors import EngineError
from ..parameters import Declaration, Parameter, law_constructor
from .registry import LAW_CODES, LAW_MODULES, LAW_NAMES, LAWS, NONE, ROW_WIDTH

LAW_ARGUMENTS = ("k", "n", "m_eff", "delta_u", "k_w", "dashpot", "damping_ratio", "chi",
                 "c_imp_coef", "c_imp_exponent")
"""The Contact fields the laws' rows draw on (each law's ROW names those it reads)."""

SHARED_ARGUMENTS = ("k", "m_eff", "dashpot")
"""The Contact fields scaled by the part of a wall a contact point carries (Contact.part):
every law's force short of crushing is proportional to them jointly (tests/engine/test_torsion.py
checks each registered law). Not k_w: past a pad's crushing the slab bears on the wall itself
at that point, and meets the wall's own stiffness there however many pads the wall carries."""

# Contact fields a law leaves unset, and their neutral values.
_UNSET = {"delta_u": np.inf, "k_w": 0.0, "dashpot": 0.0, "damping_ratio": 0.0, "chi": 0.0,
          "c_imp_coef": 0.0, "c_imp_exponent": 0.0}


@dataclass(frozen=True)
class Contact:
    """Moat-wall contact for a batch of B members; every field is a (B,) array.

    law: int code (registry.LAW_CODES); clear_gap: clearance from the slab to the contact
    surface on either side, m (gap - (thickness - cavity) with bumpers; inf without a wall);
    k: the law's stiffness (N/m^n: the linear k, Jankowski's beta, Hertzdamp's k, the
    bumpers' k_imp); n: its exponent; cor: coefficient of restitution; m_eff: kg; delta_u:
    indentation at which the bumpers are crushed, m (inf otherwise); k_w: wall stiffness past
    delta_u, N/m. The damping constants,
    each used by one law (0 for the others): dashpot (linear, N*s/m), damping_ratio
    (Jankowski's xi), chi (Hertzdamp), c_imp_coef and c_imp_exponent (bumper: C_imp =
    c_imp_coef / v_imp^c_imp_exponent, s/m).

    Build one with a law's constructor, one per registered law and named after it
    (`Contact.bumper(gap, ...)`, `linear`, `jankowski`, `hertzdamp`; their parameters are
    declared in each law's module), `Contact.of(law, ...)` or `Contact.none(size)`.
    """

    law: np.ndarray
    clear_gap: np.ndarray
    k: np.ndarray
    n: np.ndarray
    cor: np.ndarray
    m_eff: np.ndarray
    delta_u: np.ndarray
    k_w: np.ndarray
    dashpot: np.ndarray
    damping_ratio: np.ndarray
    chi: np.ndarray
    c_imp_coef: np.ndarray
    c_imp_exponent: np.ndarray

    def __len__(self) -> int:
        return len(self.law)

    def __getitem__(self, index) -> Contact:
        if isinstance(index, (int, np.integer)):
            index = [index]
        return Contact(*(getattr(self, f.name)[index] for f in fields(self)))

    def part(self, share) -> Contact:
        """This wall carried by a part of it, share (B,) or a number in (0, 1]: its law with
        SHARED_ARGUMENTS times share (one of a wall's contact points, engine/torsion.py), so
        that its force at any indentation short of delta_u, and at any rate, is share times
        the wall's; past delta_u the crushed pad's point adds the wall's own k_w (delta -
        delta_u), unshared."""
        return dataclasses.replace(self, **{name: getattr(self, name) * share
                                            for name in SHARED_ARGUMENTS})

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
    def none(cls, size: int = 1) -> Contact:
        """No moat wall: the unconstrained building."""
        inf, zero, one = np.full(size, np.inf), np.zeros(size), np.ones(size)
        return cls(law=np.full(size, NONE, dtype=np.int8), clear_gap=inf, k=zero, n=one,
                   cor=one, m_eff=one, delta_u=inf, k_w=zero, dashpot=zero.copy(),
                   damping_ratio=zero.copy(), chi=zero.copy(), c_imp_coef=zero.copy(),
                   c_imp_exponent=zero.copy())

    @classmethod
    def of(cls, law: str, **params) -> Contact:
        """A wall of the named law ("linear", "jankowski", "hertzdamp", "bumper") from its
        declared parameters (`LAWS[law].PARAMETERS`); omitted ones take their defaults.
        Numeric parameters are scalars or (B,) arrays, broadcast together."""
        if law not in LAWS:
            raise EngineError(f"unknown impact law {law!r}; choose one of {tuple(LAWS)}")
        declaration: Declaration = LAWS[law].PARAMETERS
        values = declaration.resolve(params)
        numeric = [n for n, e in declaration.items()
                   if isinstance(e, Parameter) and values[n] is not None]
        arrays = np.broadcast_arrays(*(values[n] for n in numeric))
        if arrays[0].ndim > 1:
            raise EngineError(
                f"contact parameters must be scalars or 1-D arrays, got shape {arrays[0].shape}")
        values.update(zip(numeric, (np.atleast_1d(a).copy() for a in arrays), strict=True))
        size = values["gap"].size
        physics = LAWS[law].contact_fields(**values)
        columns = {**_UNSET, "cor": values["cor"], "m_eff": values["m_eff"], **physics}
        return cls(law=np.full(size, LAW_CODES[law], dtype=np.int8),
                   **{name: np.broadcast_to(np.asarray(value, dtype=float), (size,)).copy()
                      for name, value in columns.items()})

    def max_tangent_stiffness(self, indentation_bound: float) -> np.ndarray:
        """(B,) stiffest contact tangent (N/m) each member can reach; 0 without a wall."""
        out = np.zeros(len(self))
        for code, module in LAW_MODULES.items():
            sel = self.law == code
            if np.any(sel):
                out[sel] = module.max_tangent_stiffness(self[np.flatnonzero(sel)],
                                                        indentation_bound)
        return out


def _build(cls, law, **arguments):
    return cls.of(law, **arguments)


for _name, _module in LAWS.items():
    setattr(Contact, _name, law_constructor(
        "Contact", _name, _module.PARAMETERS,
        f"A {_name} moat wall ({_module.__name__}); every parameter is a scalar or a (B,) "
        "array, broadcast together:", _build))


def law_blocks(contact: Contact):
    """Order members by law so that each law runs on a contiguous view.

    Returns (order, blocks): `contact[order]` is the sorted batch and `blocks` lists
    (slice into the sorted batch, law module, that block's law_arguments), the arguments
    gathered once rather than at every step of a time loop.
    """
    order = np.argsort(contact.law, kind="stable")
    law = contact.law[order]
    blocks = []
    for code, module in LAW_MODULES.items():
        idx = np.flatnonzero(law == code)
        if idx.size:
            block = slice(idx[0], idx[-1] + 1)
            blocks.append((block, module, law_arguments(contact[order[block]], module)))
    return order, blocks


def law_arguments(p: Contact, module) -> tuple:
    """The row the law of `module` takes after (delta, delta_dot, v_imp), for the NumPy loops:
    the (B,) Contact fields its ROW names, a tuple in ROW's order."""
    return tuple(getattr(p, name) for name in module.ROW._fields)


def law_rows(contact: Contact) -> np.ndarray:
    """(B, ROW_WIDTH) float64: each member's law row for the compiled loops, its law's ROW
    fields first (zeros after them, and for a member without wall)."""
    rows = np.zeros((len(contact), ROW_WIDTH))
    for code, module in LAW_MODULES.items():
        sel = np.flatnonzero(contact.law == code)
        for column, name in enumerate(module.ROW._fields):
            rows[sel, column] = getattr(contact, name)[sel]
    return rows


def fill_force_terms(blocks, delta, delta_dot, v_imp, elastic, dashpot):
    """Evaluate every law on its block of the sorted batch into elastic and dashpot, (B,)."""
    for block, module, arguments in blocks:
        elastic[block], dashpot[block] = module.force_terms(
            delta[block], delta_dot[block], v_imp[block], arguments)
