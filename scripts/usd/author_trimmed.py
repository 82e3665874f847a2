"""Writes glint's trimmed NURBS models with the real USD library (the usd-core package): two
products whose openings are cut by trim curves, as pipelines write them.

    pip install usd-core
    python3 scripts/usd/author_trimmed.py

It writes two layers, z up, each with its default prim:

- patches/speaker.usda: a smart speaker facing -y (its left at +x), 1.98 tall and 0.85 in
  radius. /speaker/body holds the wall in four quarter patches (front, left, back, right:
  rational quadratic arcs around, a cubic barrel up) and a top and a bottom cap (full rational
  circles around, a rounded shoulder and a flat face along the profile); /speaker/driver holds
  a woofer cone and its dust cap, revolved about -y behind the front. The front is trimmed with
  a round port, through which the driver shows, and a grille of 20 small round holes in three
  staggered rows; the left and right quarters each have a rounded-rectangle handle slot, and
  the back a round cable port.
- patches/car_doors.usda: the side panels of a small car, x forward, y to its left (ISO 8855),
  4.3 long. /car/fender, /car/door_front, /car/door_rear and /car/quarter each hold a left and
  a right bicubic panel, gently curved (tumblehome above the belt line, tapered toward the
  ends), 0.9-1.3 long and 0.7-1 tall, with shut-line gaps of 0.01 between them. The doors'
  window openings and handle holes, the fender's side repeater and the quarter panel's fuel
  filler are holes; the wheel arches are cut into the outer loops (the rear arch runs across
  the rear door's lower rear corner and into the quarter panel), as are the doors' sloping
  pillars and the rounded corners.

Surfaces: `points[v * uVertexCount + u]`, Euclidean with `pointWeights` where rational, knots
`count + order` long, ranges the knots' domain, and N = dP/du x dP/dv pointing out of the body.

Trims: each curve's `trimCurve:points` are homogeneous (u w, v w, w); a loop's curves join head
to tail and close; the outer loop runs counter-clockwise in (u, v), holes clockwise. Shapes are
drawn in a metric plane (the panel's x and z, or arc length and height around a point of the
speaker) and mapped to (u, v) by an affine map, which keeps lines straight and rational arcs
exact, so holes are round on the surface (on the speaker's curved wall, to a few per cent).
Every loop's direction is then set from its signed area in (u, v).
"""

import math
import os

from pxr import Gf, UsdGeom, Vt

# A new z-up layer at a path, replacing what was there.
from author_models import layer as new_stage

W = math.sqrt(0.5)
CIRCLE_KNOTS = [0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1]


# --- B-splines ---------------------------------------------------------------------------

def clamped_knots(count, order):
    """Uniform knots on [0, 1], clamped at both ends: `count + order` of them."""
    spans = count - order + 1
    return [0.0] * order + [i / spans for i in range(1, spans)] + [1.0] * order


def greville(knots, order, count):
    """The Greville abscissae: control points placed there make a coordinate linear in t."""
    p = order - 1
    return [sum(knots[i + 1:i + p + 1]) / p for i in range(count)]


def de_boor(knots, order, ctrl, t):
    """The point at t of the B-spline with control points `ctrl` (tuples, any length)."""
    n, p = len(ctrl), order - 1
    k = p
    while k < n - 1 and knots[k + 1] <= t:
        k += 1
    d = [list(ctrl[j + k - p]) for j in range(p + 1)]
    for r in range(1, p + 1):
        for j in range(p, r - 1, -1):
            lo, hi = knots[j + k - p], knots[j + 1 + k - r]
            a = 0.0 if hi == lo else (t - lo) / (hi - lo)
            d[j] = [(1 - a) * x + a * y for x, y in zip(d[j - 1], d[j])]
    return d[p]


