"""`python -m studies.loss`: the recipe's command line."""
from . import main

raise SystemExit(main())
