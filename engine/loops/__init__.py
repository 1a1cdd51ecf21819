"""The time loops of the scheme (engine/scheme.py), planar and in plan, each with one interface:

    ground_motion(accel, accel_dt, dt, n_steps) -> (n_steps,) m/s^2 on the step grid
    run_simulation(ag, dt, arrays, contact, history, progress, scale) -> (peaks, history)
    run_two_body(contact, v, dt, m_eff, max_steps) -> (steps or None, out (B, 4), delta, force)
    run_plan(ag, dt, arrays, contacts, moat, progress, scale, angle, history) -> (peaks, history)

numpy_loop.py and numpy_plan.py are the readable references (vectorised over the batch, no
compiler); numba_loop.py and numba_plan.py the compiled defaults (members outer, steps inner;
compiled once per number of levels), with compiled.py, the physics both compile for scalars
(the slip elements, the contact solve, the impact laws' dispatch), and numba_support.py, what
they need of numba beyond @njit (a cache keyed on the physics, arrays on the stack). The loops
import only the scheme, the laws, the isolator's hysteresis and the result schema, and call the
same physics functions; engine.simulate picks one (engine/backends.py).
"""
