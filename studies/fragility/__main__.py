"""`python -m studies.fragility`: the recipe's command line."""
from . import main

raise SystemExit(main())
