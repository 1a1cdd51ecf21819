"""Three friction elements in series, a step at a time: the triple friction pendulum's physics
(engine/isolators/laws/triple_friction_pendulum.py declares the law), written once for both
time loops (scalars and arrays alike, as isolators/hysteresis.py: compiled with the law).

An element (Fenz & Constantinou 2008's series model; OpenSees' TripleFrictionPendulum) is a
pendulum spring in parallel with an elastic-perfectly-plastic slip element (circular in plan)
and a stop, a spring on |d| - gap past its gap. Its constants (`elements`): (pendulum stiffness
N/m, slip stiffness N/m, slip limit N, gap m, stop stiffness N/m). A bearing's state: each
element's deformation d (m) and slip force s (N), and the force the three carry (N), in the
order of STATE (one axis) and STATE_XY (in plan); its constants in the order of ROW.

A step is given the bearing's displacement increment and finds the elements' with one force:
    along one axis, event to event (`step_along`): the elements are piecewise linear, so each
        sub-step to the next event (an element starting to slide, meeting or leaving its stop)
        is exact, and so is the step;
    in plan, by Newton's method on the force (`step_in_plan`): an element's deformation at a
        given force is exact (`_carrying`: explicit but for an element sliding past its stop,
        there Newton's method on its own potential), and the deformations' mismatch with the
        bearing's is the gradient of a convex function of the force (the elements'
        complementary energies less F.u), which steers the backtracking of a Newton step.
"""
import numpy as np

ELEMENTS = ("inner", "lower", "upper")
"""The three elements: the two inner surfaces, the lower outer one, the upper outer one."""
ROW = (*(f"{name}_{element}" for element in ELEMENTS
         for name in ("pendulum", "slip", "limit", "gap")), "stop")
"""A bearing's constants: per element its pendulum and slip stiffness (N/m), slip limit (N)
and gap (m), then the stops' stiffness (N/m)."""
STATE = (*(f"deformation_{e}" for e in ELEMENTS), *(f"slip_{e}" for e in ELEMENTS),
         "bearing_force")
"""A bearing's state along one axis: the elements' deformations (m) and slip forces (N), the
force they carry (N)."""
STATE_XY = (*(f"deformation_{e}_{a}" for e in ELEMENTS for a in "xy"),
            *(f"slip_{e}_{a}" for e in ELEMENTS for a in "xy"), "bearing_force_x",
            "bearing_force_y", "stiffness_xx", "stiffness_xy", "stiffness_yy")
"""In plan: the same, x and y each; then the series' tangent stiffness (N/m, xx, xy, yy)
where the last step ended, the next step's first Newton step (zero at rest: the first step
starts with an evaluation)."""

EVENTS = 8
"""Sub-steps of a step along one axis: one per event, at most two per element in a step
(starting to slide, meeting or leaving the stop), and the last; a step that would need more
(none does) takes its rest on the elements as they are after the last event."""
NEWTON = 12
"""Evaluations of a step in plan (Newton's method on the force)."""
STOP_NEWTON = 24
"""Newton steps of an element sliding past its stop, at a force."""
TOLERANCE = 1e-11
"""m: a step in plan ends where the elements' deformations add up to the bearing's to this, an
element past its stop where its Newton step is. The force is then within the stiffest
element's E times it of the exact one (7e-10 of the weight at the default yield_disp), and the
elements' sum follows the bearing to a few 1e-10 m over a record (measured: 6e-10 m after 4000
steps of 0.5 ms). At 1e-14 m, the round-off's order, a step took 2.6 evaluations on a record,
at 1e-11 m 1.9: the law 22% faster in plan, the same peaks as OpenSees' element to its own
tolerance (engine/isolators/laws/triple_friction_pendulum.py's tests)."""
ARMIJO = 1e-4
"""The share of the decrease its slope promises that a backtracked Newton step must give
(where it does not at least halve the mismatch)."""
_TINY = 1e-30
"""The least length (m) or force (N) a direction is taken from, and divided by (a zero one
stays zero, and its reciprocal finite)."""
_FAR = 1e100
"""The distance (m) to an event that does not come, and the energy a Newton step in plan must
first beat (large finite numbers: blended by 0 and 1, they must not be inf)."""


def elements(row):
    """The three elements' constants ((pendulum, slip, limit, gap, stop) each) of a ROW."""
    return ((row[0], row[1], row[2], row[3], row[12]), (row[4], row[5], row[6], row[7], row[12]),
            (row[8], row[9], row[10], row[11], row[12]))


