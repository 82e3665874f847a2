//! An instance's moving parts as written: each found among the instance's parts, their nesting
//! (every patch moved by parts that hold one another), and how far they can carry the model.

use std::path::Path;
use std::sync::Arc;

use super::file::InstanceSpec;
use super::pose::{Deform, InstancePose};
use super::source::Source;
use super::ShotError;
use crate::formats::ron_location::closest_name;
use crate::formats::ron_paths::Step::{Entry, Field, Index};
use crate::geom::{PatchGroup, PatchLibrary, MAX_COORDINATE};

/// How instance `spec` (item `index` of the shot's instances) is placed at any frame: its
/// transform, its model's own motion (`deform`, read from `file`), and each of its moving parts
/// found among `groups` (the model's parts and the instance's own, indices into `model`). Every
/// patch must be moved by parts that nest: of any two moving parts holding it, one holds every
/// patch of the other (and more).
pub(super) fn pose_of(
    spec: &InstanceSpec,
    index: usize,
    (model, deform, file): (&Arc<PatchLibrary>, Option<Deform>, &Path),
    groups: &[&PatchGroup],
    source: &Source,
    first_patch: usize,
) -> Result<InstancePose, ShotError> {
    let at = |part: &str, message: String| {
        source.error_at(
            &[
                Field("instances"),
                Index(index),
                Field("parts"),
                Entry(part),
            ],
            message,
        )
    };
    let mut parts = Vec::with_capacity(spec.parts.len());
    let mut members: Vec<&[usize]> = Vec::with_capacity(spec.parts.len());
    for (name, transform) in &spec.parts {
        let Some(group) = groups.iter().find(|g| g.name == *name) else {
            let names: Vec<&str> = groups.iter().map(|g| g.name.as_str()).collect();
            let mut message = format!("instance \"{}\" has no part \"{name}\"", spec.name);
            match closest_name(name, &names) {
                Some(close) => message.push_str(&format!("; did you mean \"{close}\"?")),
                None if names.is_empty() => message.push_str(
                    "; it has no parts (a model's parts file or the instance's `groups` name them)",
                ),
                None => {
                    let quoted: Vec<String> = names.iter().map(|n| format!("\"{n}\"")).collect();
                    message.push_str(&format!("; its parts are {}", quoted.join(", ")));
                }
            }
            return Err(at(name, message));
        };
        transform.check().map_err(|(field, message)| {
            source.error_at(
                &[
                    Field("instances"),
                    Index(index),
                    Field("parts"),
                    Entry(name),
                    Field(field),
                ],
                format!("part \"{name}\" of instance \"{}\": {message}", spec.name),
            )
        })?;
        parts.push((name.clone(), transform.clone()));
        members.push(group.patches.as_slice());
    }
    let mut chains = vec![Vec::new(); model.patches.len()];
    for (part, patches) in members.iter().enumerate() {
        for &patch in *patches {
            chains[patch].push(part);
        }
    }
    for (patch, chain) in chains.iter_mut().enumerate() {
        // Outermost first: a part holding another has more patches.
        chain.sort_by_key(|&part| std::cmp::Reverse(members[part].len()));
        for pair in chain.windows(2) {
            let (outer, inner) = (pair[0], pair[1]);
            let nested = members[outer].len() > members[inner].len()
                && members[inner].iter().all(|p| members[outer].contains(p));
            if !nested {
                let (a, b) = (&parts[outer].0, &parts[inner].0);
                return Err(at(b, format!(
                    "the parts \"{a}\" and \"{b}\" of instance \"{}\" both move the patch \"{}\", and neither holds the other: a patch may move with parts nested one in another, never with two side by side",
                    spec.name, model.patches[patch].name
                )));
            }
        }
    }
    Ok(InstancePose {
        patches: first_patch..first_patch + model.patches.len(),
        model: Arc::clone(model),
        transform: spec.transform.clone(),
        parts,
        chains,
        deform,
        file: file.to_path_buf(),
    })
}

/// Checks that no frame carries a patch of `pose` beyond ±[`MAX_COORDINATE`], where
/// coordinates lose their precision: the reach of the instance's transform over that of each
/// chain of parts ([`TransformSpec::reach`](super::file::TransformSpec::reach)), from the model's
/// farthest control point.
pub(super) fn check_reach(
    pose: &InstancePose,
    spec: &InstanceSpec,
    index: usize,
    source: &Source,
) -> Result<(), ShotError> {
    let mut radius = pose
        .model
        .control_points()
        .map(|p| p.length())
        .fold(0.0, f64::max);
    if let Some(deform) = &pose.deform {
        for &patch in deform.motion.moving() {
            for &time in deform.motion.sample_times() {
                let farthest = deform
                    .motion
                    .points_at(patch, time)
                    .iter()
                    .map(|p| p.length())
                    .fold(0.0, f64::max);
                radius = radius.max(farthest);
            }
        }
    }
    let mut chains: Vec<&Vec<usize>> = pose.chains.iter().collect();
    chains.sort();
    chains.dedup();
    let reach = chains
        .into_iter()
        .map(|chain| {
            let inside = chain
                .iter()
                .rev()
                .fold(radius, |r, &part| pose.parts[part].1.reach(r));
            pose.transform.reach(inside)
        })
        .fold(0.0, f64::max);
    if reach.is_finite() && reach <= MAX_COORDINATE {
        return Ok(());
    }
    Err(source.error_at(
        &[Field("instances"), Index(index), Field("transform")],
        format!(
            "the transforms of instance \"{}\" can carry its patches up to {reach:e} from the origin at some frame, beyond ±{MAX_COORDINATE:e}, where coordinates lose their precision; scale or move it less",
            spec.name
        ),
    ))
}
