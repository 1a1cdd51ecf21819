"""The stories' laws: one module each in stories/laws/ (linear, bilinear, imk), found by the
registry, and `Stories`, the law and parameters a building's stories follow."""
from .registry import LAWS
from .stories import Stories

__all__ = ["LAWS", "Stories"]
