"""Writes glint's USD models with the real USD library (the usd-core package), so that the
files are what pipelines write.

    pip install usd-core
    python3 scripts/usd/author_models.py

It writes patches/sphere.usda and patches/torus.usda, and binary layers for the tests in
tests/data/usd/ (the sphere as .usdc, and a .usdc whose prim references another layer): the exact NURBS sphere and torus that
glint builds for `Sphere(radius: 1.0)` and `Torus(major_radius: 1.0, minor_radius: 0.35)`
(docs/patch-format.md), from the rational quadratic circle — nine control points on the
square around the unit circle, weights 1, sqrt(1/2), 1, ..., knots 0,0,0,1/4,1/4,...,1,1,1 —
swept about +z: P_ij = (x_i r_j, y_i r_j, z_j), w_ij = w_i w_j.
"""

import math
import os

from pxr import Gf, Sdf, Usd, UsdGeom, Vt

W = math.sqrt(0.5)
CIRCLE = [(1, 0, 1), (1, 1, W), (0, 1, 1), (-1, 1, W), (-1, 0, 1),
          (-1, -1, W), (0, -1, 1), (1, -1, W), (1, 0, 1)]
CIRCLE_KNOTS = [0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1]
HALF_CIRCLE_KNOTS = [0, 0, 0, 0.5, 0.5, 1, 1, 1]


def revolve(stage, path, profile, profile_knots):
    """A NurbsPatch at `path`: `profile` [(r, z, w)] swept counter-clockwise about +z along u."""
    patch = UsdGeom.NurbsPatch.Define(stage, path)
    nu, nv = len(CIRCLE), len(profile)
    # USD lays the points out with u varying fastest: points[v * nu + u].
    points, weights = [], []
    for (r, z, wj) in profile:
        for (x, y, wi) in CIRCLE:
            points.append(Gf.Vec3f(x * r, y * r, z))
            weights.append(wi * wj)
    patch.CreateUVertexCountAttr(nu)
    patch.CreateVVertexCountAttr(nv)
    patch.CreateUOrderAttr(3)
    patch.CreateVOrderAttr(len(profile_knots) - nv)
    patch.CreateUKnotsAttr(Vt.DoubleArray(CIRCLE_KNOTS))
    patch.CreateVKnotsAttr(Vt.DoubleArray(profile_knots))
    patch.CreateURangeAttr(Gf.Vec2d(0, 1))
    patch.CreateVRangeAttr(Gf.Vec2d(0, 1))
    patch.CreateUFormAttr(UsdGeom.Tokens.closed)
    patch.CreatePointsAttr(Vt.Vec3fArray(points))
    patch.CreatePointWeightsAttr(Vt.DoubleArray(weights))
    return patch


def layer(path):
    if os.path.exists(path):
        os.remove(path)
    stage = Usd.Stage.CreateNew(path)
    UsdGeom.SetStageUpAxis(stage, UsdGeom.Tokens.z)
    return stage


def main():
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "patches")

    stage = layer(os.path.join(root, "sphere.usda"))
    meridian = [(0, -1, 1), (1, -1, W), (1, 0, 1), (1, 1, W), (0, 1, 1)]
    revolve(stage, "/sphere", meridian, HALF_CIRCLE_KNOTS)
    stage.SetDefaultPrim(stage.GetPrimAtPath("/sphere"))
    stage.GetRootLayer().Save()

    stage = layer(os.path.join(root, "torus.usda"))
    major, minor = 1.0, 0.35
    tube = [(major + minor * x, minor * y, w) for (x, y, w) in CIRCLE]
    revolve(stage, "/torus", tube, CIRCLE_KNOTS)
    stage.SetDefaultPrim(stage.GetPrimAtPath("/torus"))
    stage.GetRootLayer().Save()

    data = os.path.join(root, "..", "tests", "data", "usd")
    os.makedirs(data, exist_ok=True)
    sphere = Sdf.Layer.FindOrOpen(os.path.join(root, "sphere.usda"))
    sphere.Export(os.path.join(data, "sphere.usdc"))
    stage = layer(os.path.join(data, "referencing.usdc"))
    ball = stage.DefinePrim("/ball", "Xform")
    ball.GetReferences().AddReference("./sphere.usdc")
    stage.GetRootLayer().Save()


if __name__ == "__main__":
    main()
