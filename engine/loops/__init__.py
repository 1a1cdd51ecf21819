"""The two time loops of the scheme (engine/scheme.py), with one interface:

    ground_motion(accel, accel_dt, dt, n_steps) -> (n_steps,) m/s^2 on the step grid
    run_simulation(ag, dt, arrays, contact, history, progress, scale) -> (peaks, history)
    run_two_body(contact, v, dt, m_eff, max_steps) -> (steps or None, out (B, 4), delta, force)

numpy_loop.py is the readable reference (vectorised over the batch, no compiler);
numba_loop.py the compiled default (members outer, steps inner; compiled once per number of
levels), with numba_support.py, what it needs of numba beyond @njit (a cache keyed on the
physics, arrays on the stack). The two loops import only the scheme, the laws, the isolator's
hysteresis and the result schema, and call the same physics functions; engine.simulate picks
one (engine/backends.py).
"""