def settled(rest):
    """Whether nothing is left to do (every member, on a batch)."""
    return np.all(rest == 0.0)


# ------------------------------------------------------------------------------ one axis

def _stiffness(x, y, element):
    """One element moving along the loading direction from deformation x (m) and slip force y
    (N), both taken positive along it: (its tangent stiffness N/m, the deformation to its
    slip element's limit m, the deformation to its stop's next change m; _FAR when none)."""
    pendulum, slip, limit, gap, stop = element
    sliding = y >= limit
    beyond = x >= gap  # the stop engaged ahead
    behind = x < -gap  # the stop engaged behind, released at -gap
    tangent = pendulum + slip * (1.0 - sliding) + stop * (beyond + behind)
    to_slide = (limit - y) / slip + _FAR * sliding
    to_stop = (gap - x) - 2.0 * gap * behind + _FAR * beyond
    return tangent, to_slide, to_stop


def _moved(x, y, push, move, events, element):
    """(x, y) of the element after a force increment push (N) that moves it by `move` (m),
    events = (its tangent, deformation to sliding, to its stop): an event reached lands
    exactly (the slip force at its limit, the deformation at the stop)."""
    tangent, to_slide, to_stop = events
    _, slip, limit, gap, _ = element
    slid = push >= tangent * to_slide
    stopped = push >= tangent * to_stop
    y = np.minimum(y + slip * move + 2.0 * limit * slid, limit)
    mark = gap * (1.0 - 2.0 * (x < -gap))
    x = np.maximum(x + move, mark * stopped - _FAR * (1.0 - stopped))
    return x, y


def step_along(state, du, elements):
    """Along one axis: the elements after the bearing moves by du (m), state (STATE's
    columns) updated in place. The increment is taken up event to event, each sub-step the
    force increment that moves the series to its next event or takes up the rest."""
    sign = 1.0 - 2.0 * (du < 0.0)
    rest = sign * du
    e1, e2, e3 = elements
    x1, x2, x3 = sign * state[0], sign * state[1], sign * state[2]
    y1, y2, y3 = sign * state[3], sign * state[4], sign * state[5]
    carried = sign * state[6]
    for sub in range(EVENTS):
        if settled(rest):
            break
        a1, a2, a3 = _stiffness(x1, y1, e1), _stiffness(x2, y2, e2), _stiffness(x3, y3, e3)
        c1, c2, c3 = 1.0 / a1[0], 1.0 / a2[0], 1.0 / a3[0]  # compliances
        needed = rest / (c1 + c2 + c3)  # the force that takes up the rest
        event = np.minimum(np.minimum(a1[0] * np.minimum(a1[1], a1[2]),
                                      a2[0] * np.minimum(a2[1], a2[2])),
                           a3[0] * np.minimum(a3[1], a3[2])) + _FAR * (sub == EVENTS - 1)
        push = np.minimum(needed, event)
        m1, m2, m3 = push * c1, push * c2, push * c3
        rest = np.maximum(rest - (m1 + m2 + m3), 0.0) * (needed > event)
        x1, y1 = _moved(x1, y1, push, m1, a1, e1)
        x2, y2 = _moved(x2, y2, push, m2, a2, e2)
        x3, y3 = _moved(x3, y3, push, m3, a3, e3)
        carried = carried + push
    state[0], state[1], state[2] = sign * x1, sign * x2, sign * x3
    state[3], state[4], state[5] = sign * y1, sign * y2, sign * y3
    state[6] = sign * carried


# ------------------------------------------------------------------------------ in plan

