//! Validation helpers: every failed check names the key, the value and the allowed range.

use std::fmt::Display;

/// One failed check: which key, what it held and what it may hold.
#[derive(Debug, Clone, PartialEq)]
pub struct InvalidValue {
    /// Dotted key, e.g. `guidance.b0_ft`.
    pub key: String,
    /// The offending value as written.
    pub value: String,
    /// What the key allows, e.g. `(0, 1]` or `one of "perfect", "camera"`.
    pub allowed: String,
}

impl Display for InvalidValue {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} = {} is invalid: allowed {}",
            self.key, self.value, self.allowed
        )
    }
}

/// A parser's message on one line (TOML errors span several, with a source excerpt).
pub fn one_line(message: &impl Display) -> String {
    message.to_string().trim_end().replace('\n', " ")
}

/// Result of a check.
pub type Check = Result<(), InvalidValue>;

fn invalid(key: &str, value: impl Display, allowed: impl Display) -> Check {
    Err(InvalidValue {
        key: key.to_string(),
        value: short_number(value.to_string()),
        allowed: short_numbers_in(&allowed.to_string()),
    })
}

/// Every number written out in full inside `text` (a bound printed from a tiny float runs to
/// 50 digits) in exponent form; the words around them as they are.
pub fn short_numbers_in(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut number = String::new();
    let mut after_word = false;
    for c in text.chars() {
        let continues = !number.is_empty() && (c.is_ascii_digit() || c == '.');
        if continues || (c.is_ascii_digit() && !after_word) {
            number.push(c);
            continue;
        }
        out.push_str(&short_number(std::mem::take(&mut number)));
        out.push(c);
        after_word = c.is_alphanumeric() || c == '_';
    }
    out.push_str(&short_number(number));
    out
}

/// A number written out in full (`1e308` displays as 309 digits) in exponent form where that
/// is shorter; any other text as it is.
pub fn short_number(text: String) -> String {
    match text.parse::<f64>() {
        Ok(x) if text.len() > 12 && format!("{x:e}").len() < text.len() => format!("{x:e}"),
        _ => text,
    }
}

/// Smallest gain, weight, spectral density or length a key that must be > 0 may take: below
/// it a value (5e-324, say) is no design but a number that overflows the first division.
pub const MIN_POSITIVE: f64 = 1e-9;
/// Largest such value, and largest a key that must be >= 0 may take.
pub const MAX_MAGNITUDE: f64 = 1e9;
/// Largest position component, ft (the run stops as diverged beyond a range of 1e6 ft).
pub const MAX_POSITION_FT: f64 = 1e6;

/// `value` is > 0, within [[`MIN_POSITIVE`], [`MAX_MAGNITUDE`]].
pub fn positive(key: &str, value: f64) -> Check {
    if (MIN_POSITIVE..=MAX_MAGNITUDE).contains(&value) {
        Ok(())
    } else {
        invalid(
            key,
            value,
            format!("> 0: [{MIN_POSITIVE:e}, {MAX_MAGNITUDE:e}]"),
        )
    }
}

/// `value` is >= 0, within [0, [`MAX_MAGNITUDE`]].
pub fn non_negative(key: &str, value: f64) -> Check {
    if (0.0..=MAX_MAGNITUDE).contains(&value) {
        Ok(())
    } else {
        invalid(key, value, format!(">= 0: [0, {MAX_MAGNITUDE:e}]"))
    }
}

/// A position, ft: three numbers within ±[`MAX_POSITION_FT`].
pub fn position_ft(key: &str, value: &[f64; 3]) -> Check {
    if value.iter().all(|x| x.abs() <= MAX_POSITION_FT) {
        Ok(())
    } else {
        let shown: Vec<String> = value.iter().map(|x| short_number(x.to_string())).collect();
        invalid(
            key,
            format!("[{}]", shown.join(", ")),
            format!("three numbers in [-{MAX_POSITION_FT:e}, {MAX_POSITION_FT:e}] ft"),
        )
    }
}

/// `value` is finite and in the closed interval [lo, hi].
pub fn in_closed(key: &str, value: f64, lo: f64, hi: f64) -> Check {
    if value.is_finite() && value >= lo && value <= hi {
        Ok(())
    } else {
        invalid(key, value, format!("[{lo}, {hi}]"))
    }
}

/// `value` is finite and in the open interval (lo, hi); `bounds` names the limits for the
/// message (e.g. `"(guidance.b_min_ft = 1, guidance.b_max_ft = 30)"`).
pub fn in_open(key: &str, value: f64, lo: f64, hi: f64, bounds: &str) -> Check {
    if value.is_finite() && value > lo && value < hi {
        Ok(())
    } else {
        invalid(key, value, bounds)
    }
}

/// An integer in [lo, hi].
pub fn int_in(key: &str, value: i64, lo: i64, hi: i64) -> Check {
    if (lo..=hi).contains(&value) {
        Ok(())
    } else {
        invalid(key, value, format!("an integer in [{lo}, {hi}]"))
    }
}

/// Every component finite.
pub fn finite_vec(key: &str, value: &[f64; 3]) -> Check {
    if value.iter().all(|x| x.is_finite()) {
        Ok(())
    } else {
        invalid(key, format!("{value:?}"), "three finite numbers")
    }
}

/// A vector of nonzero length.
pub fn nonzero_vec(key: &str, value: &[f64; 3]) -> Check {
    finite_vec(key, value)?;
    if value.iter().any(|x| *x != 0.0) {
        Ok(())
    } else {
        invalid(key, format!("{value:?}"), "a nonzero vector")
    }
}

/// Fails with a free-form reason (for cross-key conditions).
pub fn require(ok: bool, key: &str, value: impl Display, allowed: impl Display) -> Check {
    if ok {
        Ok(())
    } else {
        invalid(key, value, allowed)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Huge and tiny numbers are printed in exponent form, ordinary ones as they are.
    #[test]
    fn numbers_are_printed_short() {
        let err = in_closed("run.duration_s", 1e308, 1e-3, 1e5).unwrap_err();
        assert_eq!(err.value, "1e308");
        let err = in_closed("k", 1e-320, 1.0, 2.0).unwrap_err();
        assert_eq!(err.value, "1e-320");
        assert_eq!(in_closed("k", 250.5, 0.0, 1.0).unwrap_err().value, "250.5");
        let tiny = format!("<= d = {} (x2)", 1e-30);
        assert_eq!(short_numbers_in(&tiny), "<= d = 1e-30 (x2)");
        assert_eq!(
            short_numbers_in("[0.00001, 0.1] in k3"),
            "[0.00001, 0.1] in k3"
        );
    }

    /// Gains at the edge of the floating-point range and positions no aircraft can have are
    /// refused with their range.
    #[test]
    fn meaningless_magnitudes_are_refused() {
        assert!(positive("k", 5e-324).is_err());
        assert!(positive("k", 1.8e-5).is_ok());
        assert!(non_negative("k", 1e300).is_err());
        let err = position_ft("p", &[1e308, 0.0, 0.0]).unwrap_err();
        assert_eq!(err.value, "[1e308, 0, 0]");
        assert_eq!(err.allowed, "three numbers in [-1e6, 1e6] ft");
    }
}
