"""`python -m studies.suite`: the recipe's command line."""
from . import main

raise SystemExit(main())