def _tangent(dx, dy, plastic, element, sticking):
    """One element at deformation (dx, dy) (m) on its sticking (sticking 1: the slip element
    elastic, s = slip (d - p)) or sliding branch (0: s = limit (d - p) / |d - p|), p =
    `plastic` its committed plastic slip: (the xx, xy, yy of its consistent tangent (N/m), its
    force x, y (N), its slip force x, y (N), its energy (J): the step's potential whose
    gradient is its force, pendulum |d|^2 / 2 + stop max(|d| - gap, 0)^2 / 2 + the slip
    element's slip |d - p|^2 / 2 sticking, limit |d - p| - limit^2 / (2 slip) sliding)."""
    px, py = plastic
    pendulum, slip, limit, gap, stop = element
    ex, ey = dx - px, dy - py
    apart = np.sqrt(ex * ex + ey * ey)
    free = 1.0 / np.maximum(apart, _TINY)
    nx, ny = ex * free, ey * free
    grip = slip * sticking + limit * free * (1.0 - sticking)  # the slip force per (d - p)
    sliding = limit * free * (1.0 - sticking)  # dropped from the tangent along d - p
    reach = np.sqrt(dx * dx + dy * dy)
    outward = 1.0 / np.maximum(reach, _TINY)
    excess = np.maximum(1.0 - gap * outward, 0.0)  # the stop's force is stop excess d
    radial = stop * (1.0 - excess) * (reach > gap)  # its tangent's extra along d
    mx, my = dx * outward, dy * outward
    even = pendulum + grip + stop * excess
    sx, sy = grip * ex, grip * ey
    beyond = np.maximum(reach - gap, 0.0)
    held = 0.5 * slip * apart * apart * sticking \
        + (limit * apart - 0.5 * limit * limit / slip) * (1.0 - sticking)
    return (even - sliding * nx * nx + radial * mx * mx,
            radial * mx * my - sliding * nx * ny,
            even - sliding * ny * ny + radial * my * my,
            (pendulum + stop * excess) * dx + sx, (pendulum + stop * excess) * dy + sy, sx, sy,
            0.5 * (pendulum * reach * reach + stop * beyond * beyond) + held)


def _inverse(xx, xy, yy):
    """The inverse of the symmetric 2 x 2 matrix (xx, xy, yy)."""
    scale = 1.0 / (xx * yy - xy * xy)
    return yy * scale, -xy * scale, xx * scale


def _at(dx, dy, plastic, element):
    """_tangent at (dx, dy) on the branch that deformation takes (sticking where slip |d - p|
    is within the limit)."""
    px, py = plastic
    _, slip, limit, _, _ = element
    sticking = slip * slip * ((dx - px) ** 2 + (dy - py) ** 2) <= limit * limit
    return _tangent(dx, dy, plastic, element, sticking)


def _past_stop(dx, dy, force, plastic, element, active):
    """The deformation (m) of a sliding element past its stop carrying `force` (fx, fy) (N),
    where `active` (else (dx, dy) as it is): Newton's method on its energy less F.d (convex)
    from (dx, dy), a step halved until it lowers it enough (ARMIJO) or halves the force's
    mismatch, until the step is at most TOLERANCE (at most STOP_NEWTON evaluations)."""
    fx, fy = force
    value, gx, gy = _FAR, 0.0, 0.0
    wx, wy, step = 0.0, 0.0, 1.0
    for first in range(STOP_NEWTON):
        if settled(active):
            break
        tx, ty = dx + step * wx * active, dy + step * wy * active
        kxx, kxy, kyy, ex, ey, _, _, held = _at(tx, ty, plastic, element)
        trial, hx, hy = held - fx * tx - fy * ty, ex - fx, ey - fy
        taken = ((first == 0) | (trial <= value + ARMIJO * step * (gx * wx + gy * wy))
                 | (hx * hx + hy * hy <= 0.25 * (gx * gx + gy * gy))) * active
        kept = 1.0 - taken
        cxx, cxy, cyy = _inverse(kxx, kxy, kyy)
        dx, dy = tx * taken + dx * kept, ty * taken + dy * kept
        value, gx, gy = trial * taken + value * kept, hx * taken + gx * kept, \
            hy * taken + gy * kept
        wx = -(cxx * hx + cxy * hy) * taken + wx * kept
        wy = -(cxy * hx + cyy * hy) * taken + wy * kept
        step = taken + 0.5 * step * kept
        active = active * (np.maximum(np.abs(wx), np.abs(wy)) * step > TOLERANCE)
    return dx, dy


