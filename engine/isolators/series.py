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
            "bearing_force_y")
"""In plan: the same, x and y each."""

EVENTS = 8
"""Sub-steps of a step along one axis: one per event, at most two per element in a step
(starting to slide, meeting or leaving the stop), and the last; a step that would need more
(none does) takes its rest on the elements as they are after the last event."""
NEWTON = 12
"""Evaluations of a step in plan (Newton's method on the force)."""
STOP_NEWTON = 24
"""Newton steps of an element sliding past its stop, at a force."""
TOLERANCE = 1e-14
"""m: a step in plan ends where the elements' deformations add up to the bearing's to this
(their round-off is about 1e-16 m), an element past its stop where its Newton step is."""
ARMIJO = 1e-4
"""The share of the decrease its slope promises that a backtracked Newton step must give
(where it does not at least halve the mismatch)."""
STUCK = 1e-9
"""A step in plan starts on the committed tangent, an element whose slip force is within this
share of its limit (squared) taken as sliding on."""
_FAR = 1e100
"""The distance (m) to an event that does not come; the first mismatch of a step in plan (a
large finite number: blended by 0 and 1, it must not be inf)."""


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


def _moved(x, y, push, tangent, to_slide, to_stop, element):
    """(x, y) of the element after a force increment push (N) at its tangent: an event
    reached lands exactly (the slip force at its limit, the deformation at the stop)."""
    _, slip, limit, gap, _ = element
    slid = push >= tangent * to_slide
    stopped = push >= tangent * to_stop
    y = np.minimum(y + slip * (push / tangent) + 2.0 * limit * slid, limit)
    mark = gap * (1.0 - 2.0 * (x < -gap))
    x = np.maximum(x + push / tangent, mark * stopped - _FAR * (1.0 - stopped))
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
        k1, slide1, stop1 = _stiffness(x1, y1, e1)
        k2, slide2, stop2 = _stiffness(x2, y2, e2)
        k3, slide3, stop3 = _stiffness(x3, y3, e3)
        needed = rest / (1.0 / k1 + 1.0 / k2 + 1.0 / k3)  # the force that takes up the rest
        event = np.minimum(np.minimum(k1 * np.minimum(slide1, stop1),
                                      k2 * np.minimum(slide2, stop2)),
                           k3 * np.minimum(slide3, stop3)) + _FAR * (sub == EVENTS - 1)
        push = np.minimum(needed, event)
        moved = push / k1 + push / k2 + push / k3
        rest = np.maximum(rest - moved, 0.0) * (needed > event)
        x1, y1 = _moved(x1, y1, push, k1, slide1, stop1, e1)
        x2, y2 = _moved(x2, y2, push, k2, slide2, stop2, e2)
        x3, y3 = _moved(x3, y3, push, k3, slide3, stop3, e3)
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
    free = 1.0 / np.maximum(apart, 1e-300)
    nx, ny = ex * free, ey * free
    grip = slip * sticking + limit * free * (1.0 - sticking)  # the slip force per (d - p)
    sliding = limit * free * (1.0 - sticking)  # dropped from the tangent along d - p
    reach = np.sqrt(dx * dx + dy * dy)
    outward = 1.0 / np.maximum(reach, 1e-300)
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
    its energy (J), whose gradient is d). Sticking (the slip element elastic, its force
    slip (d - p) within its limit), d lies
    along F + slip p with (pendulum + slip) |d| + stop max(|d| - gap, 0) = |F + slip p|.
    Sliding, the slip force is limit n: without the stop n lies along m = F - pendulum p and
    d = (F - limit n) / pendulum, which holds where it lies inside the stop's circle and
    slides (|m| (pendulum + slip) >= limit slip); else `_past_stop` (from there, or from the
    sticking deformation where it would not slide). element: (pendulum, slip, limit, gap,
    stop) and 1 / pendulum, 1 / (pendulum + slip), 1 / (pendulum + slip + stop)."""
    px, py = plastic
    pendulum, slip, limit, gap, stop = element[:5]
    easy, stiff, stopped = element[5:]  # 1 / pendulum, 1 / (pendulum + slip), 1 / (... + stop)
    qx, qy = fx + slip * px, fy + slip * py
    size = np.sqrt(qx * qx + qy * qy)
    scale = np.minimum(stiff, (1.0 + stop * gap / np.maximum(size, 1e-300)) * stopped)
    ex, ey = qx * scale, qy * scale
    sticking = (slip * (ex - px)) ** 2 + (slip * (ey - py)) ** 2 <= limit * limit
    mx, my = fx - pendulum * px, fy - pendulum * py
    pull = np.sqrt(mx * mx + my * my)
    across = limit / np.maximum(pull, 1e-300)
    sx, sy = (fx - mx * across) * easy, (fy - my * across) * easy
    # past the stop where it lies outside the circle, or would not slide without the stop
    # (from the sticking deformation then: it was sliding by little)
    unslid = pull < limit * slip * stiff
    sx, sy = ex * unslid + sx * (1.0 - unslid), ey * unslid + sy * (1.0 - unslid)
    dx, dy = _past_stop(sx, sy, (fx, fy), plastic, element[:5],
                        ((sx * sx + sy * sy > gap * gap) | unslid) * (1.0 - sticking))
    dx, dy = ex * sticking + dx * (1.0 - sticking), ey * sticking + dy * (1.0 - sticking)
    kxx, kxy, kyy, _, _, sx, sy, held = _tangent(dx, dy, plastic, element[:5], sticking)
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


def _committed(state, plastic, elements):
    """(xx, xy, yy of the series' tangent stiffness (N/m), the elements' energy (J)) at the
    committed state, an element whose slip force is within STUCK of its limit (squared) taken
    as sliding on: its tangent is the one it keeps when the bearing moves on as it moved (a
    sticking one would overshoot the force)."""
    axx, axy, ayy, held = 0.0, 0.0, 0.0, 0.0
    for k in range(3):
        _, _, limit, _, _ = elements[k]
        sx, sy = state[6 + 2 * k], state[7 + 2 * k]
        sticking = sx * sx + sy * sy < limit * limit * (1.0 - STUCK)
        kxx, kxy, kyy, _, _, _, _, energy = _tangent(state[2 * k], state[2 * k + 1], plastic[k],
                                                     elements[k], sticking)
        cxx, cxy, cyy = _inverse(kxx, kxy, kyy)
        axx, axy, ayy, held = axx + cxx, axy + cxy, ayy + cyy, held + energy
    kxx, kxy, kyy = _inverse(axx, axy, ayy)
    return kxx, kxy, kyy, held


def _derived(element):
    """An element's constants with 1 / pendulum, 1 / (pendulum + slip) and 1 / (pendulum +
    slip + stop) (`_carrying`'s)."""
    pendulum, slip, limit, gap, stop = element
    return (pendulum, slip, limit, gap, stop, 1.0 / pendulum, 1.0 / (pendulum + slip),
            1.0 / (pendulum + slip + stop))


def step_in_plan(state, dux, duy, elements):
    """In plan: the elements after the bearing moves by (dux, duy) (m), state (STATE_XY's
    columns) updated in place: the force F they all carry, by Newton's method from the
    committed one (its first step on the committed tangent, `_committed`), until their
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
    kxx, kxy, kyy, held = _committed(state, plastic, elements)
    rx, ry = -dux, -duy  # the mismatch at the committed force
    size, energy = rx * rx + ry * ry, -held - (fx * dux + fy * duy)
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
        gx = -(out[12] * qx + out[13] * qy) * taken + gx * kept
        gy = -(out[13] * qx + out[14] * qy) * taken + gy * kept
        step = taken + 0.5 * step * kept
    state[12], state[13] = fx, fy
