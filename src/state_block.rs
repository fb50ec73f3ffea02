//! Typed state blocks in the simulation's one flat state vector.
//!
//! RK4 integrates every stage's continuous state as one `Vec<f64>`. Each stage owns a
//! contiguous slice of it and reads and writes that slice only through its own typed block (a
//! struct with `unpack` and `pack`), written with [`StateReader`] and [`StateWriter`]: the
//! order of a block's fields in those two functions is its layout, so adding a state touches
//! one place. The derivative of a block is the same struct holding rates, packed the same way.

use crate::frames::Vec3;

/// Reads consecutive values of a state slice.
#[derive(Debug)]
pub struct StateReader<'a> {
    x: &'a [f64],
    at: usize,
}

impl<'a> StateReader<'a> {
    /// A reader at the start of `x`.
    pub fn new(x: &'a [f64]) -> Self {
        Self { x, at: 0 }
    }

    /// The next value.
    pub fn scalar(&mut self) -> f64 {
        let value = self.x[self.at];
        self.at += 1;
        value
    }

    /// The next three values.
    pub fn vec3(&mut self) -> Vec3 {
        Vec3::from(self.array::<3>())
    }

    /// The next `N` values.
    pub fn array<const N: usize>(&mut self) -> [f64; N] {
        let mut out = [0.0; N];
        out.copy_from_slice(&self.x[self.at..self.at + N]);
        self.at += N;
        out
    }

    /// The next three values when `present`.
    pub fn optional_vec3(&mut self, present: bool) -> Option<Vec3> {
        present.then(|| self.vec3())
    }

    /// The next `n` values, borrowed.
    pub fn slice(&mut self, n: usize) -> &'a [f64] {
        let out = &self.x[self.at..self.at + n];
        self.at += n;
        out
    }

    /// How many values have been read.
    pub fn position(&self) -> usize {
        self.at
    }
}

/// Writes consecutive values into a state slice.
#[derive(Debug)]
pub struct StateWriter<'a> {
    x: &'a mut [f64],
    at: usize,
}

impl<'a> StateWriter<'a> {
    /// A writer at the start of `x`.
    pub fn new(x: &'a mut [f64]) -> Self {
        Self { x, at: 0 }
    }

    /// Writes one value.
    pub fn scalar(&mut self, value: f64) -> &mut Self {
        self.x[self.at] = value;
        self.at += 1;
        self
    }

    /// Writes three values.
    pub fn vec3(&mut self, value: &Vec3) -> &mut Self {
        self.values(value.as_slice())
    }

    /// Writes three values when there are some.
    pub fn optional_vec3(&mut self, value: &Option<Vec3>) -> &mut Self {
        if let Some(v) = value {
            self.vec3(v);
        }
        self
    }

    /// Writes a run of values.
    pub fn values(&mut self, values: &[f64]) -> &mut Self {
        self.x[self.at..self.at + values.len()].copy_from_slice(values);
        self.at += values.len();
        self
    }

    /// How many values have been written.
    pub fn position(&self) -> usize {
        self.at
    }
}

/// The components of a vector in NED axes, for [`element_names`].
pub const NED: &[&str] = &["n", "e", "d"];
/// The components of a vector along x, y, z, for [`element_names`].
pub const XYZ: &[&str] = &["x", "y", "z"];

/// The names of a state slice's elements (for messages): each group is a quantity and its
/// components (none for a scalar), in the slice's order; every name starts with `prefix`.
pub fn element_names(prefix: &str, groups: &[(&str, &[&str])]) -> Vec<String> {
    let mut names = Vec::new();
    for (quantity, parts) in groups {
        if parts.is_empty() {
            names.push(format!("{prefix}: {quantity}"));
        }
        names.extend(parts.iter().map(|p| format!("{prefix}: {quantity} ({p})")));
    }
    names
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What a writer packs, a reader unpacks in the same order.
    #[test]
    fn round_trip() {
        let mut x = [0.0; 9];
        StateWriter::new(&mut x)
            .scalar(1.0)
            .vec3(&Vec3::new(2.0, 3.0, 4.0))
            .optional_vec3(&None)
            .values(&[5.0, 6.0])
            .optional_vec3(&Some(Vec3::new(7.0, 8.0, 9.0)));
        let mut r = StateReader::new(&x);
        assert_eq!(r.scalar(), 1.0);
        assert_eq!(r.vec3(), Vec3::new(2.0, 3.0, 4.0));
        assert_eq!(r.optional_vec3(false), None);
        assert_eq!(r.array::<2>(), [5.0, 6.0]);
        assert_eq!(r.optional_vec3(true), Some(Vec3::new(7.0, 8.0, 9.0)));
        assert_eq!(r.position(), 9);
    }
}
