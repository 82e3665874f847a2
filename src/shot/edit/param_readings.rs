//! Every parameter of a shot or look file read at one frame: its value there and the frames of
//! its keys, by its [`ParamPath`] — what an editor shows beside each parameter.

use super::error::EditError;
use super::param_path::ParamPath;
use super::param_sites::TrackMut;
use super::read::read_file;
use crate::anim::Track;

/// One parameter of a file read at a frame.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamReading {
    /// The parameter (highlights named by their index in the file).
    pub path: ParamPath,
    /// Its value at the frame, component by component (one for a number, three for a point,
    /// a direction or a colour); empty for a track left out (a layer without feather).
    pub value: Vec<f32>,
    /// The frames of its keys, in order; empty for a constant.
    pub keys: Vec<f64>,
}

/// Every parameter of the file `text` ([`super::param_paths`], in the same order) with its value
/// at `frame` and the frames of its keys. A `colour` is read whole and then component by
/// component, each with its own keys.
pub fn param_readings(text: &str, frame: f64) -> Result<Vec<ParamReading>, EditError> {
    let mut file = read_file(text)?;
    let mut readings = Vec::new();
    file.for_each_site(&mut |site| match site.track {
        TrackMut::Scalar(track) => readings.push(scalar(site.path, track, frame)),
        TrackMut::Optional(track) => readings.push(match track {
            Some(track) => scalar(site.path, track, frame),
            None => ParamReading {
                path: site.path,
                value: Vec::new(),
                keys: Vec::new(),
            },
        }),
        TrackMut::Point(track) => readings.push(ParamReading {
            path: site.path,
            value: track.at(frame).to_array().to_vec(),
            keys: track.key_frames().collect(),
        }),
        TrackMut::Direction(track) => readings.push(ParamReading {
            path: site.path,
            value: track.at(frame).0.to_array().to_vec(),
            keys: track.key_frames().collect(),
        }),
        TrackMut::Triple(tracks) => {
            let mut keys: Vec<f64> = tracks.iter().flat_map(Track::key_frames).collect();
            keys.sort_by(f64::total_cmp);
            keys.dedup();
            readings.push(ParamReading {
                path: site.path.clone(),
                value: tracks.iter().map(|t| t.at(frame)).collect(),
                keys,
            });
            for (c, track) in tracks.iter().enumerate() {
                if let Some(path) = site.path.try_with_component(c) {
                    readings.push(scalar(path, track, frame));
                }
            }
        }
    });
    Ok(readings)
}

fn scalar(path: ParamPath, track: &Track<f32>, frame: f64) -> ParamReading {
    ParamReading {
        path,
        value: vec![track.at(frame)],
        keys: track.key_frames().collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shot::fixtures::shot_with_highlights;

    /// A shot whose one layer has a keyed translation and a colour keyed in one component.
    fn shot() -> String {
        shot_with_highlights(
            r#"[(patches: "*", expr: Layer((
        stack: [Translate(alpha: [(1, 0.0), (21, 0.4)], beta: 0.1)],
        epsilon: 0.05,
        colour: (1.0, [(1, 0.0), (11, 1.0)], 0.5),
    )))]"#,
        )
    }

    fn reading<'a>(readings: &'a [ParamReading], path: &str) -> &'a ParamReading {
        let path: ParamPath = path.parse().unwrap();
        readings.iter().find(|r| r.path == path).unwrap()
    }

    #[test]
    fn a_keyed_number_is_read_between_its_keys() {
        let readings = param_readings(&shot(), 6.0).unwrap();
        let alpha = reading(&readings, "highlights[0].layers[0].stack[0].alpha");
        assert!((alpha.value[0] - 0.1).abs() < 1e-6, "{alpha:?}");
        assert_eq!(alpha.keys, vec![1.0, 21.0]);
        let beta = reading(&readings, "highlights[0].layers[0].stack[0].beta");
        assert_eq!((beta.value.clone(), beta.keys.len()), (vec![0.1], 0));
    }

    #[test]
    fn a_colour_is_read_whole_and_by_component() {
        let readings = param_readings(&shot(), 6.0).unwrap();
        let colour = reading(&readings, "highlights[0].layers[0].colour");
        assert_eq!(colour.value, vec![1.0, 0.5, 0.5]);
        assert_eq!(colour.keys, vec![1.0, 11.0]);
        let green = reading(&readings, "highlights[0].layers[0].colour[1]");
        assert_eq!(green.value, vec![0.5]);
        let red = reading(&readings, "highlights[0].layers[0].colour[0]");
        assert!(red.keys.is_empty());
    }

    #[test]
    fn a_feather_left_out_has_no_value() {
        let readings = param_readings(&shot(), 1.0).unwrap();
        let feather = reading(&readings, "highlights[0].layers[0].feather");
        assert!(feather.value.is_empty() && feather.keys.is_empty());
        let opacity = reading(&readings, "highlights[0].layers[0].opacity");
        assert_eq!(opacity.value, vec![1.0]);
    }
}
