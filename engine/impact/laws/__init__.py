"""The moat-wall impact laws, one module each: every module in this folder is a law, found by
engine.impact.registry, so a new law is a new module here and nothing else.

A law module holds, besides its own helpers:
    NAME: str                      its name in Contact.of, sweeps and archives
    ORDER: int                     its place in listings (the paper's section 2 order)
    PARAMETERS: Declaration        its parameters, once (engine.impact.parameters)
    contact_fields(**checked)      -> the Contact fields of its members
    force_terms(delta, delta_dot, v_imp, *LAW_ARGUMENTS) -> (elastic N, dashpot N*s/m)
    max_tangent_stiffness(contact, indentation_bound) -> (B,) N/m, for the stability limit
`force_terms` is the law's physics, written once: plain arithmetic and NumPy ufuncs on scalars
or (B,) arrays alike, so the NumPy time loop calls it on arrays and the compiled loop compiles
the very same function for scalars (engine.impact.contact.LAW_ARGUMENTS lists the arguments,
the same for every law; a law ignores those it does not use).
"""
