//! `[estimator]`: what infers the target's range and size between sensing and guidance: the
//! seed's adaptive laws, which estimate b̂ and d̂ inside the guidance law, or the Kalman filter
//! (docs/equations.md, Range and size from the follower's own motion), which infers r, d, a
//! and 1/b from the measurements and the follower's own velocity and hands them to the law
//! (`estimation::kalman`).

use serde::{Deserialize, Serialize};

use super::check::{self, Check};

/// Which estimator feeds the guidance.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum EstimatorKind {
    /// The seed's adaptive laws (4.5), (5.20)-(5.41), (6.16): b̂ and d̂ adapt inside the law.
    Adaptive,
    /// The Kalman filter (`estimation::kalman`); the law flies on its estimates (certainty
    /// equivalence).
    Kalman,
}

/// What the size b the filter estimates is (seed 8.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SizeModel {
    /// The seed's: the silhouette's maximal length, taken as constant whatever the aspect.
    Apparent,
    /// The target's wing span, foreshortened by its attitude as inferred from the estimated
    /// velocity and acceleration (`estimation::aspect`): the frames' lengths are corrected
    /// for the aspect, and count for their bearing only where the span is seen too
    /// obliquely to be the silhouette's longest dimension.
    Span,
    /// The target's size (its largest dimension), its shape known up to scale from
    /// `camera.mesh`: each frame's length is divided by the normalised maximal length of that
    /// shape seen from the view the estimated velocity and acceleration imply
    /// (`estimation::airframe`), corrected for the vision's short reading, and weighted by
    /// how steeply that length changes with the view; its bearing is moved from the point the
    /// vision measures (`camera.bearing_point`) to the target's reference point by that
    /// shape's offset between them in the same view.
    Airframe,
}

/// Where the airframe size model's inferred attitude takes the target's angle of attack from
/// (`estimation::trim_alpha`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum AirframeAlpha {
    /// No angle of attack: the nose along the estimated velocity (a kinematic target's
    /// attitude).
    Zero,
    /// The trim α of the target's aircraft data (`target.aircraft`) at the estimated airspeed
    /// and load factor.
    Trim,
}

/// Where the estimator's own-motion displacement ΔR_F comes from (docs/equations.md, Range
/// and size from the follower's own motion). Both are the truth under perfect navigation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum OwnMotion {
    /// The difference of the navigation's positions (the INS/GPS solution, which follows the
    /// GPS's fixes: their noise and the steps of their slow error enter the displacement).
    Position,
    /// The displacement the INS integrates from its velocity alone: its error is the
    /// integral of the velocity error, smooth over seconds, which the filter's target-motion
    /// states absorb.
    Inertial,
}

/// Where the size's bounds [b_min, b_max] (`guidance.b_min_ft`, `b_max_ft`) act
/// (docs/equations.md, The size's bounds in the filter).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SizeBounds {
    /// The seed's: the law projects b̂ into them (its adaptive law's projection); the filter's
    /// β is free, and its other states follow the β it holds.
    Law,
    /// The filter's estimate too is projected onto β ∈ [1/b_max, 1/b_min] after every
    /// update, every state moved with β by its covariance with it, so that the velocity the law
    /// flies, b̂ d̂, is the one the measurements give for the bounded size.
    Filter,
}

/// Where the size the filter holds comes from (docs/equations.md, The size from the
/// excitation as an instrument).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SizeFrom {
    /// The seed's: the filter infers it from the follower's own motion against the image's,
    /// the tracked aircraft's motion taken as independent of the follower's.
    Filter,
    /// The follower's own excitation used as an instrument (`estimation::instrument`): once
    /// that reading's σ / b̂ is below `instrument_take_fraction`, the filter takes its size
    /// and σ at every frame, and until then the excitation follows that σ (the larger of it
    /// and the filter's). Needs the Kalman filter and an excitation at a period the tracked
    /// aircraft does not swing at.
    Excitation,
}

/// The direction along which the instrument reads the frames' increments (docs/equations.md,
/// The instrument's direction).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum InstrumentAxis {
    /// Along the excitation's direction E.
    Excitation,
    /// Along E less its component on the slot's line of sight R_c / |R_c|: the increments of
    /// r across the line of sight are the bearing's, which the centroid measures, and those
    /// along it the range's, which the size model's aspect error moves as the swing changes
    /// the view.
    AcrossSlot,
}

