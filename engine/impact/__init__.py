"""Moat-wall impacts: the laws, how they declare their parameters, and the Contact built from
them.

    laws/          one module per impact law (its physics `force_terms`, its PARAMETERS, ...);
                   every module there is a law: see laws/__init__.py for what it holds
    registry.py    the laws found in laws/, their names and the codes the time loops use
    parameters.py  how a law declares a parameter (unit, valid range, default, meaning, the
                   paper's equation, its name in sweeps), once
    contact.py     Contact: a batch's walls as (B,) arrays, built from the declarations
    calibration.py damping that makes Hunt-Crossley-type laws realise a COR exactly

The implicit contact solve and the onset weighting, shared by the time loops, are part of the
integration scheme (engine/scheme.py).
"""
from .contact import Contact
from .parameters import GAP, M_EFF, REQUIRED, Declaration, Option, Parameter
from .registry import LAW_CODES, LAW_NAMES, LAWS, NO_WALL, NONE

__all__ = ["GAP", "LAWS", "LAW_CODES", "LAW_NAMES", "M_EFF", "NONE", "NO_WALL", "REQUIRED",
           "Contact", "Declaration", "Option", "Parameter"]
