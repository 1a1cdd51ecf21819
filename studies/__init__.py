"""One recipe per figure of the paper, each `python -m studies.NAME [--quick] [--replot]`,
and `studies.sweep`, the general command line of pipeline.sweep.

_recipe.py holds what every recipe shares (command line, archive, figure, paper check),
_plot.py the figure style, _peaks_vs_gap.py the figure and checks of Figs. 16-21. Recipes
compute no physics: they choose grids, call the pipeline or the engine, and draw.
"""
