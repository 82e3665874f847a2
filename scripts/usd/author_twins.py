"""Writes the twin USD layers of glint's tests with the real USD library (the usd-core
package): each layer as text (.usda) and as binary (.usdc), so that the tests can read every
binary layer to the same patches and motion as its text twin, and refuse the same ones.

    pip install usd-core
    python3 scripts/usd/author_twins.py

It writes, into tests/data/usd/:

- xform_ops: a bicubic patch at each level of three nested Xforms that between them use every
  xformOp glint reads: translate, scale, rotateX, rotateY, rotateZ, the six rotateABC orders,
  orient, transform, and a pivot (a translate and its inverse, `!invert!`), with a y-up layer.
- knots: two rational bicubic patches with non-uniform knots, one written with count + order
  knots and one with Maya's count + order - 2 (the end knots left out).
- trim_ranges: a patch with a square hole whose trim curve runs on past the loop (its range is
  narrower than its knots: only the range closes the loop), and a round hole of two rational
  arcs, one of them limited to two thirds of its knots' domain.
- animated: a patch whose points are sampled at time codes 1, 10 and 24, under an Xform whose
  translate and orient are sampled at 1 and 24; 30 time codes a second, 24 frames a second,
  start time code 1.
- half_ops: a patch under an Xform whose ops are written in half precision (translate,
  rotateXYZ, orient, rotateZ, scale), each value one a half holds exactly, so that text and
  binary name the same numbers.
- over and sublayer: compositions glint refuses (an `over` prim, a layer with a sublayer).
"""

import math
import os

from pxr import Gf, Sdf, Usd, UsdGeom, Vt

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "..", "tests", "data", "usd")


def bicubic(stage, path, lift=0.0, weights=None):
    """A bicubic 4 x 4 patch at `path` over [0, 1]^2: a gently curved sheet, 2 wide and 1.5
    deep, its middle lifted by `lift`."""
    patch = UsdGeom.NurbsPatch.Define(stage, path)
    points = []
    for j in range(4):
        for i in range(4):
            x, y = -1.0 + 2.0 * i / 3, -0.75 + 1.5 * j / 3
            z = 0.3 * math.sin(1.1 * i + 0.4 * j) + (lift if 0 < i < 3 and 0 < j < 3 else 0.0)
            points.append(Gf.Vec3f(x, y, z))
    patch.CreateUVertexCountAttr(4)
    patch.CreateVVertexCountAttr(4)
    patch.CreateUOrderAttr(4)
    patch.CreateVOrderAttr(4)
    patch.CreateUKnotsAttr(Vt.DoubleArray([0, 0, 0, 0, 1, 1, 1, 1]))
    patch.CreateVKnotsAttr(Vt.DoubleArray([0, 0, 0, 0, 1, 1, 1, 1]))
    patch.CreateURangeAttr(Gf.Vec2d(0, 1))
    patch.CreateVRangeAttr(Gf.Vec2d(0, 1))
    patch.CreatePointsAttr(Vt.Vec3fArray(points))
    if weights is not None:
        patch.CreatePointWeightsAttr(Vt.DoubleArray(weights))
    return patch


def save(stage, name):
    """The stage's layer as NAME.usda and NAME.usdc."""
    layer = stage.GetRootLayer()
    layer.Export(os.path.join(OUT, name + ".usda"))
    layer.Export(os.path.join(OUT, name + ".usdc"))


