"""The name a command goes by: `bumpers NAME` while the `bumpers` command runs it, else
`python -m MODULE` (studies/cli.py sets it; every command's parser reads it)."""
from __future__ import annotations

RUNNING: dict[str, str] = {}
"""module -> command name of the command `bumpers` is running (while it runs): read by
`program`, so that its help and errors name it as the user typed it."""


def program(module: str) -> str:
    """The program name a command's help, usage and errors show: `bumpers NAME` while the
    `bumpers` command runs it, else `python -m MODULE` (how it was run then)."""
    name = RUNNING.get(module)
    return f"bumpers {name}" if name else f"python -m {module}"
