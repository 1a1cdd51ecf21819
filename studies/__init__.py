"""Every command a user runs: one recipe per figure of the paper, `python -m studies.NAME
[--quick] [--replot]`, studies beyond the paper (suite, design, plan, torsion, fragility) and
`studies.sweep`, the general command line of pipeline.sweep. They share one set of
command-line conventions (common/recipe.py), which is why the general sweep lives here beside
the recipes.

Recipes, one module each or a package for a family of modules (suite/, design/, plan/,
torsion/, each still `python -m studies.NAME`), none importing another:
    impact_validation (Fig. 6), damping_calibration (Eq. 9), practical_example (Figs. 9-13),
    gap_size (Figs. 14-15), thickness (Fig. 16), strain (Fig. 18), n_bumpers (Figs. 19-20),
    wall_stiffness (Fig. 21), restitution (Fig. 22); suite, design, plan, torsion, fragility,
    collapse and loss (beyond the paper).
common/ (imported by the recipes, never run):
    paper.py          the paper's fixed choices, each with where the paper states it: the
                      practical bumper (thickness, count, strain, area, wall k_w), the 0.9 gap
                      rule, the paper's gaps, the gap range of Figs. 14-21, Fig. 19's counts,
                      Fig. 21's walls, Fig. 6's test. Values the paper leaves open stay in the
                      recipe that chooses them (its `chosen` text); the model's constants stay
                      in engine.impact (e.g. laws.rubber_bumper.EQ9_*, the laws' PARAMETERS).
    recipe.py         what every recipe shares: command line, archive, figure, paper check.
    plot.py           the figure style and record labels.
    options.py        the options of the studies beyond the paper (moat, wall capacity, site
                      and scaling rule, default pairs) and the bare wall's text.
    peaks_vs_gap.py   the gap grid, figure and check helpers of Figs. 16-21.
    collapse_ida.py   the collapse study's grid and its IDA to collapse, which the loss study
                      runs on too (collapse and loss).
Recipes compute no physics: they choose grids, call the pipeline (pipeline.sweep,
pipeline.histories, pipeline.motions.scaling, pipeline.motions.intensity) or the engine, label and
draw.
"""
