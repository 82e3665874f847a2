//! Pinned highlights: each pin's patch found when the shot is read, its parameters checked at
//! every frame, and on each frame the layer's translation solved for its point.

use super::file::HighlightSpec;
use super::frame_state::{FrameState, HeldFrames};
use super::source::Source;
use super::validated::Shot;
use super::written::Written;
use super::ShotError;
use crate::anim::Track;
use crate::formats::ron_location::closest_name;
use crate::formats::ron_paths::Step::{self, Field, Index};
use crate::geom::PatchLibrary;
use crate::highlight::{Expr, Pin};

/// Where the pin of layer `layer` of highlight entry `written` is: `highlights[i].expr`, the
/// Booleans' operands down to the layer, its parentheses, `pin`.
pub(super) fn pin_path<P>(written: Written, expr: &Expr<P>, layer: usize) -> Vec<Step<'static>> {
    let mut path = vec![Field("highlights"), Index(written.index), Field("expr")];
    path.extend(
        expr.layer_route(layer)
            .unwrap_or_default()
            .into_iter()
            .map(Index),
    );
    path.push(Field("pin"));
    path
}

/// The patch (index into `library`) of every pin: per highlight entry, per layer left to
/// right, `None` for a layer without a pin. A pin names a patch, or a part and the `member`-th
/// of its patches in index order.
pub(super) fn resolve_pins(
    highlights: &[(HighlightSpec, Written)],
    library: &PatchLibrary,
    sources: &[Source],
) -> Result<Vec<Vec<Option<usize>>>, ShotError> {
    highlights
        .iter()
        .map(|(spec, written)| {
            let layers = spec.expr.layers();
            (0..layers.len())
                .map(|k| {
                    let Some(pin) = &layers[k].pin else {
                        return Ok(None);
                    };
                    pin_patch(pin, library).map(Some).map_err(|message| {
                        let mut path = pin_path(*written, &spec.expr, k);
                        path.push(Field("patch"));
                        sources[written.source].error_at(&path, message)
                    })
                })
                .collect()
        })
        .collect()
}

/// The patch `pin` names, or why it names none.
fn pin_patch(pin: &Pin<Track<f32>>, library: &PatchLibrary) -> Result<usize, String> {
    if let Some(patch) = library.patches.iter().position(|p| p.name == pin.patch) {
        return match pin.member {
            0 => Ok(patch),
            m => Err(format!(
                "the pin names the patch \"{}\", which has no members: member is {m}, but only a \
                 part has members; leave it out",
                pin.patch
            )),
        };
    }
    if let Some(group) = library.group(&pin.patch) {
        return group.patches.get(pin.member).copied().ok_or_else(|| {
            format!(
                "the part \"{}\" has {} patches, so member must be below {}, not {}",
                pin.patch,
                group.patches.len(),
                group.patches.len(),
                pin.member
            )
        });
    }
    let names = library.names();
    let mut message = format!("the pin's patch \"{}\" is no patch or part", pin.patch);
    if let Some(close) = closest_name(&pin.patch, &names) {
        message.push_str(&format!("; did you mean \"{close}\"?"));
    } else {
        message.push_str("; patches are named INSTANCE/PATCH and parts INSTANCE/PART");
    }
    Err(message)
}

impl Shot {
    /// The patch that layer `layer` of highlight entry `entry` is pinned to, if it is pinned.
    #[must_use]
    pub fn pinned_patch(&self, entry: usize, layer: usize) -> Option<usize> {
        self.pins.get(entry)?.get(layer).copied().flatten()
    }

    /// Centres every pinned layer of highlight entry `entry`, read at a frame as `expr`, on its
    /// pin's point on the frame's model under its camera and light ([`Layer::centred_at`]),
    /// so that a pin on a moving part stays on its point of the part; the pins are cleared. A
    /// layer whose centring fails (an invalid operation before its translation) keeps its pin,
    /// so that preparing it reports the error.
    ///
    /// A pin that holds its shape ([`Pin::hold`]) on a frame other than the held one also gets
    /// the map that keeps its highlight on the surface as it lies there ([`Shot::shape_map`]):
    /// the layer as read at this frame, centred on the same (u, v) on the held frame's model,
    /// under its camera and light.
    pub(super) fn centre_pins(
        &self,
        entry: usize,
        expr: &mut Expr,
        state: &FrameState,
        held: &mut HeldFrames,
    ) {
        for (k, layer) in expr.layers_mut().into_iter().enumerate() {
            let (Some(pin), Some(patch)) = (&layer.pin, self.pinned_patch(entry, k)) else {
                continue;
            };
            let uv = (f64::from(pin.u), f64::from(pin.v));
            let point = self.highlight_point(state, patch, uv);
            // Centred in the layer's frame as the pinned patch draws it; the layer keeps its axis
            // in the model's coordinates.
            let drawn = self.layer_on(layer, patch, state.frame);
            let Ok(mut centred) = drawn.centred_at(&point.frame, point.half_vector) else {
                continue;
            };
            if let Some(frame) = pin.hold.filter(|&f| f as f64 != state.frame) {
                let held_state = self.held_frame(held, frame);
                let point = self.highlight_point(held_state, patch, uv);
                let drawn = self.layer_on(layer, patch, held_state.frame);
                if let Ok(then) = drawn.centred_at(&point.frame, point.half_vector) {
                    centred.shape_map =
                        self.shape_map((&centred, state), (&then, held_state), patch, uv);
                }
            }
            let frame = std::mem::replace(&mut layer.frame, centred.frame.clone());
            *layer = centred;
            layer.frame = frame;
        }
    }

    /// Checks that the (u, v) of `pin`, the pin of layer `layer` of highlight entry `entry`,
    /// at `frame` lies in its patch's domain; the error is the message.
    pub(super) fn check_pin(
        &self,
        entry: usize,
        layer: usize,
        pin: &Pin<Track<f32>>,
        frame: f64,
    ) -> Result<(), String> {
        let Some(patch) = self.pinned_patch(entry, layer) else {
            return Ok(());
        };
        let named = &self.library.patches[patch];
        let domain = named.surface.domain();
        let (u, v) = (f64::from(pin.u.at(frame)), f64::from(pin.v.at(frame)));
        if domain.contains(u, v) {
            return Ok(());
        }
        Err(format!(
            "at frame {frame} the pin's (u, v) = ({u}, {v}) is outside the domain of \
             \"{}\": u in [{}, {}], v in [{}, {}]",
            named.name, domain.u.0, domain.u.1, domain.v.0, domain.v.1
        ))
    }
}