/// Whether the filter reads the target's turn from its bank (docs/equations.md, The target's
/// bank from its wing line).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TargetBank {
    /// The seed's: the camera's frames give the target's position alone; its acceleration is
    /// inferred from their sequence.
    Inferred,
    /// Each frame's maximal length, where it is the span, gives the target's bank and so its
    /// acceleration across its velocity in feet (g cos γ tan φ, coordinated flight), fused
    /// beside the frame's position (`estimation::bank`).
    Measured,
}

/// Where the Kalman filter maps a camera frame's pixel covariance through the Jacobian of
/// (3.3)-(3.12) (docs/equations.md, Noisy measurements).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CovarianceAt {
    /// At the frame's own pixels (the seed's mapping of pixel noise, the converted
    /// measurement's usual choice): a blob shorter than the target brings a σ along the line
    /// of sight widened by the square of its shortness, so a fragment of a distant target
    /// fuses as a target farther off.
    Measurement,
    /// At the pixels the filter predicts for the frame's capture, as an extended Kalman
    /// filter linearises: a fragment is weighed as the target it claims to be, and its
    /// normalised innovation grows with its shortness. Falls back to the measurement before
    /// the filter runs or while the prediction is behind the camera.
    Prediction,
}

/// `[estimator]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct EstimatorSection {
    /// Which estimator feeds the guidance (default the seed's).
    pub kind: EstimatorKind,
    /// With `kind = "adaptive"`: run the Kalman filter on the same measurements too and log
    /// its estimates beside the law's (`kf_*` columns), for comparison.
    pub log_kalman: bool,
    /// q_j, the intensity of the white jerk of a = a_T/b per axis, 1/s⁵. Choice: the seed
    /// target's acceleration changes by up to about 1 ft/s² within a second where its
    /// profile's pieces meet and by 0.3 ft/s³ inside them; (0.3 ft/s³ / 8 ft)² · 10 s ≈ 0.01.
    pub jerk_psd: f64,
    /// q_β, the intensity of the random walk of β = 1/b, 1/(ft² s). b is constant, but the
    /// size the camera measures is the silhouette's, which changes with the target's aspect
    /// (seed 8.2) by a few percent over tens of seconds: choice 1e-7 (σ_β grows by
    /// 1e-7^½ · √30 s ≈ 0.0017/ft, 1.4% of 1/8 ft, in 30 s without information).
    pub inverse_size_psd: f64,
    /// σ_g, the stationary σ per axis of the target's gust velocity about its path, ft/s
    /// (docs/equations.md, The target's gust velocity): 0 (default) leaves it out, as for the
    /// seed's kinematic target, which has none. An aircraft target in light turbulence
    /// wanders about its path by about 1-2 ft/s (measured in docs/findings.md, The realistic
    /// world).
    pub target_gust_sigma_fps: f64,
    /// τ_g, the gust velocity's correlation time, s: the time over which the target's
    /// response to a gust fades (its phugoid and its autopilot's speed hold; choice 2 s).
    pub target_gust_time_s: f64,
    /// T_L, the period of the tracked aircraft's swing across its track, s, when it is a
    /// teammate that excites its own motion at a known period (docs/equations.md, The
    /// leader's swing in its model): the filter explains the relative motion at 2π/T_L as the
    /// leader's, and hands on the leader's path (its velocity and position without the
    /// swing), which the law flies. 0 (default): no swing; otherwise at least 0.1 s. The
    /// follower's own excitation needs another period.
    pub leader_swing_period_s: f64,
    /// σ_s, the stationary σ per axis of the swing's velocity, ft/s. Choice: a teammate
    /// excited by ±2-3 ft at 3-5 s swings at about 3-4 ft/s across its track, 2.5 ft/s RMS.
    pub leader_swing_sigma_fps: f64,
    /// τ_s, the time over which the swing's amplitude and phase wander, s (at least T_L).
    /// Choice: 20 s, the time over which a teammate's excitation amplitude, following its own
    /// uncertainty, changes.
    pub leader_swing_time_s: f64,
    /// `law` (default, the seed's) or `filter`: whether the filter's estimate is kept within
    /// the size's bounds too (docs/equations.md, The size's bounds in the filter).
    pub size_bounds: SizeBounds,
    /// σ of the image measurements (yI, zI, bI), px, that the measurement covariance maps
    /// through the Jacobian of (3.3)-(3.12). Choice: the vision pipeline's centroid is within
    /// 0.2 px of the silhouette's, and the silhouette's centroid moves by a few pixels from
    /// the target's reference point with its attitude at close range; its maximal length
    /// reads short by 1-7% with range and aspect.
    pub pixel_sigma_px: [f64; 3],
    /// Factor on the measurement covariance (about 2 keeps b̂ from sitting low on the
    /// short-reading lengths; matched, b̂ sat 1-3% low in an independent study).
    pub measurement_inflation: f64,
    /// σ of r per axis (scaled units) below which a continuous sensor's measurement is not
    /// trusted (the `perfect` sensor has none of its own).
    pub scaled_sigma_floor: f64,
    /// σ of β(0) = 1/b̂(0), 1/ft (b̂(0) is `guidance.b0_ft`). Choice: 0.15 covers β from
    /// 0.1 to 0.4 (b from 2.5 to 10 ft) about b̂(0) = 4 ft within 1σ.
    pub initial_inverse_size_sigma_per_ft: f64,
    /// σ of the target's velocity relative to the follower's at the start, per axis, ft/s.
    pub initial_relative_velocity_sigma_fps: f64,
    /// σ of the target's acceleration at the start, per axis, ft/s² (seed: |a_T| ≤ 3.2).
    pub initial_acceleration_sigma_fps2: f64,
    /// b counts as known once σ_b / b̂ falls below this (reported as `b_known_time_s`; the
    /// target command frame follows the estimated target velocity from then on).
    pub known_sigma_fraction: f64,
    /// What b is: the apparent size (the seed's), the wing span seen through the aspect, or
    /// the airframe's size seen through its shape.
    pub size_model: SizeModel,
    /// With the span model, the smallest aspect factor s (the span's image length over its
    /// length across the optical axis) at which a frame's length is used. Choice: 0.8, the
    /// span seen up to 37° off the target's plane of symmetry: the fuselage, at most as long
    /// as the span on an aircraft, is then at most 0.6 of it in the image.
    pub span_aspect_min: f64,
    /// With the span model, the shortest the silhouette's maximal length can be at any view,
    /// as a fraction of the span (docs/equations.md, The length's bounds at any view). A
    /// frame counted for its bearing alone still bounds the range: R/b lies between this
    /// times r* and r*, and a prediction outside that interval is pulled to its nearer end, so
    /// a filter whose own view of the target is wrong cannot drift its range away from what
    /// the lengths allow. 0 (default): no bound, such frames measure the bearing only. The
    /// seed target's mesh (8 ft span, 6 ft long) reads 0.709 at its narrowest view.
    pub span_length_min_fraction: f64,
    /// `position` (default) or `inertial`: where the follower's own displacement comes from,
    /// for the filter and the measurement hold alike.
    pub own_motion: OwnMotion,
    /// With the airframe model, σ of the view direction the target's attitude is inferred
    /// from beyond the filter's own heading uncertainty (sideslip, angle of attack,
    /// turbulence), deg: with the slope of the normalised length it widens a frame's length
    /// variance. Choice: 5°, a light aircraft's angle of attack at formation speeds.
    pub airframe_view_sigma_deg: f64,
    /// With the airframe model, how much the measured maximal length reads short, px: each
    /// frame's length is taken as the measurement plus this. Calibrated from the silhouette
    /// truth (the telemetry's `b_i_true_px` - `b_i_px`) over formation.toml and its 4 ft,
    /// 2 ft, 320x240 and [80, 20, 0] ft slot variations, streams 1-2, 4 samples per pixel:
    /// 2.0-2.4 px at every length from 15 to 200 px (median 2.1, 70,000 frames), 3.2-3.7 px
    /// below 15 px. One sample per pixel reads short by 3.6 px at 100-140 px and 8-15 px
    /// below 70 px (a thin wing breaks up): no constant fits it.
    pub airframe_length_bias_px: f64,
    /// With the airframe model, σ of the corrected length, px, as [s₀, s₁]:
    /// σ(bI) = √(s₀² + (s₁ / bI)²). Calibrated as `airframe_length_bias_px`: 0.6-0.9 px above
    /// 20 px, 1.6-2.1 px below 15 px (frame to frame; the errors stay correlated over
    /// seconds, which `measurement_inflation` still covers).
    pub airframe_length_sigma_px: [f64; 2],
    /// With the airframe model, `zero` (default: the nose along the estimated velocity, as a
    /// kinematic target flies) or `trim` (pitched up by the trim α of `target.aircraft` at the
    /// estimated airspeed, ground velocity less `atmosphere.wind_ned_fps`, and load factor):
    /// the angle of attack of the attitude the view is inferred from. `trim` moves the
    /// inferred view of a kinematic target off its true one (formation.toml streams 1-5 in
    /// docs/findings.md, The airframe size model).
    pub airframe_angle_of_attack: AirframeAlpha,
    /// With the airframe model, σ of the relative error of the normalised length n (and of
    /// the corrected length) that averaging over frames does not remove, in [0, 1]: it
    /// changes with the geometry over tens of seconds, not from frame to frame (the table's
    /// orthographic views against the perspective drawing, the short reading's change with
    /// the aspect, the view inferred from the estimate), so b̂ is off by it whatever the
    /// number of frames, and σ_b is reported no smaller than b̂ times it. Choice: 0.025
    /// (docs/findings.md, The airframe size model: over the last 20 s of
    /// seed_ch7_velocity_camera.toml streams 1-5 n is predicted 0.9-1.0% low and the
    /// corrected length reads up to 1% long; inflating each frame's variance instead let b̂
    /// run 14-40% high).
    pub airframe_shape_sigma: f64,
    /// The Kalman filter's validation gate (docs/equations.md, The innovation gate): a frame
    /// whose normalised innovation νᵀ S⁻¹ ν exceeds it is not fused, as a measurement of
    /// something other than the target (0, the default: every frame is fused). νᵀ S⁻¹ ν is
    /// χ² with 3 degrees of freedom when the filter's model holds: 16.3 keeps out one
    /// frame in 1,000 of the target's own.
    pub innovation_gate: f64,
    /// The Kalman filter's gate on a frame's bearing alone (docs/equations.md, The bearing
    /// gate): a frame whose ray, where it meets the plane across the predicted line of sight
    /// at the predicted range, lies further from the prediction than this normalised square
    /// allows is not fused, whatever its length (0, the default: no such gate). The
    /// innovation gate takes a fragment of the target far off the prediction: its short
    /// length puts it far along its own ray, where its range is uncertain enough to explain
    /// the innovation. It is χ² with 2 degrees of freedom when the filter's model holds:
    /// 13.8 keeps out one frame in 1,000 of the target's own.
    pub bearing_gate: f64,
    /// The bearing gate weighs only a frame whose |r*| is off the prediction's |r̂| by this
    /// factor or more, either way: a length under its inverse or over it times the
    /// predicted length (a fragment, or the target merged with something), which the
    /// innovation gate weighs by its range's wide σ rather than its bearing. 1 (the
    /// default): every frame. A frame of the whole target then meets the innovation gate
    /// alone.
    pub bearing_gate_range_ratio: f64,
    /// With the innovation gate, how long a streak of frames it kept out, each within the gate
    /// of the one before, may last before the filter takes the next one, s (docs/equations.md,
    /// The gate re-opened): its kinematic covariance widened until that frame's normalised
    /// innovation is what the model expects, the size's kept. A target the filter's
    /// prediction lost (a few fragments that passed the gate moved it) is otherwise kept out
    /// until the prediction's covariance has grown enough to take it. 0 (the default): never.
    pub gate_reopen_s: f64,
    /// The gate re-opens only on a frame whose |r*| is within this factor of the
    /// prediction's |r̂| (its range, or its length, within the factor): a prediction that
    /// fragments moved is off by 1.1-1.3, a blob merged with a road reads 2.3-3 times the
    /// target's length (docs/findings.md, A whole-covered pixel's rounding). Choice: 2, between
    /// the two. Only with `gate_reopen_s`.
    pub gate_reopen_range_ratio: f64,
    /// `measurement` (default) or `prediction`: the pixels at which a frame's pixel covariance
    /// is mapped to r's (Kalman filter, camera frames). `measurement` is the seed's mapping of
    /// pixel noise at the measurement; `prediction` linearises at the filter's prediction, as
    /// an extended Kalman filter does, so a short fragment of the target reads a normalised
    /// innovation as large as its range error warrants. `prediction` loses formation_scene's
    /// target in the approach on half the streams (docs/findings.md, The covariance at the
    /// prediction).
    pub covariance_at: CovarianceAt,
    /// `filter` (default, the seed's) or `excitation`: where the filter's size comes from
    /// (docs/equations.md, The size from the excitation as an instrument).
    pub size_from: SizeFrom,
    /// With `size_from = "excitation"`, Q of the band-pass about the excitation's frequency
    /// that the follower's position and the image's r pass before they are correlated with
    /// the excitation. Choice: 3, a band of a third of the frequency, which takes out the
    /// formation's turns (tens of seconds) and the frame-to-frame jitter and settles within
    /// a few periods.
    pub instrument_q: f64,
    /// With `size_from = "excitation"`, the length of the blocks over which the reading's σ
    /// is taken from the spread of the leader's part, in excitation periods. Choice: 3: the
    /// band-passed leader motion stays correlated over about a period, so shorter blocks
    /// read σ low (two periods read it 1.4 times low in `estimation::instrument`'s test).
    pub instrument_block_periods: f64,
    /// With `size_from = "excitation"`, the fewest whole blocks before the reading counts.
    /// Choice: 4, the fewest whose spread gives σ within about a third.
    pub instrument_min_blocks: u32,
    /// With `size_from = "excitation"`, how long after the first frame the sums start, s.
    /// Choice: 10 s, a few of the band-pass's settling times at a 3-5 s period.
    pub instrument_settle_s: f64,
    /// With `size_from = "excitation"`, the σ / b̂ of the reading below which the filter
    /// takes it. Choice: 0.05, the size's bar in the group runs.
    pub instrument_take_fraction: f64,
    /// With `size_from = "excitation"`, the time constant of the low-pass the excitation's
    /// direction E passes before the instrument reads the increments along it, in excitation
    /// periods (0: E as it is). Choice: 2, which passes a twelfth of a wobble at the swing's
    /// own frequency. With `excitation.frame = "target"` E turns with the command's frame,
    /// whose heading the follower's own swing moves (through its estimate of the leader's
    /// velocity); along an E that wobbles 1° in step with the swing, a leader's 50 ft/s
    /// along its track moves 0.9 ft at a 6 s period, read as an answer to the excitation
    /// (docs/equations.md, The instrument's direction; docs/findings.md, Group tracking, The
    /// instrument's direction).
    pub instrument_direction_periods: f64,
    /// With `size_from = "excitation"`, `excitation` or `across_slot`: the direction the
    /// instrument reads the increments along, before its low-pass. Choice: `excitation`, E
    /// itself, as first built; `across_slot` removes from E its component along the slot's
    /// line of sight, where a link in echelon (the slot 8 ft aside at 33 ft, 14°) reads a
    /// quarter of its swing through the range, whose error the swing moves (docs/findings.md,
    /// Group tracking, The instrument across the slot's line of sight).
    pub instrument_axis: InstrumentAxis,
    /// `inferred` (default) or `measured`: whether each frame's wing line is fused as the
    /// target's acceleration across its velocity (Kalman filter only; frames whose span the
    /// filter's view puts below `span_aspect_min` are not).
    pub target_bank: TargetBank,
    /// With `target_bank = "measured"`, σ of each end of the maximal length across it, px:
    /// the line's direction is uncertain by √2 σ / bI. Choice: 0.5 px, the sub-pixel edge's
    /// scatter about the silhouette (docs/findings.md, The target's bank from its wing line).
    pub bank_end_sigma_px: f64,
    /// With `target_bank = "measured"`, σ of the acceleration across the target's velocity
    /// beyond the line's noise, ft/s²: how far the target's turn departs from coordinated
    /// flight (sideslip in gusts, the lift's lag while it rolls) and the span's ends from the
    /// wing axis. Choice: 1 ft/s² (docs/findings.md, The target's bank from its wing line).
    pub bank_accel_sigma_fps2: f64,
}

