"""``python -m pipeline.records``: see :func:`pipeline.records.cli.main`."""

import sys

from ..errors import closed_pipe
from .cli import main

if __name__ == "__main__":
    try:
        status = main()
    except BrokenPipeError:  # `python -m pipeline.records | head`
        status = closed_pipe()
    sys.exit(status)
