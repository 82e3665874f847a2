//! OpenEXR output: named f32 channels of one image in one file, for compositing (the AOVs as
//! layers: `R G B A`, `matte.Y`, `depth.Z`, `normal.X` …), written atomically.

use std::path::Path;

use exr::prelude::{
    AnyChannel, AnyChannels, AttributeValue, FlatSamples, Image, SmallVec, Text, WritableImage,
};

use super::atomic::{write_atomically, WriteError};

/// Writes `channels` (name, one value per pixel, rows from the top) as a `width × height` EXR,
/// with a text attribute in its header for each `(name, text)` of `text`. Channel names with a
/// dot are read as `layer.channel` by compositing software.
pub fn write_exr(
    path: &Path,
    width: u32,
    height: u32,
    channels: Vec<(String, Vec<f32>)>,
    text: &[(&str, &str)],
) -> Result<(), WriteError> {
    let pixels = width as usize * height as usize;
    if let Some((name, values)) = channels.iter().find(|(_, v)| v.len() != pixels) {
        return Err(WriteError {
            path: path.display().to_string(),
            reason: format!(
                "channel {name} has {} values for {pixels} pixels",
                values.len()
            ),
        });
    }
    let list: SmallVec<[AnyChannel<FlatSamples>; 4]> = channels
        .into_iter()
        .map(|(name, values)| AnyChannel::new(name.as_str(), FlatSamples::F32(values)))
        .collect();
    let mut image =
        Image::from_channels((width as usize, height as usize), AnyChannels::sort(list));
    for (name, value) in text {
        image
            .attributes
            .other
            .insert(Text::from(*name), AttributeValue::Text(Text::from(*value)));
    }
    write_atomically(path, |out| {
        image.write().to_buffered(out).map_err(|e| e.to_string())
    })
}

/// The text attribute `name` in the header of the EXR file at `path`: `Ok(None)` when it has
/// none, `Err` when the file cannot be read as an EXR.
pub fn try_read_exr_text(path: &Path, name: &str) -> Result<Option<String>, String> {
    let meta = exr::meta::MetaData::read_from_file(path, false).map_err(|e| e.to_string())?;
    let found = meta.headers.iter().find_map(|header| {
        let attributes = [
            &header.shared_attributes.other,
            &header.own_attributes.other,
        ];
        attributes
            .into_iter()
            .find_map(|other| match other.get(&Text::from(name)) {
                Some(AttributeValue::Text(text)) => Some(text.to_string()),
                _ => None,
            })
    });
    Ok(found)
}

#[cfg(test)]
mod tests {
    use super::*;
    use exr::prelude::read_all_flat_layers_from_file;

    #[test]
    fn channels_round_trip_by_name() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.exr");
        let channels = vec![
            ("R".to_string(), vec![0.25, 0.5, 0.75, 1.0, 0.0, 2.0]),
            (
                "depth.Z".to_string(),
                vec![0.1, 0.2, 0.3, 0.4, 0.5, f32::INFINITY],
            ),
        ];
        write_exr(
            &path,
            3,
            2,
            channels.clone(),
            &[("glint:fingerprint", "abc")],
        )
        .unwrap();
        assert_eq!(
            try_read_exr_text(&path, "glint:fingerprint"),
            Ok(Some("abc".to_string()))
        );
        assert_eq!(try_read_exr_text(&path, "other"), Ok(None));
        let image = read_all_flat_layers_from_file(&path).unwrap();
        let layer = &image.layer_data[0];
        for (name, values) in channels {
            let channel = layer
                .channel_data
                .list
                .iter()
                .find(|c| c.name.to_string() == name)
                .unwrap();
            let read: Vec<f32> = channel.sample_data.values_as_f32().collect();
            assert_eq!(read, values, "{name}");
        }
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn a_short_channel_is_refused_before_writing() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("b.exr");
        let e = write_exr(&path, 2, 2, vec![("Y".into(), vec![0.0; 3])], &[]).unwrap_err();
        assert!(e.to_string().contains("3 values for 4 pixels"), "{e}");
        assert!(!path.exists());
    }
}