impl Default for EstimatorSection {
    fn default() -> Self {
        Self {
            kind: EstimatorKind::Adaptive,
            log_kalman: false,
            jerk_psd: 0.01,
            inverse_size_psd: 1e-7,
            target_gust_sigma_fps: 0.0,
            target_gust_time_s: 2.0,
            leader_swing_period_s: 0.0,
            leader_swing_sigma_fps: 2.5,
            leader_swing_time_s: 20.0,
            size_bounds: SizeBounds::Law,
            pixel_sigma_px: [1.0, 1.0, 2.0],
            measurement_inflation: 2.0,
            scaled_sigma_floor: 1e-4,
            initial_inverse_size_sigma_per_ft: 0.15,
            initial_relative_velocity_sigma_fps: 15.0,
            initial_acceleration_sigma_fps2: 3.0,
            known_sigma_fraction: 0.05,
            size_model: SizeModel::Apparent,
            span_aspect_min: 0.8,
            span_length_min_fraction: 0.0,
            own_motion: OwnMotion::Position,
            airframe_view_sigma_deg: 5.0,
            airframe_length_bias_px: 2.1,
            airframe_length_sigma_px: [0.8, 16.0],
            airframe_angle_of_attack: AirframeAlpha::Zero,
            airframe_shape_sigma: 0.025,
            innovation_gate: 0.0,
            bearing_gate: 0.0,
            bearing_gate_range_ratio: 1.0,
            gate_reopen_s: 0.0,
            gate_reopen_range_ratio: 2.0,
            covariance_at: CovarianceAt::Measurement,
            target_bank: TargetBank::Inferred,
            size_from: SizeFrom::Filter,
            instrument_q: 3.0,
            instrument_block_periods: 3.0,
            instrument_min_blocks: 4,
            instrument_settle_s: 10.0,
            instrument_take_fraction: 0.05,
            instrument_direction_periods: 2.0,
            instrument_axis: InstrumentAxis::Excitation,
            bank_end_sigma_px: 0.5,
            bank_accel_sigma_fps2: 1.0,
        }
    }
}

