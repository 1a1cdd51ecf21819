"""`python -m studies.design`: the recipe's command line."""
from . import main

raise SystemExit(main())