def xform_ops():
    stage = Usd.Stage.CreateInMemory()
    UsdGeom.SetStageUpAxis(stage, UsdGeom.Tokens.y)
    outer = UsdGeom.Xform.Define(stage, "/rig")
    outer.AddTranslateOp().Set(Gf.Vec3d(0.5, -1.25, 2.0))
    outer.AddRotateXYZOp().Set(Gf.Vec3f(10.0, -25.0, 40.0))
    outer.AddScaleOp().Set(Gf.Vec3f(1.5, 0.8, 1.2))
    bicubic(stage, "/rig/base")

    arm = UsdGeom.Xform.Define(stage, "/rig/arm")
    arm.AddRotateXOp().Set(30.0)
    arm.AddRotateYOp().Set(-15.0)
    arm.AddRotateZOp().Set(75.0)
    # A pivot: turned about (1, 0.5, 0) rather than the origin.
    pivot = arm.AddTranslateOp(opSuffix="pivot")
    pivot.Set(Gf.Vec3d(1.0, 0.5, 0.0))
    arm.AddOrientOp().Set(Gf.Quatf(0.8, Gf.Vec3f(0.2, -0.4, 0.4)).GetNormalized())
    arm.AddTranslateOp(opSuffix="pivot", isInverseOp=True)
    bicubic(stage, "/rig/arm/upper", lift=0.2)

    hand = UsdGeom.Xform.Define(stage, "/rig/arm/hand")
    for k, order in enumerate(["XZY", "YXZ", "YZX", "ZXY", "ZYX"]):
        op = getattr(hand, "AddRotate%sOp" % order)(opSuffix="r%d" % k)
        op.Set(Gf.Vec3f(5.0 + 7 * k, -12.0 + 3 * k, 20.0 - 9 * k))
    m = Gf.Matrix4d().SetRotate(Gf.Rotation(Gf.Vec3d(1, 1, 0), 33.0))
    m.SetTranslateOnly(Gf.Vec3d(-0.3, 0.7, 1.1))
    hand.AddTransformOp().Set(m)
    bicubic(stage, "/rig/arm/hand/palm", lift=-0.15)
    save(stage, "xform_ops")


def half_ops():
    stage = Usd.Stage.CreateInMemory()
    rig = UsdGeom.Xform.Define(stage, "/rig")
    half = UsdGeom.XformOp.PrecisionHalf
    rig.AddTranslateOp(precision=half).Set(Gf.Vec3h(0.5, -1.25, 2.0))
    rig.AddRotateXYZOp(precision=half).Set(Gf.Vec3h(10.0, -24.0, 40.0))
    # 120 degrees about (1, 1, 1).
    rig.AddOrientOp(precision=half).Set(Gf.Quath(0.5, Gf.Vec3h(0.5, 0.5, 0.5)))
    rig.AddRotateZOp(precision=half).Set(30.0)
    rig.AddScaleOp(precision=half).Set(Gf.Vec3h(1.5, 0.75, 1.25))
    bicubic(stage, "/rig/sheet", lift=0.25)
    save(stage, "half_ops")


def knots():
    stage = Usd.Stage.CreateInMemory()
    UsdGeom.Xform.Define(stage, "/knots")
    for name, full, lift in [("whole", True, 0.0), ("maya", False, 0.4)]:
        patch = UsdGeom.NurbsPatch.Define(stage, "/knots/" + name)
        nu, nv = 6, 5
        ku = [0, 0, 0, 0, 0.3, 0.7, 1, 1, 1, 1]
        kv = [0, 0, 0, 0, 0.45, 1, 1, 1, 1]
        if not full:
            ku, kv = ku[1:-1], kv[1:-1]
        points, weights = [], []
        for j in range(nv):
            for i in range(nu):
                x, y = i / (nu - 1) * 3.0, j / (nv - 1) * 2.0
                points.append(Gf.Vec3f(x, y, 0.25 * math.cos(x + 2 * y) + lift))
                weights.append(1.0 + 0.5 * ((i + 2 * j) % 3) / 2)
        patch.CreateUVertexCountAttr(nu)
        patch.CreateVVertexCountAttr(nv)
        patch.CreateUOrderAttr(4)
        patch.CreateVOrderAttr(4)
        patch.CreateUKnotsAttr(Vt.DoubleArray(ku))
        patch.CreateVKnotsAttr(Vt.DoubleArray(kv))
        patch.CreatePointsAttr(Vt.Vec3fArray(points))
        patch.CreatePointWeightsAttr(Vt.DoubleArray(weights))
    save(stage, "knots")


