"""Writes glint's animated USD model with the real USD library (the usd-core package), so that
its time samples are what pipelines write.

    pip install usd-core
    python3 scripts/usd/author_animated.py

It writes patches/flag.usda: a flag on a pole, 24 time codes a second from time code 1 to 24.

- /flag/cloth, a bicubic NurbsPatch 2 units wide along x (from the pole at x = 0) and 1 high
  along z, whose `points` are sampled at time codes 1, 12 and 24: each control point (x, 0, z)
  is displaced in y by c(x) * (0.4 * sin(pi * x - phase) + (z - 0.5)^2), phase 0, pi/2 and pi,
  with c = 0, 0, 0.5, 1, 1 along x, so that its edge on the pole stays straight and flat.
- /flag/turn/vane, a flat NurbsPatch (a unit square in the xz plane, from x = -1 to the pole;
  linear along x, cubic along z with the cloth's rows) under the Xform /flag/turn, whose `xformOp:rotateZ` is sampled at time codes 1
  (0 degrees) and 24 (90 degrees): a vane hinged on the pole, sharing the cloth's edge at time
  code 1.
"""

import math
import os

from pxr import Gf, Sdf, Usd, UsdGeom, Vt

NU, NV = 5, 4
RAMP = [0.0, 0.0, 0.5, 1.0, 1.0]
TIMES = [1, 12, 24]
PHASES = [0.0, math.pi / 2, math.pi]


def cloth_points(phase):
    """The cloth's control points, u (along x) varying fastest: points[v * NU + u]."""
    points = []
    for j in range(NV):
        z = j / (NV - 1)
        for i in range(NU):
            x = 2.0 * i / (NU - 1)
            y = RAMP[i] * (0.4 * math.sin(math.pi * x - phase) + (z - 0.5) ** 2)
            points.append(Gf.Vec3f(x, y, z))
    return points


def open_knots(count, order):
    """A clamped uniform knot vector of count + order knots over [0, 1]."""
    inner = count - order
    return [0.0] * order + [(k + 1) / (inner + 1) for k in range(inner)] + [1.0] * order


def main():
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "patches")
    path = os.path.join(root, "flag.usda")
    if os.path.exists(path):
        os.remove(path)
    stage = Usd.Stage.CreateNew(path)
    UsdGeom.SetStageUpAxis(stage, UsdGeom.Tokens.z)
    stage.SetTimeCodesPerSecond(24)
    stage.SetFramesPerSecond(24)
    stage.SetStartTimeCode(1)
    stage.SetEndTimeCode(24)

    flag = UsdGeom.Xform.Define(stage, "/flag")
    stage.SetDefaultPrim(flag.GetPrim())

    cloth = UsdGeom.NurbsPatch.Define(stage, "/flag/cloth")
    cloth.CreateUVertexCountAttr(NU)
    cloth.CreateVVertexCountAttr(NV)
    cloth.CreateUOrderAttr(4)
    cloth.CreateVOrderAttr(4)
    cloth.CreateUKnotsAttr(Vt.DoubleArray(open_knots(NU, 4)))
    cloth.CreateVKnotsAttr(Vt.DoubleArray(open_knots(NV, 4)))
    cloth.CreateURangeAttr(Gf.Vec2d(0, 1))
    cloth.CreateVRangeAttr(Gf.Vec2d(0, 1))
    points = cloth.CreatePointsAttr()
    for time, phase in zip(TIMES, PHASES):
        points.Set(Vt.Vec3fArray(cloth_points(phase)), Usd.TimeCode(time))

    turn = UsdGeom.Xform.Define(stage, "/flag/turn")
    rotate = turn.AddRotateZOp(UsdGeom.XformOp.PrecisionDouble)
    rotate.Set(0.0, Usd.TimeCode(1))
    rotate.Set(90.0, Usd.TimeCode(24))

    vane = UsdGeom.NurbsPatch.Define(stage, "/flag/turn/vane")
    vane.CreateUVertexCountAttr(2)
    vane.CreateVVertexCountAttr(NV)
    vane.CreateUOrderAttr(2)
    vane.CreateVOrderAttr(4)
    vane.CreateUKnotsAttr(Vt.DoubleArray([0, 0, 1, 1]))
    vane.CreateVKnotsAttr(Vt.DoubleArray(open_knots(NV, 4)))
    # The same rows as the cloth's, so that the shared edge is the same curve.
    rows = [j / (NV - 1) for j in range(NV)]
    vane.CreatePointsAttr(Vt.Vec3fArray([Gf.Vec3f(x, 0, z) for z in rows for x in (-1, 0)]))

    stage.GetRootLayer().Save()


if __name__ == "__main__":
    main()
