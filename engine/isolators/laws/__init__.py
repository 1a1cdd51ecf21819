"""The isolator laws, one module each: every module in this folder is a law, found by
engine.isolators.registry, so a new law, its state and physics included, is a new module here
and nothing else.

A law's physics is its own, written once for both time loops (for scalars and for arrays
alike: the NumPy loops call it on batches, the compiled loops compile it); the bilinear and
friction pendulum laws are made of the slip element of engine/isolators/hysteresis.py, the
triple friction pendulum of the elements in series of engine/isolators/series.py. A law
module holds:
    NAME: str, ORDER: int          its name and place in listings
    PARAMETERS: Declaration        its parameters, once (engine.parameters)
    DEFAULT_ZETA: float            the isolation damping ratio it implies unless one is given
    DASHPOT_TEXT: str              the isolation dashpot of damping="paper" in the law's
                                   symbols, for the archives' provenance
    check(**checked)               ValueError when the parameters contradict each other
    ROW: columns(...)              the constants the time loops read (engine/layout.py)
    CARRIED: tuple[str, ...]       the names of ROW proportional to the weight carried (a
                                   building that twists gives each of its n bearings 1/n)
    STATE, STATE_XY: columns(...)  the law's state along one axis and in plan (zero at rest)
    fields(mass, g, **checked)     -> ROW by name (mass: the building's total mass M in kg,
                                      g in m/s^2: the weight is g M)
    force(u, state, row)           -> N at displacement u (m); reads the state
    advance(state, velocity, dt, row)   commits the state after a step of dt (s) at the
                                      step's velocity (m/s)
    force_xy(ux, uy, state, row)   -> (N, N) in plan; advance_xy(state, vx, vy, dt, row)
                                      (row: the ROW values, state: the STATE values, each
                                      indexed by column: one number each in a compiled loop,
                                      a batch's arrays in a NumPy loop)
    initial_stiffness(mass, g, **checked) -> N/m, before any slip (stability limit, damping)
    yield_displacement(mass, g, **checked) -> m, where the slip element starts to slip
    displacement_capacity(mass, g, **checked) -> m, where the bearing meets its restrainer or
                                      fails (inf: none): a run passing it is a collapse
    effective_stiffness(mass, g, displacement, **checked) -> N/m, the secant stiffness at a
                                      displacement (ASCE 7 chapter 17's k_eff)
and, for the code's equivalent-linear design (pipeline.motions.target.isolation_design; a law
without them cannot be designed so, and says so when asked,
engine.isolators.registry.CODE_INTERFACE):
    post_yield_stiffness(mass, g, **checked) -> N/m, the secant stiffness's limit at large
                                      displacements
    energy_per_cycle(mass, g, displacement, **checked) -> J, the energy dissipated per cycle
                                      at a displacement amplitude (ASCE 7 chapter 17's E_M)
"""
