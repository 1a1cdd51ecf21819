"""The story laws, one module each: every module here is found by engine/stories/registry.py.

A law declares NAME, ORDER, PARAMETERS (each value one number or one per story), N_FIELDS,
N_STATE, `check`, `fields(stiffness, **values)` -> (N, N_FIELDS) constants per story,
`initial_state(row)` -> (N_STATE,) and `force(drift, state, row)`: the story's force (N) at its
drift (m), committing the state in place (one trial and commit per step, the scheme being
explicit). `force` is written once for scalars: the NumPy loop calls it as it is, the compiled
loops compile it.
"""
