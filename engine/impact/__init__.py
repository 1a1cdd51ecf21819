"""Moat-wall impacts: the laws, how they declare their parameters, and the Contact built from
them.

    laws/          one module per impact law (its physics `force_terms`, its PARAMETERS, ...);
                   every module there is a law: see laws/__init__.py for what it holds
    registry.py    the laws found in laws/, their names and the codes the time loops use
    parameters.py  the parameters every wall law takes (gap, m_eff); how a law declares a
                   parameter is engine/parameters.py
    contact.py     Contact: a batch's walls as (B,) arrays, built from the declarations
    calibration.py damping that makes Hunt-Crossley-type laws realise a COR exactly

The implicit contact solve and the onset weighting, shared by the time loops, are part of the
integration scheme (engine/scheme.py).
"""
from ..parameters import REQUIRED, Declaration, Option, Parameter
from .contact import Contact
from .parameters import GAP, M_EFF
from .registry import LAW_CODES, LAW_NAMES, LAWS, NO_WALL, NONE

__all__ = ["GAP", "LAWS", "LAW_CODES", "LAW_NAMES", "M_EFF", "NONE", "NO_WALL", "REQUIRED",
           "Contact", "Declaration", "Option", "Parameter"]
