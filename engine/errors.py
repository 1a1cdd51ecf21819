"""Errors raised by the engine for bad input: never a silent wrong answer."""


class EngineError(ValueError):
    """Invalid engine input; the message names the offending parameter."""


class UnstableTimeStep(EngineError):
    """The integration step exceeds the central-difference stability limit."""
