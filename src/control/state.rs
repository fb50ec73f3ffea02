//! The controller's continuous state: its layout in the simulation's state vector
//! ([`AutopilotState`], `[V_I, V_m | φ_I, φ_m, φ̇_m | θ_I, θ_m, θ̇_m | ψ_I, ψ_m, ψ̇_m |
//! p_f, ṗ_f, q_f, q̇_f, r_f, ṙ_f | ŵ (3) | I_E, I_B, ḣ_f | Ŵ_D, Ŵ_l, Ŵ_m, Ŵ_n]`, the weights RBF_CENTRES each)
//! and the names of its elements.

use super::rbf::RBF_CENTRES;
use crate::frames::Vec3;
use crate::state_block::{StateReader, StateWriter};

/// Length of the controller's state.
pub const AUTOPILOT_STATE_LEN: usize = 23 + 4 * RBF_CENTRES;

/// Index of each network among the weights: drag, roll, pitch, yaw moment.
pub(super) const DRAG: usize = 0;
pub(super) const ROLL: usize = 1;
pub(super) const PITCH: usize = 2;
pub(super) const YAW: usize = 3;

/// The controller's continuous state ([`AUTOPILOT_STATE_LEN`] values, in this order);
/// holding rates, its derivative.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AutopilotState {
    /// `[V_I, V_m]`: the airspeed prefilter (7.33).
    pub airspeed_filter: [f64; 2],
    /// `[φ_I, φ_m, φ̇_m]`: the roll prefilter.
    pub roll_filter: [f64; 3],
    /// `[θ_I, θ_m, θ̇_m]`: the pitch prefilter.
    pub pitch_filter: [f64; 3],
    /// `[ψ_I, ψ_m, ψ̇_m]`: the heading prefilter (ψ_m continuous, not wrapped).
    pub heading_filter: [f64; 3],
    /// `[ω_f, ω̇_f]` for p, q and r: the rate command filter.
    pub rate_filter: [[f64; 2]; 3],
    /// ŵ: the wind estimate, NED, ft/s.
    pub wind_estimate_ned_fps: Vec3,
    /// `[I_E, I_B, ḣ_f]`: the energy loop's integrals of the total energy rate error and of
    /// the balance rate error, ft/s², and its shaped climb-rate demand, ft/s (zero, and
    /// still, with the Chapter 7 outer loop).
    pub energy_loop: [f64; 3],
    /// The RBF weights Ŵ_D, Ŵ_l, Ŵ_m, Ŵ_n.
    pub weights: [[f64; RBF_CENTRES]; 4],
}

impl AutopilotState {
    /// Everything zero.
    pub fn zero() -> Self {
        Self {
            airspeed_filter: [0.0; 2],
            roll_filter: [0.0; 3],
            pitch_filter: [0.0; 3],
            heading_filter: [0.0; 3],
            rate_filter: [[0.0; 2]; 3],
            wind_estimate_ned_fps: Vec3::zeros(),
            energy_loop: [0.0; 3],
            weights: [[0.0; RBF_CENTRES]; 4],
        }
    }

    /// The typed state of a state slice.
    pub fn unpack(x: &[f64]) -> Self {
        let mut r = StateReader::new(x);
        Self {
            airspeed_filter: r.array(),
            roll_filter: r.array(),
            pitch_filter: r.array(),
            heading_filter: r.array(),
            rate_filter: [(); 3].map(|_| r.array()),
            wind_estimate_ned_fps: r.vec3(),
            energy_loop: r.array(),
            weights: [(); 4].map(|_| r.array()),
        }
    }

    /// Writes the block into its state slice.
    pub fn pack(&self, x: &mut [f64]) {
        let mut w = StateWriter::new(x);
        w.values(&self.airspeed_filter)
            .values(&self.roll_filter)
            .values(&self.pitch_filter)
            .values(&self.heading_filter);
        for axis in &self.rate_filter {
            w.values(axis);
        }
        w.vec3(&self.wind_estimate_ned_fps)
            .values(&self.energy_loop);
        for network in &self.weights {
            w.values(network);
        }
    }

    /// Ŵ_D.
    pub fn drag_weights(&self) -> &[f64; RBF_CENTRES] {
        &self.weights[DRAG]
    }

    /// Ŵ_l, Ŵ_m, Ŵ_n (in that order).
    pub fn moment_weights(&self) -> [&[f64; RBF_CENTRES]; 3] {
        [
            &self.weights[ROLL],
            &self.weights[PITCH],
            &self.weights[YAW],
        ]
    }
}

/// The names of the controller's state elements, in [`AutopilotState`]'s order (for
/// messages): "autopilot: RBF weight 3 of the pitch channel".
pub fn autopilot_state_names() -> Vec<String> {
    use crate::state_block::{NED, element_names};
    let filter = ["filtered command", "its rate"];
    let mut names = element_names(
        "autopilot",
        &[
            ("airspeed prefilter", &["integral", "V_m"]),
            ("roll prefilter", &["integral", "φ_m", "φ̇_m"]),
            ("pitch prefilter", &["integral", "θ_m", "θ̇_m"]),
            ("heading prefilter", &["integral", "ψ_m", "ψ̇_m"]),
            ("p command filter", &filter),
            ("q command filter", &filter),
            ("r command filter", &filter),
            ("wind estimate, ft/s", NED),
            (
                "energy loop",
                &[
                    "total energy integral, ft/s²",
                    "balance integral, ft/s²",
                    "shaped climb rate, ft/s",
                ],
            ),
        ],
    );
    for channel in ["drag", "roll", "pitch", "yaw"] {
        names.extend(
            (0..RBF_CENTRES).map(|k| format!("autopilot: RBF weight {k} of the {channel} channel")),
        );
    }
    names
}
