//! Every animatable parameter of a shot, visited one at a time: what checking every key needs,
//! with the compiler naming this file when a parameter is added.

use super::file::{CameraSpec, LightSpec, ProjectionSpec};
use super::validated::{Material, Shot};
use crate::anim::Keyed;

impl Shot {
    /// Calls `f` with every track of the shot: the camera's, the light's, each material's,
    /// each highlight's, each shade entry's, the outlines' and each `lines` entry's, in that order.
    pub fn for_each_param(&self, f: &mut dyn FnMut(&dyn Keyed)) {
        self.camera.for_each_param(f);
        self.light.for_each_param(f);
        for (_, material) in &self.materials {
            material.for_each_param(f);
        }
        for highlight in &self.highlights {
            highlight.expr.for_each_param(|track| f(track));
        }
        for shade in &self.shade {
            shade.stack().for_each_param(|track| f(track));
        }
        if let Some(outlines) = &self.outlines {
            outlines.for_each_param(f);
        }
        for line in &self.lines {
            line.for_each_param(f);
        }
    }
}

impl CameraSpec {
    /// Calls `f` with every track of the camera. The fields are named one by one, so a new
    /// field does not compile until it is visited here (or said to be no track).
    pub(super) fn for_each_param(&self, f: &mut dyn FnMut(&dyn Keyed)) {
        let CameraSpec {
            eye,
            orbit,
            target,
            up,
            projection,
            near: _,
            far: _,
        } = self;
        if let Some(eye) = eye {
            f(eye);
        }
        if let Some(orbit) = orbit {
            orbit.for_each_track(&mut |_, track| f(track));
        }
        f(target);
        f(up);
        match projection {
            ProjectionSpec::Perspective { fov_y_degrees } => f(fov_y_degrees),
            ProjectionSpec::Orthographic { height } => f(height),
        }
    }
}

impl LightSpec {
    pub(super) fn for_each_param(&self, f: &mut dyn FnMut(&dyn Keyed)) {
        match self {
            LightSpec::Directional { towards } => f(towards),
            LightSpec::Point { position } => f(position),
        }
    }
}

impl Material {
    pub(super) fn for_each_param(&self, f: &mut dyn FnMut(&dyn Keyed)) {
        match self {
            Material::Cel { base, bands } => {
                f(base);
                for (threshold, colour) in bands {
                    f(threshold);
                    f(colour);
                }
            }
            Material::XToon {
                tone,
                texture: _,
                shape: _,
            } => tone.for_each_param(|track| f(track)),
        }
    }
}