impl EstimatorSection {
    /// Checks every value.
    pub fn validate(&self) -> Check {
        // (key, value, allowed [min, max]) of every scalar.
        let scalars = [
            ("jerk_psd", self.jerk_psd, 0.0, 1e6),
            ("inverse_size_psd", self.inverse_size_psd, 0.0, 1.0),
            (
                "target_gust_sigma_fps",
                self.target_gust_sigma_fps,
                0.0,
                1e3,
            ),
            ("target_gust_time_s", self.target_gust_time_s, 0.01, 1e4),
            (
                "measurement_inflation",
                self.measurement_inflation,
                0.01,
                1e4,
            ),
            ("scaled_sigma_floor", self.scaled_sigma_floor, 1e-9, 10.0),
            (
                "initial_inverse_size_sigma_per_ft",
                self.initial_inverse_size_sigma_per_ft,
                1e-6,
                100.0,
            ),
            (
                "initial_relative_velocity_sigma_fps",
                self.initial_relative_velocity_sigma_fps,
                0.0,
                1e4,
            ),
            (
                "initial_acceleration_sigma_fps2",
                self.initial_acceleration_sigma_fps2,
                0.0,
                1e4,
            ),
            ("known_sigma_fraction", self.known_sigma_fraction, 1e-6, 1.0),
            ("span_aspect_min", self.span_aspect_min, 0.0, 1.0),
            (
                "span_length_min_fraction",
                self.span_length_min_fraction,
                0.0,
                1.0,
            ),
            (
                "airframe_view_sigma_deg",
                self.airframe_view_sigma_deg,
                0.0,
                90.0,
            ),
            (
                "airframe_length_bias_px",
                self.airframe_length_bias_px,
                -100.0,
                100.0,
            ),
            ("airframe_shape_sigma", self.airframe_shape_sigma, 0.0, 1.0),
            ("bank_end_sigma_px", self.bank_end_sigma_px, 1e-3, 1e3),
            (
                "bank_accel_sigma_fps2",
                self.bank_accel_sigma_fps2,
                1e-3,
                1e3,
            ),
        ];
        for (key, value, min, max) in scalars.into_iter().chain(self.gate_scalars()) {
            check::in_closed(&format!("estimator.{key}"), value, min, max)?;
        }
        self.validate_swing()?;
        self.validate_instrument()?;
        for (i, sigma) in self.pixel_sigma_px.iter().enumerate() {
            check::in_closed(&format!("estimator.pixel_sigma_px[{i}]"), *sigma, 1e-3, 1e3)?;
        }
        for (i, sigma) in self.airframe_length_sigma_px.iter().enumerate() {
            let key = format!("estimator.airframe_length_sigma_px[{i}]");
            check::in_closed(&key, *sigma, 0.0, 1e4)?;
        }
        Ok(())
    }

