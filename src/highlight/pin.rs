//! A pin: the surface point a layer's highlight centre is kept on.

use serde::{Deserialize, Serialize};

/// A surface point, named by patch and parameters, that a layer's highlight centre stays on
/// while the camera, light and model move: on every frame the layer's placing translation
/// ([`Layer::placing_translation`](super::Layer::placing_translation)) is solved so that the
/// transformed H equals N there ([`Layer::centred_on`](super::Layer::centred_on)).
///
/// The highlight model knows points only by their frames, so the names are resolved and the
/// point's frame found by whoever knows the geometry (a shot); a layer whose pin is still set
/// does not [`prepare`](super::Layer::prepare).
///
/// RON: `(patch: "teapot/lid", u: 0.5, v: 0.25)`, or with keys
/// `(patch: "teapot/5", u: [(1, 0.2), (48, 0.6)], v: 0.5)`; holding the shape the layer has at
/// frame 1, `(patch: "teapot/24", u: 0.5, v: 0.5, hold: 1)`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Pin<P = f32> {
    /// A patch name (`INSTANCE/PATCH`) or a part name (`INSTANCE/PART`).
    pub patch: String,
    /// Which patch of a part, counting its patches in index order from 0 (default 0); 0 for a
    /// patch name.
    #[serde(default)]
    pub member: usize,
    /// The u parameter, inside the patch's domain.
    pub u: P,
    /// The v parameter, inside the patch's domain.
    pub v: P,
    /// The frame whose shape the layer holds around the point: on every frame a linear map of
    /// the tangent coordinates is solved so that the highlight covers the surface about the
    /// point as it does at this frame, in size, aspect and direction, while the view and light
    /// change ([`ShapeMap`](super::ShapeMap)). None (the default): the shape follows the view.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub hold: Option<i64>,
}

impl<P> Pin<P> {
    /// The same pin with its parameters mapped through `f`, u before v.
    #[must_use]
    pub fn map<Q>(&self, mut f: impl FnMut(&P) -> Q) -> Pin<Q> {
        Pin {
            patch: self.patch.clone(),
            member: self.member,
            u: f(&self.u),
            v: f(&self.v),
            hold: self.hold,
        }
    }
}
