//! Where each stage's slice lies in the simulation's one state vector:
//! `[follower | gimbal | command frame | guidance law]`.

use std::ops::Range;

/// The slice lengths, laid out one after the other.
#[derive(Debug, Clone, PartialEq)]
pub struct StateLayout {
    follower: Range<usize>,
    gimbal: Range<usize>,
    command: Range<usize>,
    guidance: Range<usize>,
}

/// The stages' slices of one state (or derivative).
#[derive(Debug)]
pub struct Slices<T> {
    /// The follower's plant, controller and integrators.
    pub follower: T,
    /// The camera gimbal's angles (empty without one).
    pub gimbal: T,
    /// The command frame's state.
    pub command: T,
    /// The guidance law's state.
    pub guidance: T,
}

impl StateLayout {
    /// Slices of the given lengths, in the order above.
    pub fn new(follower: usize, gimbal: usize, command: usize, guidance: usize) -> Self {
        let gimbal_at = follower;
        let command_at = gimbal_at + gimbal;
        let guidance_at = command_at + command;
        Self {
            follower: 0..gimbal_at,
            gimbal: gimbal_at..command_at,
            command: command_at..guidance_at,
            guidance: guidance_at..guidance_at + guidance,
        }
    }

    /// The slices of a state.
    pub fn split<'a>(&self, x: &'a [f64]) -> Slices<&'a [f64]> {
        Slices {
            follower: &x[self.follower.clone()],
            gimbal: &x[self.gimbal.clone()],
            command: &x[self.command.clone()],
            guidance: &x[self.guidance.clone()],
        }
    }

    /// What element `i` of the state is, from each stage's names for its slice (a stage
    /// that names fewer elements than it has gives "stage, element k").
    pub fn describe(&self, i: usize, names: &Slices<Vec<String>>) -> String {
        let stages = [
            ("follower", &self.follower, &names.follower),
            ("gimbal", &self.gimbal, &names.gimbal),
            ("command frame", &self.command, &names.command),
            ("guidance", &self.guidance, &names.guidance),
        ];
        for (stage, range, names) in stages {
            if range.contains(&i) {
                let k = i - range.start;
                return names
                    .get(k)
                    .cloned()
                    .unwrap_or_else(|| format!("{stage}, element {k}"));
            }
        }
        format!("state element {i}")
    }

    /// The slices of a state, mutable.
    pub fn split_mut<'a>(&self, x: &'a mut [f64]) -> Slices<&'a mut [f64]> {
        let (rest, guidance) = x.split_at_mut(self.guidance.start);
        let (rest, command) = rest.split_at_mut(self.command.start);
        let (follower, gimbal) = rest.split_at_mut(self.gimbal.start);
        Slices {
            follower,
            gimbal,
            command,
            guidance: &mut guidance[..self.guidance.len()],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slices_follow_each_other() {
        let layout = StateLayout::new(3, 2, 1, 4);
        let x: Vec<f64> = (0..10).map(f64::from).collect();
        let s = layout.split(&x);
        assert_eq!(
            (s.follower, s.gimbal, s.command, s.guidance),
            (&x[0..3], &x[3..5], &x[5..6], &x[6..10])
        );
        let mut y = x.clone();
        layout.split_mut(&mut y).gimbal[1] = -1.0;
        assert_eq!(y[4], -1.0);
    }

    #[test]
    fn elements_are_named_by_their_stage() {
        let layout = StateLayout::new(2, 0, 1, 2);
        let names = Slices {
            follower: vec!["aircraft: x".to_string(), "autopilot: y".to_string()],
            gimbal: vec![],
            command: vec!["command frame: heading".to_string()],
            guidance: vec!["guidance: b̂".to_string()],
        };
        assert_eq!(layout.describe(1, &names), "autopilot: y");
        assert_eq!(layout.describe(3, &names), "guidance: b̂");
        assert_eq!(layout.describe(4, &names), "guidance, element 1");
    }
}
