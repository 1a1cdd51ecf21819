"""The time loops of the scheme (engine/scheme.py): planar, in plan, and of buildings that
twist, each with one interface:

    ground_motion(accel, accel_dt, dt, n_steps) -> (n_steps,) m/s^2 on the step grid
    run_simulation(ag, dt, arrays, contact, history, progress, scale) -> (peaks, history)
    run_two_body(contact, v, dt, m_eff, max_steps) -> (steps or None, out (B, 4), delta, force)
    run_plan(ag, dt, arrays, contacts, moat, progress, scale, angle, history, arrays_y,
             mu_wall) -> (peaks, history)
    run_torsion(ag, dt, arrays, torsion_arrays, contacts, points, progress, scale, angle,
                history, mu_wall) -> (peaks, history)

numpy_loop.py, numpy_plan.py and numpy_torsion.py are the readable references (vectorised over
the batch, no compiler); numba_loop.py, numba_plan.py and numba_torsion.py the compiled
defaults (members outer, steps inner; compiled once per number of levels), with compiled.py,
the physics they compile for scalars (the contact solve, the impact laws' dispatch, the story
and isolator laws resolved per kernel), layout.py, the columns of the arrays they pack
(declared once),
numba_contacts.py, the contact points of the twisting kernel and their solve,
numba_bearings.py, its bearings,
numpy_isolators.py, the isolator laws on a NumPy batch (the NumPy loops' twin of compiled.py's
isolator laws), and
numba_support.py, what they need of numba beyond @njit (a cache keyed on the physics, arrays
on the stack, pairs in one register, members on threads, a kernel per law). The loops import
only the scheme, the laws, the isolator's hysteresis, the torsion model and the result
schema, and call the same physics functions; engine.simulate picks one (engine/backends.py).
"""