def _carrying(fx, fy, plastic, element):
    """One element carrying the force F = (fx, fy) (N), p = `plastic` (p_x, p_y) its committed
    plastic slip (m): (its deformation x, y (m), its slip force x, y (N), the xx, xy, yy of its
    compliance, the inverse of its consistent tangent (m/N), its complementary energy F.d -
    its energy (J), whose gradient is d). Force driven and exact. Sticking (the slip element
    elastic, its force slip (d - p) within its limit), d lies along q = F + slip p with
    (pendulum + slip) |d| + stop max(|d| - gap, 0) = |q|. Sliding, the slip force is limit n:
    without the stop n lies along m = F - pendulum p and d = (F - limit n) / pendulum, which
    holds where d lies inside the stop's circle and slides (|m| - limit >= limit pendulum /
    slip); else `_past_stop`, from there or, where it would not slide, from the sticking
    deformation (it slides by little then). element: (pendulum, slip, limit, gap, stop) and
    1 / pendulum, 1 / (pendulum + slip), 1 / (pendulum + slip + stop), limit^2 / slip."""
    px, py = plastic
    pendulum, slip, limit, gap, stop, easy, stiff, stopped, spent = element
    # sticking: radial along q, the stop's tangent along it too
    qx, qy = fx + slip * px, fy + slip * py
    size = np.sqrt(qx * qx + qy * qy)
    inward = 1.0 / np.maximum(size, _TINY)
    scale = np.minimum(stiff, (1.0 + stop * gap * inward) * stopped)
    ex, ey = qx * scale, qy * scale
    wide = (ex - px) ** 2 + (ey - py) ** 2
    sticking = slip * slip * wide <= limit * limit
    reach = size * scale
    excess = np.maximum(1.0 - gap / np.maximum(reach, _TINY), 0.0)
    radial = stop * (1.0 - excess) * (reach > gap)
    ux, uy = qx * inward, qy * inward
    even = pendulum + slip + stop * excess
    beyond = np.maximum(reach - gap, 0.0)
    kept = 0.5 * (pendulum * reach * reach + stop * beyond * beyond + slip * wide)
    # sliding inside the circle: n along m, |d - p| = (|m| - limit) / pendulum
    mx, my = fx - pendulum * px, fy - pendulum * py
    pull = np.sqrt(mx * mx + my * my)
    toward = 1.0 / np.maximum(pull, _TINY)
    nx, ny = mx * toward, my * toward
    lx, ly = (fx - limit * nx) * easy, (fy - limit * ny) * easy
    apart = (pull - limit) * easy
    across = limit / np.maximum(apart, _TINY)  # the slip force's stiffness across n
    moved = 0.5 * pendulum * (lx * lx + ly * ly) + limit * apart - 0.5 * spent
    sliding = 1.0 - sticking
    dx, dy = ex * sticking + lx * sliding, ey * sticking + ly * sliding
    sx, sy = slip * (ex - px) * sticking + limit * nx * sliding, \
        slip * (ey - py) * sticking + limit * ny * sliding
    kxx = (even + radial * ux * ux) * sticking + (pendulum + across * ny * ny) * sliding
    kxy = radial * ux * uy * sticking - across * nx * ny * sliding
    kyy = (even + radial * uy * uy) * sticking + (pendulum + across * nx * nx) * sliding
    held = kept * sticking + moved * sliding
    # past the stop, or sliding by so little that without the stop it would not slide
    unslid = apart * slip < limit
    past = ((lx * lx + ly * ly > gap * gap) | unslid) * sliding
    if not settled(past):
        bx, by = _past_stop(ex * unslid + lx * (1.0 - unslid), ey * unslid + ly * (1.0 - unslid),
                            (fx, fy), plastic, element[:5], past)
        k = _tangent(bx, by, plastic, element[:5], 0.0)
        other = 1.0 - past
        dx, dy = bx * past + dx * other, by * past + dy * other
        kxx, kxy, kyy = k[0] * past + kxx * other, k[1] * past + kxy * other, \
            k[2] * past + kyy * other
        sx, sy = k[5] * past + sx * other, k[6] * past + sy * other
        held = k[7] * past + held * other
    cxx, cxy, cyy = _inverse(kxx, kxy, kyy)
    return dx, dy, sx, sy, cxx, cxy, cyy, fx * dx + fy * dy - held


def _series(fx, fy, plastic, elements):
    """The three elements carrying the force (fx, fy) (N), plastic = their committed plastic
    slips ((p_x, p_y) each): their deformations (m) and slip forces (N) in STATE_XY's order,
    then the xx, xy, yy of the series' tangent stiffness (N/m) and its complementary energy
    (J, whose gradient is the deformations' sum)."""
    p1, p2, p3 = plastic
    e1, e2, e3 = elements
    d1x, d1y, s1x, s1y, c1xx, c1xy, c1yy, w1 = _carrying(fx, fy, p1, e1)
    d2x, d2y, s2x, s2y, c2xx, c2xy, c2yy, w2 = _carrying(fx, fy, p2, e2)
    d3x, d3y, s3x, s3y, c3xx, c3xy, c3yy, w3 = _carrying(fx, fy, p3, e3)
    kxx, kxy, kyy = _inverse(c1xx + c2xx + c3xx, c1xy + c2xy + c3xy, c1yy + c2yy + c3yy)
    return (d1x, d1y, d2x, d2y, d3x, d3y, s1x, s1y, s2x, s2y, s3x, s3y, kxx, kxy, kyy,
            w1 + w2 + w3)