class Net:
    """A NURBS surface's data as USD writes it, with an evaluator to size trims on it."""

    def __init__(self, nu, nv, u_order, v_order, u_knots, v_knots, points, weights=None):
        self.nu, self.nv = nu, nv
        self.u_order, self.v_order = u_order, v_order
        self.u_knots, self.v_knots = u_knots, v_knots
        self.points = points
        self.weights = weights

    def at(self, u, v):
        w = self.weights or [1.0] * len(self.points)
        rows = []
        for j in range(self.nv):
            row = [(x * w[j * self.nu + i], y * w[j * self.nu + i], z * w[j * self.nu + i],
                    w[j * self.nu + i])
                   for i, (x, y, z) in enumerate(self.points[j * self.nu:(j + 1) * self.nu])]
            rows.append(de_boor(self.u_knots, self.u_order, row, u))
        x, y, z, h = de_boor(self.v_knots, self.v_order, rows, v)
        return (x / h, y / h, z / h)

    def speeds(self, u, v, e=1e-6):
        """|dP/du| and |dP/dv| at (u, v), by central differences."""
        def d(a, b):
            return math.dist(a, b) / (2 * e)
        return (d(self.at(u + e, v), self.at(u - e, v)), d(self.at(u, v + e), self.at(u, v - e)))


def define_patch(stage, path, net, u_form=UsdGeom.Tokens.open):
    patch = UsdGeom.NurbsPatch.Define(stage, path)
    patch.CreateUVertexCountAttr(net.nu)
    patch.CreateVVertexCountAttr(net.nv)
    patch.CreateUOrderAttr(net.u_order)
    patch.CreateVOrderAttr(net.v_order)
    patch.CreateUKnotsAttr(Vt.DoubleArray(net.u_knots))
    patch.CreateVKnotsAttr(Vt.DoubleArray(net.v_knots))
    patch.CreateURangeAttr(Gf.Vec2d(net.u_knots[net.u_order - 1], net.u_knots[net.nu]))
    patch.CreateVRangeAttr(Gf.Vec2d(net.v_knots[net.v_order - 1], net.v_knots[net.nv]))
    patch.CreateUFormAttr(u_form)
    patch.CreateVFormAttr(UsdGeom.Tokens.open)
    patch.CreatePointsAttr(Vt.Vec3fArray([Gf.Vec3f(*p) for p in net.points]))
    if net.weights is not None:
        patch.CreatePointWeightsAttr(Vt.DoubleArray(net.weights))
    return patch


# --- Trim curves -------------------------------------------------------------------------
# A curve is (order, knots, [(x, y, w)]): Euclidean control points with weights, in the plane
# a shape is drawn in until `mapped` takes it to (u, v).

def polyline(points):
    """An order-2 curve through `points`, one knot span per segment: knots 0, 0, 1, ..., n-1,
    n-1 for n points."""
    n = len(points)
    knots = [0.0] + [float(i) for i in range(n)] + [n - 1.0]
    return (2, knots, [(x, y, 1.0) for (x, y) in points])


def arc(center, radius, start, end, clockwise):
    """A circular arc about `center` from the point `start` to the point `end` (both on the
    circle; they are the curve's exact end points), as rational quadratic spans of at most 90
    degrees with double knots between them."""
    cx, cy = center
    a0 = math.atan2(start[1] - cy, start[0] - cx)
    a1 = math.atan2(end[1] - cy, end[0] - cx)
    sweep = a1 - a0
    if clockwise:
        while sweep >= 0:
            sweep -= 2 * math.pi
    else:
        while sweep <= 0:
            sweep += 2 * math.pi
    n = max(1, math.ceil(abs(sweep) / (math.pi / 2) - 1e-9))
    phi = sweep / n
    w = math.cos(phi / 2)
    ctrl = [(start[0], start[1], 1.0)]
    for k in range(n):
        mid = a0 + (k + 0.5) * phi
        ctrl.append((cx + radius / w * math.cos(mid), cy + radius / w * math.sin(mid), w))
        if k == n - 1:
            ctrl.append((end[0], end[1], 1.0))
        else:
            a = a0 + (k + 1) * phi
            ctrl.append((cx + radius * math.cos(a), cy + radius * math.sin(a), 1.0))
    knots = [0.0] * 3 + [i / n for i in range(1, n) for _ in range(2)] + [1.0] * 3
    return (3, knots, ctrl)


def circle(center, radius):
    """The full circle: nine points on the square around it, knots 0,0,0,1/4,1/4,...,1,1,1."""
    cx, cy = center
    square = [(1, 0, 1), (1, 1, W), (0, 1, 1), (-1, 1, W), (-1, 0, 1),
              (-1, -1, W), (0, -1, 1), (1, -1, W), (1, 0, 1)]
    return [(3, list(CIRCLE_KNOTS), [(cx + radius * x, cy + radius * y, w) for x, y, w in square])]


