"""The moat-wall impact laws, one module each: every module in this folder is a law, found by
engine.impact.registry, so a new law is a new module here and nothing else.

A law module holds, besides its own helpers:
    NAME: str                      its name in Contact.of, sweeps and archives
    ORDER: int                     its place in listings (the paper's section 2 order)
    PARAMETERS: Declaration        its parameters, once (engine.impact.parameters)
    contact_fields(**checked)      -> the Contact fields of its members
    ROW: columns                   the Contact fields force_terms reads, in its packed row
    force_terms(delta, delta_dot, v_imp, row) -> (elastic N, dashpot N*s/m)
    max_tangent_stiffness(contact, indentation_bound) -> (B,) N/m, for the stability limit
`force_terms` is the law's physics, written once: plain arithmetic and NumPy ufuncs on scalars
or (B,) arrays alike, so the NumPy time loop calls it on arrays and the compiled loop compiles
the very same function for scalars. `row` is the law's own constants packed in ROW's order (a
tuple of (B,) arrays in the NumPy loops, a row of floats in the compiled ones:
engine.impact.contact.law_arguments and law_rows), read by name (row[ROW.k]): a law needing a
new constant names it in ROW (a constant no law had before is also a new field of
Contact), and no loop changes.
"""
