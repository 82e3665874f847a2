//! Layer frame axes written in a model's coordinates, turned into the world's as each patch is
//! turned at a frame.

use glam::{DQuat, DVec3};

use super::validated::Shot;
use crate::highlight::{Expr, Layer, LayerFrame};

/// `layer` with the axis of its `Along` frame turned by `rotation` (a `Patch` frame is left as it
/// is).
#[must_use]
pub(super) fn turned_layer(layer: &Layer, rotation: DQuat) -> Layer {
    let mut turned = layer.clone();
    if let LayerFrame::Along { axis } = &mut turned.frame {
        let world = rotation * DVec3::from(axis.map(f64::from));
        *axis = world.as_vec3().to_array();
    }
    turned
}

/// Whether some layer of `expr` has an `Along` frame.
#[must_use]
pub(super) fn has_axes(expr: &Expr) -> bool {
    expr.layers().iter().any(|l| !l.frame.is_patch())
}

impl Shot {
    /// `layer` as it is drawn on patch `patch` at `frame`: the axis of its `Along` frame, written
    /// in the model's coordinates, turned as the patch's instance and parts turn it there
    /// ([`Shot::rotation_at`]), so that a frame along a car's body rides with the car.
    #[must_use]
    pub fn layer_on(&self, layer: &Layer, patch: usize, frame: f64) -> Layer {
        turned_layer(layer, self.rotation_at(patch, frame))
    }

    /// `expr` as it is drawn on patch `patch` at `frame`: every layer as [`Shot::layer_on`] turns
    /// it.
    #[must_use]
    pub fn expr_on(&self, expr: &Expr, patch: usize, frame: f64) -> Expr {
        let rotation = self.rotation_at(patch, frame);
        let mut turned = expr.clone();
        for layer in turned.layers_mut() {
            *layer = turned_layer(layer, rotation);
        }
        turned
    }
}
