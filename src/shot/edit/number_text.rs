//! Numbers written as a shot file writes them: values with a `.0` on whole numbers, frames
//! without, vectors as `(x, y, z)`, each number as short as it can be.

/// `x` as the shortest decimal that reads back as the same `f32`, with `.0` on a whole number:
/// `0.25`, `1.0`, `-3.5`, `0.0000001`. What an edit writes, so that the file reads back exactly.
#[must_use]
pub fn number_text(x: f32) -> String {
    with_point(x.to_string())
}

/// `x` rounded to 6 significant digits, trailing zeros dropped, with `.0` on a whole number
/// (`0.0217391` for `0.021739129`, `1.0` for `0.99999994`); `-0` is written `0.0`. What a person
/// reads, and can paste into a file.
#[must_use]
pub fn rounded_number_text(x: f32) -> String {
    if !x.is_finite() {
        return x.to_string();
    }
    // `{:e}` with 5 decimals rounds to 6 significant digits; reading that back and writing it
    // with `{}` gives its shortest decimal, without the exponent.
    let rounded: f64 = format!("{:.5e}", f64::from(x))
        .parse()
        .unwrap_or(f64::from(x));
    with_point((rounded + 0.0).to_string())
}

/// `x` rounded to `places` decimal places, trailing zeros dropped, with `.0` on a whole number
/// (`0.1235` for `0.12345678` to 4 places, `0.5` for `0.50001`, `2.0` for `1.99999`); `-0` is
/// written `0.0`. What a drawn coordinate is written as: short, and read by people.
#[must_use]
pub fn decimal_text(x: f32, places: usize) -> String {
    if !x.is_finite() {
        return x.to_string();
    }
    let fixed = format!("{:.places$}", f64::from(x));
    let trimmed = if fixed.contains('.') {
        fixed.trim_end_matches('0').trim_end_matches('.')
    } else {
        &fixed
    };
    let written = if trimmed.trim_start_matches('-') == "0" {
        "0"
    } else {
        trimmed
    };
    with_point(written.to_string())
}

/// A key's frame as the shortest decimal that reads back as the same `f64`, without `.0` on a
/// whole frame: `17`, `10.5`, `-2`.
#[must_use]
pub fn frame_text(frame: f64) -> String {
    (frame + 0.0).to_string()
}

/// A value of `components` written with `number`: one number alone, several as a tuple
/// `(x, y, z)`.
#[must_use]
pub fn value_text(components: &[f32], number: fn(f32) -> String) -> String {
    match components {
        [one] => number(*one),
        many => {
            let written: Vec<String> = many.iter().map(|&c| number(c)).collect();
            format!("({})", written.join(", "))
        }
    }
}

/// `.0` appended to a decimal written without a point or an exponent.
fn with_point(mut text: String) -> String {
    let whole = text.bytes().all(|b| b.is_ascii_digit() || b == b'-');
    if whole {
        text.push_str(".0");
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_numbers_read_back_as_the_same_f32() {
        assert_eq!(number_text(0.25), "0.25");
        assert_eq!(number_text(1.0), "1.0");
        assert_eq!(number_text(-3.0), "-3.0");
        assert_eq!(number_text(0.1), "0.1");
        assert_eq!(number_text(1e-7), "0.0000001");
        for x in [0.021739129_f32, 1.0 / 3.0, -7.123457e-5, 3.4e38, 1.17e-38] {
            let text = number_text(x);
            assert_eq!(text.parse::<f64>().unwrap() as f32, x, "{text}");
        }
    }

    #[test]
    fn rounded_numbers_keep_six_significant_digits() {
        assert_eq!(rounded_number_text(0.021739129), "0.0217391");
        assert_eq!(rounded_number_text(0.99999994), "1.0");
        assert_eq!(rounded_number_text(-0.0), "0.0");
        assert_eq!(rounded_number_text(123456.78), "123457.0");
        assert_eq!(rounded_number_text(-2.5), "-2.5");
        assert_eq!(rounded_number_text(30.5), "30.5");
    }

    #[test]
    fn decimals_are_rounded_to_their_places_without_trailing_zeros() {
        assert_eq!(decimal_text(0.123_456_78, 4), "0.1235");
        assert_eq!(decimal_text(0.500_01, 4), "0.5");
        assert_eq!(decimal_text(1.999_99, 4), "2.0");
        assert_eq!(decimal_text(-0.000_01, 4), "0.0");
        assert_eq!(decimal_text(-0.25, 4), "-0.25");
        assert_eq!(decimal_text(3.0, 0), "3.0");
    }

    #[test]
    fn frames_are_whole_without_a_point_and_vectors_are_tuples() {
        assert_eq!(frame_text(17.0), "17");
        assert_eq!(frame_text(10.5), "10.5");
        assert_eq!(frame_text(-0.0), "0");
        assert_eq!(value_text(&[0.5], number_text), "0.5");
        assert_eq!(
            value_text(&[1.0, 0.98, 0.9], number_text),
            "(1.0, 0.98, 0.9)"
        );
    }
}
