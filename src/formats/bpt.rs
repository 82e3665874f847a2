//! The `.bpt` Bezier patch text format.
//!
//! ```text
//! 2            the number of patches
//! 3 3          patch 0: degree in u, degree in v
//! 1.4 0 2.4    (degree_u + 1)(degree_v + 1) control points "x y z", one per line:
//! ...          degree_v + 1 runs (along v) of degree_u + 1 points (along u)
//! 1 1          patch 1 ...
//! ```
//!
//! Blank lines are skipped. Patches are named by their 0-based index ("0", "1", …). With this
//! reading of the point order, `Su × Sv` points out of the Utah teapot.

use glam::DVec3;

use super::FormatError;
use crate::geom::knots::MAX_DEGREE;
use crate::geom::{shapes, GeomError, NamedPatch, PatchLibrary};

/// Reads a `.bpt` text; `path` is used in error messages only.
pub fn parse_bpt(text: &str, path: &str) -> Result<PatchLibrary, FormatError> {
    let mut lines = Lines::new(text, path);
    let (line, header) = lines.next_record("the patch count")?;
    let count: usize = parse_fields::<1, usize>(&header, path, line, "the patch count")?[0];
    let mut patches = Vec::new();
    for index in 0..count {
        let what = format!("the degrees of patch {index}");
        let (line, fields) = lines.next_record(&what)?;
        let [degree_u, degree_v] = parse_fields::<2, usize>(&fields, path, line, &what)?;
        if let Some(degree) = [degree_u, degree_v]
            .into_iter()
            .find(|d| !(1..=MAX_DEGREE).contains(d))
        {
            return Err(FormatError::Bpt {
                path: path.into(),
                line,
                message: format!("patch {index}: {}", GeomError::Degree { degree }),
            });
        }
        let mut points = Vec::with_capacity((degree_u + 1) * (degree_v + 1));
        for k in 0..(degree_u + 1) * (degree_v + 1) {
            let what = format!("control point {k} of patch {index} (x y z)");
            let (line, fields) = lines.next_record(&what)?;
            let [x, y, z] = parse_fields::<3, f64>(&fields, path, line, &what)?;
            points.push(DVec3::new(x, y, z));
        }
        // Each run of degree_u + 1 points runs along u; the runs follow each other along v.
        let rows: Vec<Vec<DVec3>> = (0..=degree_u)
            .map(|i| {
                (0..=degree_v)
                    .map(|j| points[j * (degree_u + 1) + i])
                    .collect()
            })
            .collect();
        let surface = shapes::bezier(degree_u, degree_v, &rows).map_err(|e| FormatError::Bpt {
            path: path.into(),
            line,
            message: format!("patch {index}: {e}"),
        })?;
        patches.push(NamedPatch {
            name: index.to_string(),
            trim: None,
            surface,
        });
    }
    if let Some((line, _)) = lines.next_nonblank() {
        return Err(FormatError::Bpt {
            path: path.into(),
            line,
            message: format!("unexpected data after the {count} patches the first line announces"),
        });
    }
    Ok(PatchLibrary::new(patches))
}

/// Non-blank lines with their 1-based numbers.
struct Lines<'a> {
    inner: std::iter::Enumerate<std::str::Lines<'a>>,
    path: &'a str,
    last_line: usize,
}

impl<'a> Lines<'a> {
    fn new(text: &'a str, path: &'a str) -> Self {
        Self {
            inner: text.lines().enumerate(),
            path,
            last_line: 0,
        }
    }

    fn next_nonblank(&mut self) -> Option<(usize, Vec<&'a str>)> {
        for (i, line) in self.inner.by_ref() {
            self.last_line = i + 1;
            let fields: Vec<&str> = line.split_whitespace().collect();
            if !fields.is_empty() {
                return Some((i + 1, fields));
            }
        }
        None
    }

    /// The next non-blank line, or an error saying the file ended where `what` was expected.
    fn next_record(&mut self, what: &str) -> Result<(usize, Vec<&'a str>), FormatError> {
        self.next_nonblank().ok_or_else(|| FormatError::Bpt {
            path: self.path.into(),
            line: self.last_line.max(1),
            message: format!("the file ends where {what} should follow"),
        })
    }
}

fn parse_fields<const N: usize, T: std::str::FromStr>(
    fields: &[&str],
    path: &str,
    line: usize,
    what: &str,
) -> Result<[T; N], FormatError> {
    let error = |message: String| FormatError::Bpt {
        path: path.into(),
        line,
        message,
    };
    if fields.len() != N {
        return Err(error(format!(
            "expected {what}: {N} number(s), found {} field(s)",
            fields.len()
        )));
    }
    let mut values = Vec::with_capacity(N);
    for field in fields {
        let value = field
            .parse::<T>()
            .map_err(|_| error(format!("'{field}' is not a valid number in {what}")))?;
        values.push(value);
    }
    Ok(values
        .try_into()
        .unwrap_or_else(|_| unreachable!("length checked above")))
}

#[cfg(test)]
mod tests {
    use super::*;

    const TWO_PATCHES: &str =
        "2\n1 1\n0 0 0\n0 1 0\n1 0 0\n1 1 0\n\n1 2\n0 0 0\n1 0 0\n0 1 0\n1 1 1\n0 2 0\n1 2 2\n";

    #[test]
    fn reads_patches_with_their_degrees_and_index_names() {
        let lib = parse_bpt(TWO_PATCHES, "t.bpt").unwrap();
        assert_eq!(lib.patches.len(), 2);
        assert_eq!(lib.patches[1].name, "1");
        let s = &lib.patches[1].surface;
        assert_eq!((s.knots_u().degree(), s.knots_v().degree()), (1, 2));
        // Runs of degree_u + 1 = 2 points go along u, the three runs along v.
        // P_ij = (i, j, i j) here.
        assert!((s.point(1.0, 0.0) - DVec3::new(1.0, 0.0, 0.0)).length() < 1e-15);
        assert!((s.point(0.0, 1.0) - DVec3::new(0.0, 2.0, 0.0)).length() < 1e-15);
        assert!((s.point(1.0, 1.0) - DVec3::new(1.0, 2.0, 2.0)).length() < 1e-15);
    }

    fn error_of(text: &str) -> String {
        parse_bpt(text, "t.bpt").unwrap_err().to_string()
    }

    #[test]
    fn truncated_file_names_the_last_line_and_what_is_missing() {
        assert_eq!(
            error_of("1\n1 1\n0 0 0\n0 1 0\n"),
            "t.bpt:4: the file ends where control point 2 of patch 0 (x y z) should follow"
        );
        assert_eq!(
            error_of(""),
            "t.bpt:1: the file ends where the patch count should follow"
        );
    }

    #[test]
    fn non_numeric_and_short_lines_name_their_line() {
        assert_eq!(
            error_of("1\n1 1\n0 0 0\n0 x 0\n"),
            "t.bpt:4: 'x' is not a valid number in control point 1 of patch 0 (x y z)"
        );
        assert_eq!(
            error_of("1\n1 1\n0 0\n"),
            "t.bpt:3: expected control point 0 of patch 0 (x y z): 3 number(s), found 2 field(s)"
        );
        assert_eq!(
            error_of("1\n0 1\n"),
            "t.bpt:2: patch 0: degree 0 is not supported: use a degree from 1 to 9"
        );
        assert!(error_of("1\n1 1\n0 0 0\n0 1 0\n1 0 0\n1 1 0\n5\n")
            .starts_with("t.bpt:7: unexpected data"));
    }
}
