//! `[excitation]`: the intelligent excitation R*_c = R_c + a(t) sin(ωt) E (4.31) and the
//! frame its direction is read in (`guidance::excitation`).

use super::CommandFrame;
use super::check::{self, Check};
use serde::{Deserialize, Serialize};

/// How the excitation amplitude a(t) is computed (4.31).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ExcitationMode {
    /// No excitation.
    Off,
    /// a(t) from the integral of eᵀe over the sliding window [t - T, t] (as the seed simulates).
    Continuous,
    /// a(t) from the integral over the last whole period, held through the next ((2.28), (5.27)).
    PerPeriod,
    /// a(t) = min(k_sigma σ_b(t), k1 - k3) + k3 from the Kalman estimator's uncertainty of b
    /// (docs/equations.md, Range and size from the follower's own motion): large while b is
    /// unknown, fading once known (needs `estimator.kind = "kalman"` or
    /// `estimator.log_kalman`).
    Uncertainty,
    /// a(t) = min(k_sigma σ_b(t) / b̂(t), k1 - k3) + k3: as `uncertainty`, from the relative
    /// uncertainty of b. The swing that reads b to a given relative precision depends on the
    /// range and the bearing noise, not on b, so with `units = "ft"` a target of any size is
    /// swung by the same feet at the same relative uncertainty, where `uncertainty` swings it
    /// in proportion to b̂ (ft) or b̂² (scaled) (docs/equations.md, Range and size from the
    /// follower's own motion).
    RelativeUncertainty,
}

impl ExcitationMode {
    /// Whether the amplitude follows the Kalman filter's σ_b.
    pub fn follows_the_filter(self) -> bool {
        matches!(self, Self::Uncertainty | Self::RelativeUncertainty)
    }
}

/// Units of the excitation amplitude a (and of k1, k3).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ExcitationUnits {
    /// Feet: R*_c = R_c + a sin(ωt) E as (4.31) writes it; enters r̂_c divided by b̂.
    Ft,
    /// Multiples of the target's size: r*_c = r_c + a sin(ωt) E on the scaled command the
    /// seed's Chapter 4 simulations feed back (a = 0.5 is 4 ft for the 8 ft target).
    Scaled,
}

/// Which tracking error's energy sets the excitation amplitude.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ExcitationError {
    /// The measured error: e = r* - r_c (velocity law, (4.31)), the combined output
    /// y*_a = 2y* - y_m - C ẑ (acceleration law, (5.27)).
    Measured,
    /// The law's estimate of it from its filtered states: r̂ - r_c (velocity law with the
    /// estimator (6.10)), C (ẑ - z_m) (acceleration law). With noisy measurements the
    /// measured error never falls below the noise, and the amplitude never decays.
    Estimated,
}

/// The frame the excitation's direction E is read in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ExcitationFrame {
    /// NED, fixed (the seed's: its target flies one heading).
    Inertial,
    /// The target's estimated velocity frame the command is read in (`guidance.command_frame
    /// = "target"`): x along the target's track, y to its right, z down. E turns with the
    /// frame, so a swing across the track stays across it through the target's turns, where
    /// a fixed E = [0, 1, 0] swings the follower along the track of a target flying east.
    Target,
}

/// `[excitation]`: intelligent excitation R*_c = R_c + a(t) sin(ωt) E, (4.31).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ExcitationSection {
    /// Amplitude law.
    pub mode: ExcitationMode,
    /// Units of a, k1 and k3.
    pub units: ExcitationUnits,
    /// Period T = 2π/ω, s.
    pub period_s: f64,
    /// k1: amplitude during the first period and its cap.
    pub k1: f64,
    /// k2: gain on the windowed squared scaled error ∫ eᵀe, per s.
    pub k2: f64,
    /// k3: floor of the amplitude.
    pub k3: f64,
    /// Direction E in the excitation's frame (normalised on use).
    pub direction: [f64; 3],
    /// The frame E is read in: `inertial` (NED) or `target` (the command's frame, with
    /// `guidance.command_frame = "target"`).
    pub frame: ExcitationFrame,
    /// When the excitation starts, s: before it the command carries none; after a start
    /// later than 0 (the default, the seed's) it fades in over one period.
    pub start_s: f64,
    /// When it ends, s (`inf`, the default: never): it fades out over the period before, so a
    /// follower that swings to learn the size can hold its slot once the time for it is over.
    pub end_s: f64,
    /// The error whose energy ∫ eᵀe the amplitude follows.
    pub error: ExcitationError,
    /// `mode = "uncertainty"`: amplitude per ft of the estimator's σ_b, in the excitation's
    /// units per ft.
    pub k_sigma: f64,
    /// With a camera, the amplitude is also bounded in feet and degrees by the field of view
    /// (`guidance::excitation::ViewBound`): at the commanded range L the bearing swing plus
    /// the half angle the target subtends at its estimated size b̂, atan(b̂ / 2L), stays
    /// within this fraction of the half field of view along the excitation's direction, so a
    /// large target is swung less (in scaled units the bound is divided by b̂); 0 (default)
    /// turns the bound off.
    pub fov_fraction: f64,
}

impl Default for ExcitationSection {
    fn default() -> Self {
        Self {
            mode: ExcitationMode::Continuous,
            units: ExcitationUnits::Scaled,
            period_s: 3.0,
            k1: 0.5,
            k2: 100.0,
            k3: 0.0002,
            direction: [1.0, 0.0, 0.0],
            frame: ExcitationFrame::Inertial,
            start_s: 0.0,
            end_s: f64::INFINITY,
            error: ExcitationError::Measured,
            k_sigma: 4.0,
            fov_fraction: 0.0,
        }
    }
}

impl ExcitationSection {
    /// Checks the section's values; E in the target frame needs the command read there.
    pub(super) fn validate(&self, command_frame: CommandFrame) -> Check {
        check::positive("excitation.period_s", self.period_s)?;
        check::non_negative("excitation.k1", self.k1)?;
        check::non_negative("excitation.k2", self.k2)?;
        check::in_closed("excitation.k3", self.k3, 0.0, self.k1.max(0.0))?;
        check::in_closed("excitation.k_sigma", self.k_sigma, 0.0, 1e4)?;
        check::in_closed("excitation.fov_fraction", self.fov_fraction, 0.0, 1.0)?;
        check::nonzero_vec("excitation.direction", &self.direction)?;
        check::in_closed("excitation.start_s", self.start_s, 0.0, 1e9)?;
        check::require(
            self.end_s >= self.start_s + 2.0 * self.period_s,
            "excitation.end_s",
            self.end_s,
            "at least excitation.start_s plus two periods (a fade in and a fade out)",
        )?;
        check::require(
            self.frame == ExcitationFrame::Inertial || command_frame == CommandFrame::Target,
            "excitation.frame",
            "\"target\"",
            "\"inertial\" unless guidance.command_frame = \"target\"",
        )
    }
}
