"""Independent implementations the engine is checked against, sharing no code with it: an
OpenSeesPy model of the paper's building (opensees_reference.py) and a solve_ivp building with
its own impact laws (independent_building.py)."""