    /// The leader's swing: a period of 0 (none) or at least 0.1 s, a σ, and a wander time
    /// no shorter than the period (the oscillator stays underdamped).
    fn validate_swing(&self) -> Check {
        let period = self.leader_swing_period_s;
        check::in_closed("estimator.leader_swing_period_s", period, 0.0, 1e3)?;
        check::require(
            period == 0.0 || period >= 0.1,
            "estimator.leader_swing_period_s",
            period,
            "0 (none) or [0.1, 1000]",
        )?;
        check::in_closed(
            "estimator.leader_swing_sigma_fps",
            self.leader_swing_sigma_fps,
            0.0,
            1e3,
        )?;
        check::in_closed(
            "estimator.leader_swing_time_s",
            self.leader_swing_time_s,
            period.max(0.1),
            1e4,
        )
    }

    /// The instrument's settings; it needs at least two blocks, the fewest a spread has.
    fn validate_instrument(&self) -> Check {
        for (key, value, min, max) in self.instrument_scalars() {
            check::in_closed(&format!("estimator.{key}"), value, min, max)?;
        }
        let blocks = self.instrument_min_blocks;
        check::require(
            (2..=1000).contains(&blocks),
            "estimator.instrument_min_blocks",
            blocks,
            "[2, 1000] (a spread needs two blocks)",
        )
    }

