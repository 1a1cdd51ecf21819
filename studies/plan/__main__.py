"""`python -m studies.plan`: the recipe's command line."""
from . import main

raise SystemExit(main())