def trim_ranges():
    stage = Usd.Stage.CreateInMemory()
    patch = bicubic(stage, "/sheet")
    counts, orders, vertex_counts, all_knots, ranges, points = [], [], [], [], [], []

    def curve(order, k, ctrl, rng):
        orders.append(order)
        vertex_counts.append(len(ctrl))
        all_knots.extend(k)
        ranges.append(Gf.Vec2d(*rng))
        points.extend(Gf.Vec3d(u * w, v * w, w) for u, v, w in ctrl)

    # The outer loop: the domain's boundary, counter-clockwise, its range its knots' domain.
    counts.append(1)
    curve(2, [0, 0, 1, 2, 3, 4, 4],
          [(0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1), (0, 0, 1)], (0, 4))
    # A square hole, clockwise, whose polyline runs on to a sixth point: its range [0, 4]
    # stops at the fifth, where the square closes; over the whole knots it would not close.
    counts.append(1)
    square = [(0.15, 0.15), (0.15, 0.4), (0.4, 0.4), (0.4, 0.15), (0.15, 0.15), (0.3, 0.05)]
    curve(2, [0, 0, 1, 2, 3, 4, 5, 5], [(u, v, 1) for u, v in square], (0, 4))
    # A round hole about (0.7, 0.65), radius 0.15, clockwise, of two rational quadratic
    # arcs. The first runs from east to west through south; the second is written over knots
    # [0, 1.5], three quarters from west through north and east to south, and used over
    # [0, 1]: the quarter past its range turns on around the circle, where the loop has
    # closed.
    counts.append(2)
    cx, cy, r, w = 0.7, 0.65, 0.15, math.sqrt(0.5)
    east, south, west, north = (cx + r, cy), (cx, cy - r), (cx - r, cy), (cx, cy + r)
    corner = lambda dx, dy: (cx + dx * r, cy + dy * r)
    curve(3, [0, 0, 0, 0.5, 0.5, 1, 1, 1],
          [(*east, 1), (*corner(1, -1), w), (*south, 1), (*corner(-1, -1), w), (*west, 1)],
          (0, 1))
    curve(3, [0, 0, 0, 0.5, 0.5, 1, 1, 1.5, 1.5, 1.5],
          [(*west, 1), (*corner(-1, 1), w), (*north, 1), (*corner(1, 1), w), (*east, 1),
           (*corner(1, -1), w), (*south, 1)],
          (0, 1))
    patch.CreateTrimCurveCountsAttr(Vt.IntArray(counts))
    patch.CreateTrimCurveOrdersAttr(Vt.IntArray(orders))
    patch.CreateTrimCurveVertexCountsAttr(Vt.IntArray(vertex_counts))
    patch.CreateTrimCurveKnotsAttr(Vt.DoubleArray(all_knots))
    patch.CreateTrimCurveRangesAttr(Vt.Vec2dArray(ranges))
    patch.CreateTrimCurvePointsAttr(Vt.Vec3dArray(points))
    save(stage, "trim_ranges")


def animated():
    stage = Usd.Stage.CreateInMemory()
    stage.SetTimeCodesPerSecond(30)
    stage.SetFramesPerSecond(24)
    stage.SetStartTimeCode(1)
    stage.SetEndTimeCode(24)
    mover = UsdGeom.Xform.Define(stage, "/mover")
    translate = mover.AddTranslateOp()
    translate.Set(Gf.Vec3d(0, 0, 0), Usd.TimeCode(1))
    translate.Set(Gf.Vec3d(2.0, -1.0, 0.5), Usd.TimeCode(24))
    orient = mover.AddOrientOp()
    orient.Set(Gf.Quatf(1, Gf.Vec3f(0, 0, 0)), Usd.TimeCode(1))
    half = math.radians(60) / 2
    orient.Set(Gf.Quatf(math.cos(half), Gf.Vec3f(0, 0, math.sin(half))), Usd.TimeCode(24))
    patch = bicubic(stage, "/mover/cloth")
    attribute = patch.GetPointsAttr()
    rest = list(attribute.Get())
    for time, phase in [(1, 0.0), (10, 1.3), (24, 2.9)]:
        wave = [Gf.Vec3f(p[0], p[1], p[2] + 0.2 * math.sin(2 * p[0] + phase)) for p in rest]
        attribute.Set(Vt.Vec3fArray(wave), Usd.TimeCode(time))
    save(stage, "animated")


def refused():
    stage = Usd.Stage.CreateInMemory()
    bicubic(stage, "/sheet")
    stage.OverridePrim("/sheet/extra")
    save(stage, "over")
    for ext in ["usda", "usdc"]:
        layer = Sdf.Layer.CreateAnonymous("." + ext)
        stage = Usd.Stage.Open(layer)
        bicubic(stage, "/sheet")
        layer.subLayerPaths.append("./knots." + ext)
        layer.Export(os.path.join(OUT, "sublayer." + ext))


if __name__ == "__main__":
    os.makedirs(OUT, exist_ok=True)
    xform_ops()
    half_ops()
    knots()
    trim_ranges()
    animated()
    refused()
