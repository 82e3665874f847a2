//! Frame lists as render farms pass them: `12`, `1-48`, `1-48x2` (every second frame),
//! `1,5,9-12`, and negative frames such as `-5--1`.

use crate::shot::MAX_FRAMES;

/// The frames of `spec` in the order written, without repeats: at most [`MAX_FRAMES`] in all,
/// found in time linear in them.
pub fn parse_frames(spec: &str) -> Result<Vec<i64>, String> {
    let mut frames = Vec::new();
    let mut seen = std::collections::HashSet::new();
    for part in spec.split(',').map(str::trim) {
        for frame in parse_part(part)? {
            if seen.insert(frame) {
                if frames.len() as i64 >= MAX_FRAMES {
                    return Err(format!("'{spec}' lists more than {MAX_FRAMES} frames"));
                }
                frames.push(frame);
            }
        }
    }
    Ok(frames)
}

/// `frames` as a frame list [`parse_frames`] reads back: sorted, runs of consecutive frames as
/// `first-last`, joined by commas (`3,7-9,12`); empty for no frames.
#[must_use]
pub fn frame_spec(frames: &[i64]) -> String {
    let mut sorted = frames.to_vec();
    sorted.sort_unstable();
    sorted.dedup();
    let mut parts: Vec<String> = Vec::new();
    let mut at = 0;
    while at < sorted.len() {
        let first = sorted[at];
        let mut last = first;
        while at + 1 < sorted.len() && sorted[at + 1] == last + 1 {
            at += 1;
            last = sorted[at];
        }
        parts.push(if first == last {
            first.to_string()
        } else {
            format!("{first}-{last}")
        });
        at += 1;
    }
    parts.join(",")
}

fn parse_part(part: &str) -> Result<Vec<i64>, String> {
    let bad = || {
        format!(
            "cannot read the frame list part '{part}'; write frames as 12, 1-48, 1-48x2 or 1,5,9-12"
        )
    };
    let number = |s: &str| s.trim().parse::<i64>().map_err(|_| bad());
    let (range, step) = match part.split_once('x') {
        Some((range, step)) => (range, number(step)?),
        None => (part, 1),
    };
    if step < 1 {
        return Err(format!(
            "the step in '{part}' must be at least 1, as in 1-48x2"
        ));
    }
    // The dash between two numbers is the first one after a digit.
    let dash = range
        .char_indices()
        .skip(1)
        .find(|&(i, c)| c == '-' && range[..i].ends_with(|d: char| d.is_ascii_digit()))
        .map(|(i, _)| i);
    let (first, last) = match dash {
        Some(i) => (number(&range[..i])?, number(&range[i + 1..])?),
        None if step == 1 => {
            let frame = number(range)?;
            (frame, frame)
        }
        None => return Err(bad()),
    };
    if first > last {
        return Err(format!(
            "the range '{part}' runs backwards; write the first frame first"
        ));
    }
    if (i128::from(last) - i128::from(first)) / i128::from(step) >= i128::from(MAX_FRAMES) {
        return Err(format!("'{part}' lists more than {MAX_FRAMES} frames"));
    }
    Ok((first..=last).step_by(step as usize).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn farm_frame_lists_expand_in_order() {
        assert_eq!(parse_frames("12").unwrap(), vec![12]);
        assert_eq!(parse_frames("1-4").unwrap(), vec![1, 2, 3, 4]);
        assert_eq!(parse_frames("1-9x3").unwrap(), vec![1, 4, 7]);
        assert_eq!(parse_frames("1,5,9-12").unwrap(), vec![1, 5, 9, 10, 11, 12]);
        assert_eq!(parse_frames("3, 1-3").unwrap(), vec![3, 1, 2]);
        assert_eq!(parse_frames("-3--1").unwrap(), vec![-3, -2, -1]);
        assert_eq!(parse_frames("-2-1").unwrap(), vec![-2, -1, 0, 1]);
    }

    #[test]
    fn long_lists_read_and_their_length_is_bounded() {
        assert_eq!(parse_frames("1-999999").unwrap().len(), 999_999);
        assert_eq!(parse_frames("1-999999,5,999999").unwrap().len(), 999_999);
        let e = parse_frames("1-600000,600001-1200000").unwrap_err();
        assert!(e.contains("more than"), "{e}");
    }

    #[test]
    fn a_spec_of_frames_reads_back_as_them() {
        assert_eq!(frame_spec(&[12, 3, 7, 8, 9, -2, -1]), "-2--1,3,7-9,12");
        assert_eq!(frame_spec(&[]), "");
        for frames in [
            vec![5],
            vec![1, 2, 3, 10, 11, 20],
            vec![-5, -4, -3, 0, 2, 3],
        ] {
            assert_eq!(parse_frames(&frame_spec(&frames)).unwrap(), frames);
        }
    }

    #[test]
    fn malformed_lists_explain_the_syntax() {
        for bad in [
            "",
            "a",
            "1-",
            "5-1",
            "1-4x0",
            "1-4x",
            "1..4",
            "4x2",
            "0-9999999999",
        ] {
            let e = parse_frames(bad).unwrap_err();
            assert!(e.contains(bad) || bad.is_empty(), "{bad}: {e}");
        }
    }
}