    /// (key, value, allowed [min, max]) of the instrument's scalars.
    fn instrument_scalars(&self) -> [(&'static str, f64, f64, f64); 5] {
        [
            ("instrument_q", self.instrument_q, 0.5, 100.0),
            (
                "instrument_block_periods",
                self.instrument_block_periods,
                1.0,
                1e3,
            ),
            ("instrument_settle_s", self.instrument_settle_s, 0.0, 1e4),
            (
                "instrument_take_fraction",
                self.instrument_take_fraction,
                0.0,
                1.0,
            ),
            (
                "instrument_direction_periods",
                self.instrument_direction_periods,
                0.0,
                100.0,
            ),
        ]
    }

    /// (key, value, allowed [min, max]) of the validation gates' scalars.
    fn gate_scalars(&self) -> [(&'static str, f64, f64, f64); 5] {
        [
            ("innovation_gate", self.innovation_gate, 0.0, 1e6),
            ("bearing_gate", self.bearing_gate, 0.0, 1e6),
            (
                "bearing_gate_range_ratio",
                self.bearing_gate_range_ratio,
                1.0,
                1e6,
            ),
            ("gate_reopen_s", self.gate_reopen_s, 0.0, 1e6),
            (
                "gate_reopen_range_ratio",
                self.gate_reopen_range_ratio,
                1.0,
                1e6,
            ),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_valid_and_the_seeds() {
        let s = EstimatorSection::default();
        assert_eq!(s.validate(), Ok(()));
        assert_eq!(s.kind, EstimatorKind::Adaptive);
    }

    #[test]
    fn bad_values_are_named() {
        let s = EstimatorSection {
            pixel_sigma_px: [1.0, f64::NAN, 2.0],
            ..EstimatorSection::default()
        };
        let err = s.validate().expect_err("NaN");
        assert_eq!(err.key, "estimator.pixel_sigma_px[1]");
    }
}
