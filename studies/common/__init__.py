"""What every recipe shares: the recipe itself (its command line, archive, figure and verdicts),
the paper's fixed choices, the figure style, the options of the studies beyond the paper, and
the gap grid and checks of Figs. 16-21. Not a command."""