def _stored(state, elements):
    """J: the energy the three elements hold in the committed state (STATE_XY's columns),
    their pendulums', stops' and slip elements' (|s|^2 / (2 slip)): the potential of a step's
    solve at its start."""
    held = 0.0
    for k in range(3):
        pendulum, slip, _, gap, stop = elements[k]
        dx, dy, sx, sy = state[2 * k], state[2 * k + 1], state[6 + 2 * k], state[7 + 2 * k]
        reach = np.sqrt(dx * dx + dy * dy)
        beyond = np.maximum(reach - gap, 0.0)
        held = held + 0.5 * (pendulum * reach * reach + stop * beyond * beyond
                             + (sx * sx + sy * sy) / slip)
    return held


def _derived(element):
    """An element's constants with those `_carrying` reads: 1 / pendulum, 1 / (pendulum +
    slip), 1 / (pendulum + slip + stop), limit^2 / slip."""
    pendulum, slip, limit, gap, stop = element
    return (pendulum, slip, limit, gap, stop, 1.0 / pendulum, 1.0 / (pendulum + slip),
            1.0 / (pendulum + slip + stop), limit * limit / slip)


def step_in_plan(state, dux, duy, elements):
    """In plan: the elements after the bearing moves by (dux, duy) (m), state (STATE_XY's
    columns) updated in place: the force F they all carry, by Newton's method from the
    committed one (its first step on the tangent where the last step ended), until their
    deformations add up to the bearing's to TOLERANCE (at most NEWTON evaluations); a Newton
    step that neither lowers the convex function whose gradient is the mismatch enough
    (ARMIJO) nor halves the mismatch is halved (a step from sticking to sliding, or onto a
    stop, may need it)."""
    e1, e2, e3 = elements
    ax, ay = state[0] + state[2] + state[4] + dux, state[1] + state[3] + state[5] + duy
    plastic = ((state[0] - state[6] / e1[1], state[1] - state[7] / e1[1]),
               (state[2] - state[8] / e2[1], state[3] - state[9] / e2[1]),
               (state[4] - state[10] / e3[1], state[5] - state[11] / e3[1]))
    fx, fy = state[12], state[13]
    kxx, kxy, kyy = state[14], state[15], state[16]
    rx, ry = -dux, -duy  # the mismatch at the committed force
    size, energy = rx * rx + ry * ry, -_stored(state, elements) - (fx * dux + fy * duy)
    gx, gy = -(kxx * rx + kxy * ry), -(kxy * rx + kyy * ry)
    step = 1.0
    derived = (_derived(e1), _derived(e2), _derived(e3))
    for _ in range(NEWTON):
        going = np.maximum(np.abs(rx), np.abs(ry)) > TOLERANCE
        if settled(going):
            break
        tx, ty = fx + step * gx * going, fy + step * gy * going
        out = _series(tx, ty, plastic, derived)
        qx, qy = out[0] + out[2] + out[4] - ax, out[1] + out[3] + out[5] - ay
        trial, lower = qx * qx + qy * qy, out[15] - (tx * ax + ty * ay)
        taken = ((lower <= energy + ARMIJO * step * (rx * gx + ry * gy))
                 | (trial <= 0.25 * size)) * going
        kept = 1.0 - taken
        for j in range(12):
            state[j] = out[j] * taken + state[j] * kept
        fx, fy = tx * taken + fx * kept, ty * taken + fy * kept
        rx, ry = qx * taken + rx * kept, qy * taken + ry * kept
        size, energy = trial * taken + size * kept, lower * taken + energy * kept
        kxx, kxy = out[12] * taken + kxx * kept, out[13] * taken + kxy * kept
        kyy = out[14] * taken + kyy * kept
        gx, gy = -(kxx * rx + kxy * ry), -(kxy * rx + kyy * ry)
        step = taken + 0.5 * step * kept
    state[12], state[13] = fx, fy
    state[14], state[15], state[16] = kxx, kxy, kyy
