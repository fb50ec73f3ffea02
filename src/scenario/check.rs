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
        allowed: allowed.to_string(),
    })
}

/// A number written out in full (`1e308` displays as 309 digits) in exponent form; any other
/// text as it is.
pub fn short_number(text: String) -> String {
    match text.parse::<f64>() {
        Ok(x) if text.len() > 12 => format!("{x:e}"),
        _ => text,
    }
}

/// `value` is finite and > 0.
pub fn positive(key: &str, value: f64) -> Check {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        invalid(key, value, "a finite number > 0")
    }
}

/// `value` is finite and ≥ 0.
pub fn non_negative(key: &str, value: f64) -> Check {
    if value.is_finite() && value >= 0.0 {
        Ok(())
    } else {
        invalid(key, value, "a finite number >= 0")
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
    }
}
