"""The slip element, written once for both time loops: an elastic spring in parallel with an
elastic-perfectly-plastic spring whose limit force may depend on the sliding speed. The
bilinear and friction pendulum isolators are made of it (engine/isolators/laws/), as the
bilinear story is; a law with physics of its own writes it in its own module.

Scalars or arrays alike: the NumPy loops call these functions on arrays, the compiled loops
compile the very same functions for scalars.
"""
import numpy as np


def isolator_force(u0, f_slip, k_elastic):
    """Total isolator force (N) at displacement u0 (m): the elastic spring's plus the slip
    element's force f_slip (N)."""
    return k_elastic * u0 + f_slip


def isolator_force_xy(ux, uy, fx_slip, fy_slip, k_elastic):
    """In plan: isolator_force along x and along y (N), at displacement (ux, uy) (m)."""
    return k_elastic * ux + fx_slip, k_elastic * uy + fy_slip


def slip_limit(f_limit, slow_drop, rate, speed):
    """The slip element's limit force (N) at sliding speed `speed` (m/s, either sign):
    f_limit (1 - slow_drop exp(-rate |speed|)). With slow_drop 0 it is f_limit exactly (the
    bilinear law); the friction pendulum's mu(v) W otherwise (Constantinou et al. 1990)."""
    return f_limit * (1.0 - slow_drop * np.exp(-rate * np.abs(speed)))


def plastic_spring_force(f_prev, du, k_slip, f_yield):
    """Return-mapped force (N) of the elastic-perfectly-plastic element after an increment du
    (m): the elastic trial force clipped to +-f_yield, the exact return mapping for a perfectly
    plastic spring (and, with f_yield the limit at the step's speed, for friction)."""
    return np.minimum(np.maximum(f_prev + k_slip * du, -f_yield), f_yield)


def radial_return(fx, fy, dux, duy, k_slip, f_yield):
    """Return-mapped force (N, x and y) of the elastic-perfectly-plastic element in plan after
    the increment (dux, duy) (m): the elastic trial force scaled back onto the circle of radius
    f_yield when outside it, the exact return mapping of a perfectly plastic spring with a
    circular yield surface (isotropic coupling of the two directions: an element that slips in
    one direction is softer in the other). A motion along x only gives plastic_spring_force's
    force to rounding (f_yield * trial / |trial|)."""
    tx = fx + k_slip * dux
    ty = fy + k_slip * duy
    size = np.sqrt(tx * tx + ty * ty)
    factor = np.minimum(1.0, f_yield / np.maximum(size, 1e-300))
    return tx * factor, ty * factor