def rounded_path(points, radii):
    """Curves from points[0] to points[-1] through the points between, each corner rounded by a
    circular arc of radius radii[i] (0: a sharp corner). Straight runs are order-2 polylines;
    a rounded corner is one rational quadratic span, weight sin(alpha/2) for the corner's
    interior angle alpha."""
    curves, run, used = [], [points[0]], [0.0] * len(points)
    for i in range(1, len(points) - 1):
        r = radii[i]
        if r == 0:
            run.append(points[i])
            continue
        (px, py), (x, y), (nx, ny) = points[i - 1], points[i], points[i + 1]
        la, lb = math.hypot(px - x, py - y), math.hypot(nx - x, ny - y)
        a = ((px - x) / la, (py - y) / la)
        b = ((nx - x) / lb, (ny - y) / lb)
        alpha = math.acos(max(-1.0, min(1.0, a[0] * b[0] + a[1] * b[1])))
        t = r / math.tan(alpha / 2)
        assert t + used[i - 1] < la and t < lb, ("a fillet does not fit", points[i], r)
        used[i] = t
        t1, t2 = (x + t * a[0], y + t * a[1]), (x + t * b[0], y + t * b[1])
        run.append(t1)
        curves.append(polyline(run))
        curves.append((3, [0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
                       [(t1[0], t1[1], 1.0), (x, y, math.sin(alpha / 2)), (t2[0], t2[1], 1.0)]))
        run = [t2]
    run.append(points[-1])
    curves.append(polyline(run))
    return curves


def rounded_polygon(vertices, radii):
    """A closed loop around `vertices` with rounded corners, starting at a sharp corner or, when
    every corner is rounded, halfway along the last edge."""
    sharp = [i for i, r in enumerate(radii) if r == 0]
    if sharp:
        k = sharp[0]
        path = vertices[k:] + vertices[:k] + [vertices[k]]
        rr = radii[k:] + radii[:k] + [0]
        return rounded_path(path, rr)
    (ax, ay), (bx, by) = vertices[-1], vertices[0]
    m = ((ax + bx) / 2, (ay + by) / 2)
    return rounded_path([m] + vertices + [m], [0] + radii + [0])


def rounded_rect(center, width, height, radius):
    cx, cy = center
    x0, x1, y0, y1 = cx - width / 2, cx + width / 2, cy - height / 2, cy + height / 2
    return rounded_polygon([(x0, y0), (x1, y0), (x1, y1), (x0, y1)], [radius] * 4)


def line_meet(l1, l2):
    """Where the lines (point, direction) l1 and l2 meet."""
    (p, d), (q, e) = l1, l2
    det = d[0] * -e[1] - d[1] * -e[0]
    s = ((q[0] - p[0]) * -e[1] - (q[1] - p[1]) * -e[0]) / det
    return (p[0] + s * d[0], p[1] + s * d[1])


def inset_line(a, b, distance):
    """The line through a and b moved `distance` to its left (inside a counter-clockwise
    polygon), as (point, direction)."""
    d = (b[0] - a[0], b[1] - a[1])
    length = math.hypot(*d)
    n = (-d[1] / length, d[0] / length)
    return ((a[0] + distance * n[0], a[1] + distance * n[1]), d)


def mapped(loop, to_uv):
    """The loop with every control point taken to (u, v) by the affine map `to_uv`; weights are
    kept, so the curves are the same curves in (u, v). Coordinates within 1e-12 of the domain's
    edges are put on them."""
    def snap(x):
        for edge in (0.0, 1.0):
            if abs(x - edge) < 1e-12:
                return edge
        return x
    out = []
    for order, knots, ctrl in loop:
        pts = []
        for x, y, w in ctrl:
            u, v = to_uv(x, y)
            pts.append((snap(u), snap(v), w))
        out.append((order, knots, pts))
    return out


def reversed_curve(curve):
    order, knots, ctrl = curve
    a, b = knots[0], knots[-1]
    return (order, [a + b - k for k in reversed(knots)], list(reversed(ctrl)))


def sample(loop, per_span=32):
    """Points along the loop, in (u, v)."""
    out = []
    for order, knots, ctrl in loop:
        homogeneous = [(x * w, y * w, w) for x, y, w in ctrl]
        lo, hi = knots[order - 1], knots[len(ctrl)]
        steps = per_span * (len(ctrl) - order + 1)
        for i in range(steps):
            x, y, w = de_boor(knots, order, homogeneous, lo + (hi - lo) * i / steps)
            out.append((x / w, y / w))
    return out


def signed_area(points):
    return 0.5 * sum(x0 * y1 - x1 * y0
                     for (x0, y0), (x1, y1) in zip(points, points[1:] + points[:1]))


def oriented(loop, counter_clockwise):
    """The loop, reversed if needed to run counter-clockwise (an outer loop) or clockwise (a
    hole) in (u, v)."""
    if (signed_area(sample(loop)) > 0) == counter_clockwise:
        return loop
    return [reversed_curve(c) for c in reversed(loop)]


def set_trim(patch, outer, holes):
    """Writes the trim: the outer loop counter-clockwise, then the holes clockwise."""
    loops = [oriented(outer, True)] + [oriented(h, False) for h in holes]
    counts, orders, vertex_counts, knots, ranges, points = [], [], [], [], [], []
    for loop in loops:
        counts.append(len(loop))
        for order, k, ctrl in loop:
            orders.append(order)
            vertex_counts.append(len(ctrl))
            knots.extend(k)
            ranges.append(Gf.Vec2d(k[order - 1], k[len(ctrl)]))
            points.extend(Gf.Vec3d(u * w, v * w, w) for u, v, w in ctrl)
    patch.CreateTrimCurveCountsAttr(Vt.IntArray(counts))
    patch.CreateTrimCurveOrdersAttr(Vt.IntArray(orders))
    patch.CreateTrimCurveVertexCountsAttr(Vt.IntArray(vertex_counts))
    patch.CreateTrimCurveKnotsAttr(Vt.DoubleArray(knots))
    patch.CreateTrimCurveRangesAttr(Vt.Vec2dArray(ranges))
    patch.CreateTrimCurvePointsAttr(Vt.Vec3dArray(points))


DOMAIN_LOOP = [polyline([(0, 0), (1, 0), (1, 1), (0, 1), (0, 0)])]


# --- The speaker -------------------------------------------------------------------------

R = 0.85                    # the wall's radius at its ends
BULGE = 0.035               # how far the wall bows out halfway up
Z0, Z1 = 0.12, 1.80         # the wall's bottom and top
BOTTOM_ROUND, TOP_ROUND = 0.12, 0.18
FRONT = -0.75 * math.pi     # the front quarter runs from -135 to -45 degrees


def ring(start):
    """The nine points and weights of the unit circle, counter-clockwise from angle `start`: on
    the circle every 90 degrees, on the square's corners between."""
    out = []
    for k in range(9):
        a = start + k * math.pi / 4
        s, w = (1.0, 1.0) if k % 2 == 0 else (1 / W, W)
        out.append((s * math.cos(a), s * math.sin(a), w))
    return out


def revolve(around, profile, profile_knots, profile_order, axis=None):
    """A Net sweeping `profile` [(r, h, w)] counter-clockwise along u by the circle points
    `around` [(x, y, w)]: P = r (x e1 + y e2) + h a in the frame (e1, e2, a) with
    e1 x e2 = a (default x, y, z). N = dP/du x dP/dv is the profile's direction turned a
    quarter turn clockwise in the (r, h) plane: out of a wall that goes up, up out of a top
    that goes in, down out of a bottom that goes out."""
    e1, e2, a = axis or ((1, 0, 0), (0, 1, 0), (0, 0, 1))
    points, weights = [], []
    for r, h, wj in profile:
        for x, y, wi in around:
            points.append(tuple(r * (x * e1[k] + y * e2[k]) + h * a[k] for k in range(3)))
            weights.append(wi * wj)
    return Net(len(around), len(profile), 3, profile_order, clamped_knots(len(around), 3)
               if len(around) == 3 else list(CIRCLE_KNOTS), profile_knots, points, weights)


def wall_profile():
    """The wall up the v direction: a cubic with vertical ends, bowed out by BULGE, its
    heights at the Greville abscissae so that z is linear in v."""
    knots = [0, 0, 0, 0, 0.5, 1, 1, 1, 1]
    g = greville(knots, 4, 5)
    radii = [R, R, R + 2 * BULGE, R, R]     # the middle point's basis function is 1/2 at v = 1/2
    return [(r, Z0 + (Z1 - Z0) * t, 1.0) for r, t in zip(radii, g)], knots


def z_to_v(z):
    return (z - Z0) / (Z1 - Z0)


def u_at_angle(net, v, angle):
    """The u of the wall quarter `net` where its point at height v lies at `angle`."""
    x, y, _ = net.at(0.5, v)
    middle = math.atan2(y, x)
    target = math.remainder(angle - middle, 2 * math.pi)
    lo, hi = 0.0, 1.0
    for _ in range(60):
        mid = (lo + hi) / 2
        x, y, _ = net.at(mid, v)
        if math.remainder(math.atan2(y, x) - middle, 2 * math.pi) < target:
            lo = mid
        else:
            hi = mid
    return (lo + hi) / 2


def local_map(net, u, v):
    """The affine map from a metric plane about the point (u, v) of `net` — arc length across,
    height up, in model units — to (u, v)."""
    su, sv = net.speeds(u, v)
    return lambda s, t: (u + s / su, v + t / sv)


def round_hole(net, u, v, radius):
    return mapped(circle((0.0, 0.0), radius), local_map(net, u, v))


def speaker(path):
    stage = new_stage(path)
    root = UsdGeom.Xform.Define(stage, "/speaker")
    UsdGeom.Xform.Define(stage, "/speaker/body")
    around = ring(FRONT)
    profile, knots = wall_profile()

    quarters = {}
    for i, name in enumerate(["front", "left", "back", "right"]):
        net = revolve(around[2 * i:2 * i + 3], profile, knots, 4)
        quarters[name] = (net, define_patch(stage, "/speaker/body/" + name, net))

    # Front: the port, 0.25 in radius, 0.80 up; above it the grille, 20 holes 0.035 in radius,
    # 0.15 apart along the wall, in rows 0.135 apart, the middle row staggered.
    net, patch = quarters["front"]
    v_port = z_to_v(0.80)
    holes = [round_hole(net, 0.5, v_port, 0.25)]
    middle = math.atan2(net.at(0.5, 0.5)[1], net.at(0.5, 0.5)[0])
    for row, z in enumerate([1.20, 1.335, 1.47]):
        v = z_to_v(z)
        radius_here = math.hypot(*net.at(0.5, v)[:2])
        offsets = [-0.45, -0.30, -0.15, 0.0, 0.15, 0.30, 0.45] if row != 1 else \
            [-0.375, -0.225, -0.075, 0.075, 0.225, 0.375]
        for s in offsets:
            u = u_at_angle(net, v, middle + s / radius_here)
            holes.append(round_hole(net, u, v, 0.035))
    set_trim(patch, DOMAIN_LOOP, holes)

    # Left and right: a handle slot, 0.44 along the wall by 0.11, corners 0.045, 1.58 up.
    for name in ["left", "right"]:
        net, patch = quarters[name]
        v = z_to_v(1.58)
        slot = mapped(rounded_rect((0.0, 0.0), 0.44, 0.11, 0.045), local_map(net, 0.5, v))
        set_trim(patch, DOMAIN_LOOP, [slot])

    # Back: a cable port, 0.045 in radius, 0.34 up.
    net, patch = quarters["back"]
    set_trim(patch, DOMAIN_LOOP, [round_hole(net, 0.5, z_to_v(0.34), 0.045)])

    # The caps: a quarter-circle shoulder and a flat face, a line as one quadratic span.
    cap_knots = [0, 0, 0, 0.5, 0.5, 1, 1, 1]
    r, top = R - TOP_ROUND, Z1 + TOP_ROUND
    top_profile = [(R, Z1, 1), (R, top, W), (r, top, 1), (r / 2, top, 1), (0, top, 1)]
    define_patch(stage, "/speaker/body/top", revolve(around, top_profile, cap_knots, 3),
                 UsdGeom.Tokens.closed)
    r = R - BOTTOM_ROUND
    bottom_profile = [(0, 0, 1), (r / 2, 0, 1), (r, 0, 1), (R, 0, W), (R, Z0, 1)]
    define_patch(stage, "/speaker/body/bottom", revolve(around, bottom_profile, cap_knots, 3),
                 UsdGeom.Tokens.closed)

    # The driver, behind the port: revolved about -y (e1 = x, e2 = z, a = -y), h measured
    # forward from the speaker's axis. The cone runs in from its rim (0.31 across, hidden
    # behind the wall around the port) to its throat; the dust cap is a spherical dome on it.
    driver = UsdGeom.Xform.Define(stage, "/speaker/driver")
    driver.AddTranslateOp().Set(Gf.Vec3d(0, 0, 0.80))
    frame = ((1, 0, 0), (0, 0, 1), (0, -1, 0))
    cone = [(0.31, 0.62, 1), (0.20, 0.53, 1), (0.10, 0.36, 1)]
    define_patch(stage, "/speaker/driver/cone",
                 revolve(ring(0.0), cone, [0, 0, 0, 1, 1, 1], 3, frame), UsdGeom.Tokens.closed)
    base_r, base_h, rise = 0.10, 0.36, 0.06
    rho = (base_r ** 2 + rise ** 2) / (2 * rise)        # the dome's sphere
    centre_h = base_h + rise - rho
    opening = math.atan2(base_h - centre_h, base_r)     # the base's angle above the equator
    w = math.cos((math.pi / 2 - opening) / 2)
    corner_r = base_r - rise * (base_h - centre_h) / base_r   # the base's tangent at the top
    dome = [(base_r, base_h, 1), (corner_r, base_h + rise, w), (0, base_h + rise, 1)]
    define_patch(stage, "/speaker/driver/cap",
                 revolve(ring(0.0), dome, [0, 0, 0, 1, 1, 1], 3, frame), UsdGeom.Tokens.closed)

    stage.SetDefaultPrim(root.GetPrim())
    stage.GetRootLayer().Save()


# --- The car's side panels ---------------------------------------------------------------

SILL = 0.22
BELT = 0.86
FRAME = 0.065               # the door frame's width around a window
FRONT_WHEEL, REAR_WHEEL = (1.45, 0.33), (-1.30, 0.33)
ARCH = 0.42


def half_width(x, z):
    """The body's half width: the cross-section (fullest at 0.70 up, tumbling home above the
    belt) tapered toward the bumpers in plan."""
    if z <= 0.70:
        section = 0.915 - 0.35 * (z - 0.70) ** 2
    else:
        section = 0.915 - 0.60 * (z - 0.70) ** 2
    return section - 0.12 * (x / 2.2) ** 4


def side_panel(x_back, x_front, z_top, nu, nv, left):
    """A bicubic panel over x in [x_back, x_front], z in [SILL, z_top], on the left (+y) or right
    side, and the map from (x, z) to its (u, v). The control points sit at the knots' Greville
    abscissae, so x and z are linear in u and v; u runs toward the back on the left side and
    toward the front on the right, so that N = dP/du x dP/dv points out."""
    uk, vk = clamped_knots(nu, 4), clamped_knots(nv, 4)
    gu, gv = greville(uk, 4, nu), greville(vk, 4, nv)
    x0, x1 = (x_front, x_back) if left else (x_back, x_front)
    side = 1 if left else -1
    centre = (x_back + x_front) / 2
    points = []
    for t in gv:
        z = SILL + (z_top - SILL) * t
        for s in gu:
            x = x0 + (x1 - x0) * s
            points.append((x - centre, side * half_width(x, z), z))
    net = Net(nu, nv, 4, 4, uk, vk, points)
    return net, (lambda x, z: ((x - x0) / (x1 - x0), (z - SILL) / (z_top - SILL))), centre


def arch_foot(wheel, x_side):
    """Where the wheel arch meets the sill, on the side of x_side."""
    cx, cz = wheel
    dx = math.sqrt(ARCH ** 2 - (SILL - cz) ** 2)
    return (cx + dx if x_side > cx else cx - dx, SILL)


def arch_at(wheel, x):
    """Where the wheel arch crosses the vertical x, above the wheel's centre."""
    cx, cz = wheel
    return (x, cz + math.sqrt(ARCH ** 2 - (x - cx) ** 2))


def fender():
    """Over the front wheel: the arch cut up from the sill, the front top corner rounded, a side
    repeater."""
    xb, xf, zt = 0.86, 2.15, 0.90
    back, front = arch_foot(FRONT_WHEEL, 0.0), arch_foot(FRONT_WHEEL, 3.0)
    outer = rounded_path([front, (xf, SILL), (xf, zt), (xb, zt), (xb, SILL), back],
                         [0, 0, 0.12, 0, 0, 0])
    outer.append(arc(FRONT_WHEEL, ARCH, back, front, clockwise=True))
    repeater = rounded_rect((1.07, 0.78), 0.18, 0.06, 0.025)
    return (xb, xf, zt, 6, 5), outer, [repeater]


def door_front():
    """The front door: its top front corner cut along the A-pillar; the window opening inside
    the frame, down to the belt line; the handle hole."""
    xb, xf, zt = -0.30, 0.85, 1.20
    pillar = ((xf, 0.90), (0.42, zt))
    outer = rounded_polygon([(xb, SILL), (xf, SILL), pillar[0], pillar[1], (xb, zt)],
                            [0, 0, 0.06, 0.10, 0])
    lines = [((0.0, BELT), (1, 0)), inset_line(*pillar, FRAME),
             ((0.0, zt - FRAME), (-1, 0)), ((xb + FRAME, 0.0), (0, -1))]
    window = [line_meet(lines[i - 1], lines[i]) for i in range(len(lines))]
    window = rounded_polygon(window, [0.03, 0.035, 0.08, 0.04])
    handle = rounded_rect((-0.09, 0.75), 0.22, 0.06, 0.025)
    return (xb, xf, zt, 6, 6), outer, [window, handle]


def door_rear():
    """The rear door: its lower rear corner cut by the rear wheel arch, its top rear corner
    along the C-pillar; the window opening; the handle hole."""
    xb, xf, zt = -1.25, -0.31, 1.17
    pillar = ((-1.05, zt), (xb, 1.00))
    foot, edge = arch_foot(REAR_WHEEL, 0.0), arch_at(REAR_WHEEL, xb)
    outer = rounded_path([foot, (xf, SILL), (xf, zt), pillar[0], pillar[1], edge],
                         [0, 0, 0, 0.08, 0.06, 0])
    outer.append(arc(REAR_WHEEL, ARCH, edge, foot, clockwise=True))
    lines = [((0.0, BELT), (1, 0)), ((xf - FRAME, 0.0), (0, 1)), ((0.0, zt - FRAME), (-1, 0)),
             inset_line(*pillar, FRAME), ((xb + FRAME, 0.0), (0, -1))]
    window = [line_meet(lines[i - 1], lines[i]) for i in range(len(lines))]
    window = rounded_polygon(window, [0.03, 0.03, 0.04, 0.05, 0.05])
    handle = rounded_rect((-0.89, 0.75), 0.22, 0.06, 0.025)
    return (xb, xf, zt, 5, 6), outer, [window, handle]


def quarter():
    """Behind the rear door: the rear wheel arch, from the sill to the front edge; the rear
    corners rounded; the fuel filler flap's opening."""
    xb, xf, zt = -2.15, -1.26, 0.95
    foot, edge = arch_foot(REAR_WHEEL, -3.0), arch_at(REAR_WHEEL, xf)
    outer = rounded_path([edge, (xf, zt), (xb, zt), (xb, SILL), foot], [0, 0, 0.10, 0.08, 0])
    outer.append(arc(REAR_WHEEL, ARCH, foot, edge, clockwise=True))
    return (xb, xf, zt, 5, 5), outer, [circle((-1.86, 0.76), 0.085)]


def car_doors(path):
    stage = new_stage(path)
    root = UsdGeom.Xform.Define(stage, "/car")
    for name, build in [("fender", fender), ("door_front", door_front),
                        ("door_rear", door_rear), ("quarter", quarter)]:
        (xb, xf, zt, nu, nv), outer, holes = build()
        group = UsdGeom.Xform.Define(stage, "/car/" + name)
        for side in ["left", "right"]:
            net, to_uv, centre = side_panel(xb, xf, zt, nu, nv, side == "left")
            patch = define_patch(stage, "/car/%s/%s" % (name, side), net)
            set_trim(patch, mapped(outer, to_uv), [mapped(h, to_uv) for h in holes])
        group.AddTranslateOp().Set(Gf.Vec3d(centre, 0, 0))
    stage.SetDefaultPrim(root.GetPrim())
    stage.GetRootLayer().Save()


def main():
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "patches")
    speaker(os.path.join(root, "speaker.usda"))
    car_doors(os.path.join(root, "car_doors.usda"))


if __name__ == "__main__":
    main()
