"""The isolator laws, one module each: every module in this folder is a law, found by
engine.isolators.registry, so a new law is a new module here and nothing else.

Every law is an elastic spring in parallel with a slip element (an elastic-perfectly-plastic
spring whose limit force may depend on the sliding speed); engine/isolators/hysteresis.py holds
that physics, once, for both time loops. A law module holds:
    NAME: str, ORDER: int          its name and place in listings
    PARAMETERS: Declaration        its parameters, once (engine.parameters)
    DEFAULT_ZETA: float            the isolation damping ratio it implies unless one is given
    DASHPOT_TEXT: str              the isolation dashpot of damping="paper" in the law's
                                   symbols, for the archives' provenance
    check(**checked)               ValueError when the parameters contradict each other
    fields(mass, g, **checked)     -> the hysteresis fields: k_elastic N/m, k_slip N/m,
                                      f_limit N, slow_drop 1, rate s/m (mass: the building's
                                      total mass M in kg, g in m/s^2: the weight is g M)
    initial_stiffness(mass, g, **checked) -> N/m, before any slip (stability limit, damping)
    yield_displacement(mass, g, **checked) -> m, where the slip element starts to slip
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
