"""`python -m studies.torsion`: the recipe's command line."""
from . import main

raise SystemExit(main())
