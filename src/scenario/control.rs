//! `[autopilot]`: gains and filters of the Chapter 7 flight controller (`crate::control`).
//!
//! The seed prints the control laws (7.20)-(7.33) but no numbers for them (section 7.4 gives
//! only the aircraft data and the surface limits), so every default here is a documented
//! choice. Gains are rates (1/s) of the error dynamics they set: (7.24) gives
//! ė_φ = -k_φ e_φ, so 1/k_φ is the time constant of the roll-angle error. The inner (rate)
//! loop is made about five times faster than the outer (angle) loop, and both slower than the
//! surface servos (τ = 25 ms, 40 rad/s).

use serde::{Deserialize, Serialize};

use super::check::{self, Check};

/// Which outer loop turns the guidance's V_F into the thrust and flight-path commands the
/// inner (attitude and rate) loops fly.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum OuterLoop {
    /// The seed's (7.1)-(7.3) with (7.20): thrust holds the airspeed, γ_c is V_F's, with the
    /// flight-path limits and the flags below (`control::velocity_command`).
    #[default]
    Chapter7,
    /// A total-energy controller (docs/equations.md, The energy outer loop): thrust and speed
    /// brake set the specific total energy rate, γ_c distributes it between height and speed
    /// (`control::energy`). The Chapter 7 loop's flags (`climb_waits_for_speed`,
    /// `descent_waits_for_speed`, `limited_descent_keeps_horizontal_speed`,
    /// `flight_path_limits`, `weave_period_s`) do not apply to it.
    Energy,
}

/// Where the bank limit `max_bank_deg` acts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BankLimit {
    /// On the raw coordinated-turn command (the seed's (7.14) clamp); the roll prefilter's
    /// reference may overshoot it.
    #[default]
    Command,
    /// On the command and on the prefiltered bank reference the attitude loop tracks
    /// (docs/equations.md, The bank limit on the reference).
    Reference,
}

/// `[autopilot]`: the follower's flight controller (seed Chapter 7).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct AutopilotSection {
    /// The outer loop: `"chapter7"` (the seed's, the default) or `"energy"` (a total-energy
    /// controller with a stated speed-versus-height priority).
    pub outer_loop: OuterLoop,
    /// Energy loop: highest climb rate demanded, ft/s. 15 ft/s, 17° at 50 ft/s: above the
    /// seed target's 6 ft/s climbs with room to close a height gap; what the thrust cannot
    /// hold is shared out by `energy_speed_weight`.
    pub energy_max_climb_rate_fps: f64,
    /// Energy loop: time constant of the first-order lag that shapes the climb-rate demand,
    /// s (0: none, the default). Unshaped, a step of the demand reaches the thrust at once
    /// and the flight path through the pitch loop's lag, and the difference goes into speed
    /// (a 30 ft height step: ±3.1 ft/s of airspeed unshaped, ±2.6 with 0.5 s); but the lag
    /// delays the height's response to the guidance: with 0.5 s, over moderate streams 1-30
    /// the median RMS of the vertical slot error rose from 2.1 to 3.7 ft (measured).
    pub energy_climb_rate_time_constant_s: f64,
    /// Energy loop: highest descent rate demanded, ft/s (15 ft/s, as the climb).
    pub energy_max_descent_rate_fps: f64,
    /// Energy loop: largest |γ_c|, deg. 20°: above the 17° of the rate limits at 50 ft/s, and
    /// the flight-path angles at which the α envelope (`max_alpha_deg`) still leaves room.
    pub energy_max_flight_path_deg: f64,
    /// Energy loop: the speed-versus-height priority s of TECS, in [0, 2]: the height's
    /// weight is min(2 - s, 1), the speed's min(s, 1). It decides who gives when thrust (or
    /// the speed brake) saturates: 0 holds the height and lets the speed go, 2 holds the speed
    /// and lets the height go, 1 shares the shortfall equally (TECS's default). Within 10%
    /// above `min_airspeed_cmd_fps` it moves to 2 whatever its value: the seed's thrust
    /// T ∝ V² shrinks with the speed, and a height kept at its expense ends in a stall.
    pub energy_speed_weight: f64,
    /// Energy loop: integral gain on the total energy rate error (thrust channel), 1/s: it
    /// learns the thrust the nominal drag model lacks. 0.2: a 5 s time constant, slower than
    /// the airspeed law (1 s) so that it trims rather than fights it.
    pub energy_thrust_integral_gain_per_s: f64,
    /// Energy loop: integral gain on the energy balance rate error (flight-path channel),
    /// 1/s: it learns the flight path the α reference misses. 0.2, as the thrust's.
    pub energy_balance_integral_gain_per_s: f64,
    /// k_V of the airspeed loop (7.20), 1/s. 1 s error time constant; it also damps the
    /// phugoid, which the plant's T ∝ V² thrust leaves almost undamped.
    pub airspeed_gain_per_s: f64,
    /// k_φ of (7.24), 1/s.
    pub roll_gain_per_s: f64,
    /// k_θ of (7.24), 1/s.
    pub pitch_gain_per_s: f64,
    /// k_ψ of (7.24), 1/s.
    pub yaw_gain_per_s: f64,
    /// k_p of (7.25), 1/s.
    pub roll_rate_gain_per_s: f64,
    /// k_q of (7.25), 1/s.
    pub pitch_rate_gain_per_s: f64,
    /// k_r of (7.25), 1/s.
    pub yaw_rate_gain_per_s: f64,
    /// ω_V of the airspeed prefilter (7.33), rad/s.
    pub airspeed_prefilter_omega_rps: f64,
    /// ζ_V of the airspeed prefilter (7.33).
    pub airspeed_prefilter_zeta: f64,
    /// ω of the roll-angle prefilter ((7.33) with one more integrator, on φ_c), rad/s.
    pub roll_prefilter_omega_rps: f64,
    /// ζ of the roll-angle prefilter.
    pub roll_prefilter_zeta: f64,
    /// ω of the pitch-angle prefilter ((7.33) with one more integrator, on θ_c), rad/s.
    pub pitch_prefilter_omega_rps: f64,
    /// ζ of the pitch-angle prefilter.
    pub pitch_prefilter_zeta: f64,
    /// ω of the heading prefilter ((7.33) with one more integrator, on ψ_c), rad/s.
    pub heading_prefilter_omega_rps: f64,
    /// ζ of the heading prefilter.
    pub heading_prefilter_zeta: f64,
    /// The roll, pitch and heading prefilters follow ramps without lag (true, the integral
    /// form of (7.33), whose steps overshoot), or are plain low-passes (false: no overshoot, a
    /// lag of 2ζ/ω behind a ramp; see `control::prefilter`).
    pub attitude_prefilters_follow_ramps: bool,
    /// Natural frequency of the command filter that gives ṗ_c, q̇_c, ṙ_c, rad/s.
    pub rate_filter_omega_rps: f64,
    /// Damping ratio of the rate command filter.
    pub rate_filter_zeta: f64,
    /// θ_c = γ_c + α_ref cos φ, α_ref from the nominal lift curve (true), or the seed's
    /// Remark 9 θ_c = γ_c (false: the aircraft then flies α below the commanded path).
    pub alpha_feedforward: bool,
    /// Largest |α_ref| the pitch offset may ask for, deg (the stall blend starts near 27°).
    pub max_alpha_ref_deg: f64,
    /// α envelope, upper end, deg: θ_c ≤ γ + α_max cos φ (beyond the seed; the stall blend of
    /// the seed follower's lift curve is centred on 27°).
    pub max_alpha_deg: f64,
    /// α envelope, lower end, deg: θ_c ≥ γ + α_min cos φ.
    pub min_alpha_deg: f64,
    /// Largest |φ_c| of the coordinated turn (7.14), deg.
    pub max_bank_deg: f64,
    /// `"command"` (the seed's: (7.14)'s φ_c clamped to `max_bank_deg`, which the roll
    /// prefilter's integral form overshoots on a step: an S-turn reversal from -30° to 30°
    /// reached a 46° reference) or `"reference"`: the prefiltered reference is held inside the
    /// limit too. Near its slowest speed the aircraft cannot hold its height in a 46° turn
    /// (at 34 ft/s the lift at α_max carries 1.05-1.2 g, a 17-33° bank).
    pub bank_limit: BankLimit,
    /// Keep γ_c between the steepest descent and the steepest climb that (7.20) can hold
    /// at steady speed with the throttle inside its range (beyond the seed, whose thrust
    /// T ∝ V² cannot hold every climb and descent of the target profile at every speed).
    pub flight_path_limits: bool,
    /// Fraction of the throttle range kept in reserve at each end by the flight-path limits.
    /// 0.05: with the data file's C_TδT = 0.3 that is the thrust the controller's author kept
    /// with 0.1 of C_TδT = 0.15 (a steeper descent costs speed control near idle).
    pub thrust_margin_fraction: f64,
    /// The steepest climb keeps the thrust the airspeed law needs to reach its reference
    /// (true): below the commanded speed at full throttle the climb waits until the speed is
    /// there. With false (the limits of steady speed) a follower slowed by a climb keeps
    /// climbing at the speed it has, and, the seed's thrust T ∝ V² being least at low speed,
    /// may never gain the thrust to speed up (docs/findings.md, Flight-path limits).
    pub climb_waits_for_speed: bool,
    /// When the descent limit holds γ_c above the command's, fly the command's horizontal
    /// air speed, V_c = ‖V_h‖ / cos γ_c (true), instead of its norm ‖V_F‖ (7.1) (false, the
    /// seed's). With the norm, a descent the airframe cannot fly (a sustained updraft holding
    /// it high) turns the commanded vertical speed into horizontal speed, and the follower
    /// overtakes the target (docs/formation.md, On the Chapter 7 loop). Climbs keep the norm: a
    /// follower held low needs the speed (T ∝ V²; docs/findings.md, Flight-path limits).
    pub limited_descent_keeps_horizontal_speed: bool,
    /// The steepest descent keeps the deceleration the airspeed law asks for (true): above
    /// the commanded speed at idle the descent waits until the speed is there. With false (the
    /// limits of steady speed) a follower held high by an updraft and then let down dives at
    /// the speed it has and overtakes the target (docs/formation.md, On the Chapter 7 loop).
    /// The deceleration is the one the airspeed law asks for toward the command's norm, also
    /// when `limited_descent_keeps_horizontal_speed` flies less, so with both the excess speed
    /// goes only a little sooner (tests/control_flight.rs).
    pub descent_waits_for_speed: bool,
    /// S-turns, s per pair of legs (0: none, the seed's). When the commanded horizontal air
    /// speed is below the slowest the aircraft flies, it flies that speed off the commanded
    /// course, to the right for half a period and to the left for the other half, so that it
    /// keeps the commanded speed along the course instead of overtaking a slower target. Only
    /// while the slot lies behind the target (as far behind as beside it, at least): a leg
    /// from a slot beside the target would cross under it.
    pub weave_period_s: f64,
    /// S-turns by geometry, ft off the slot's line (0: none, the seed's): when the commanded
    /// horizontal air speed is below the slowest the aircraft flies, it flies that speed off
    /// the commanded course, as the clock's S-turns do, but keeps each side until it is this
    /// far to that side of the slot's line (the target's estimated track through the slot,
    /// from the Kalman estimate), then turns to the other. It takes the place of
    /// `weave_period_s` and applies to both outer loops, behind the target only as they do.
    /// 10 ft would keep a 32 ft slot's follower within about 17° of the target's track.
    pub weave_half_width_ft: f64,
    /// S-turns by geometry: how much slower than the aircraft's slowest the command along
    /// the slot's line may be, ft/s, before a leg is flown for it (0: none, every deficit is
    /// stretched). While the follower is at or behind its slot it flies its floor straight
    /// and takes the deficit as along-track error; the deficit accepted falls to 0 as it
    /// comes `weave_lead_ft` ahead of its slot. A gust that lowers the air-relative command
    /// for a few seconds then costs a few feet along the track, not a leg and a reversal at
    /// full bank (docs/findings.md, Path stretching with a lead budget).
    pub weave_deficit_fps: f64,
    /// S-turns by geometry: how far ahead of its slot, ft, the follower may come before the
    /// deficit `weave_deficit_fps` is stretched in full. Choice: 5 ft, a sixth of the seed's
    /// 32 ft slot; with 2 ft/s accepted, 5 ft lost no frame over 100 light streams of
    /// formation.toml's energy loop, where 7 ft lost 1-4 frames on two streams and no budget
    /// 4-15 frames on two (docs/findings.md, Path stretching with a lead budget).
    pub weave_lead_ft: f64,
    /// S-turns by geometry in a turn: from this turn rate of the target, °/s (from the
    /// estimate, ω = (d̂ × â)·z / ‖d̂_h‖²), every leg is flown to the outside of the target's
    /// turn and is not reversed at the half width (0: the legs alternate as on a straight
    /// track). A leg's swing reaches the turn radius at the floor, R = V_min² / (g tan φ_max),
    /// 66 ft at 35 ft/s and 30°, and on the inside of a turn of rate ω lowers the speed the
    /// follower needs along the track by up to ω R: in a tailwind at the target's slowest,
    /// such inside legs carried followers ahead of the target and back across its track
    /// within 8 ft of it (docs/findings.md, Legs outside the turn). Choice: 1.72 °/s (0.03
    /// rad/s), where ω R is 2 ft/s, the deficit the slot accepts in the energy-control
    /// measurements (`weave_deficit_fps`), for the default floor and bank limit; it is not
    /// recomputed when those keys change.
    pub weave_outside_turn_dps: f64,
    /// Lowest airspeed command, ft/s: 1.25 times the stall speed of the seed follower
    /// (C_L,max ≈ 1.9 at the stall blend's 27° gives V_s ≈ 28 ft/s at sea level), just below
    /// the target profile's slowest 35.4 ft/s.
    pub min_airspeed_cmd_fps: f64,
    /// Highest airspeed command, ft/s: the seed's thrust T = ½ρV²S C_TδT δT grows with V² as
    /// the drag does, so this airframe has no top speed of its own; 65 ft/s is the target
    /// profile's fastest 60 ft/s plus a margin to close a gap.
    pub max_airspeed_cmd_fps: f64,
    /// The inversion of (7.19) uses at least the dynamic pressure of this airspeed, ft/s.
    pub min_control_airspeed_fps: f64,
    /// Fly V_F relative to the air mass: V_F - ŵ, ŵ the measured wind (inertial minus
    /// air-relative velocity) low-passed with `wind_filter_time_constant_s`. False: the seed's
    /// V_c = ‖V_F‖, exact only in still air.
    pub wind_compensation: bool,
    /// Time constant of the wind estimate's low-pass filter, s.
    pub wind_filter_time_constant_s: f64,
    /// Adapt the RBF networks (7.23), (7.28); false keeps Ŵ = 0.
    pub rbf_enabled: bool,
    /// Width σ of the Gaussian RBFs (2.34) in normalised input units.
    pub rbf_width: f64,
    /// Adaptation gain G_D of the drag network (7.23).
    pub drag_adaptation_gain: f64,
    /// Adaptation gain G_p of the roll-moment network (7.28).
    pub roll_adaptation_gain: f64,
    /// Adaptation gain G_q of the pitch-moment network (7.28).
    pub pitch_adaptation_gain: f64,
    /// Adaptation gain G_r of the yaw-moment network (7.28).
    pub yaw_adaptation_gain: f64,
    /// Projection bound ‖Ŵ_D‖ ≤ this (Ω_0), ft/s² per unit RBF.
    pub drag_weight_max: f64,
    /// Projection bound ‖Ŵ_l‖, ‖Ŵ_m‖, ‖Ŵ_n‖ ≤ this (Ω_0), rad/s² per unit RBF.
    pub moment_weight_max: f64,
    /// Projection tolerance ε of f(W) = (WᵀW - W_max²)/ε (Appendix A).
    pub weight_epsilon: f64,
    /// Stop a network's adaptation while the actuator it acts through is at its limit.
    pub freeze_adaptation_on_saturation: bool,
}

impl Default for AutopilotSection {
    fn default() -> Self {
        Self {
            outer_loop: OuterLoop::Chapter7,
            energy_max_climb_rate_fps: 15.0,
            energy_max_descent_rate_fps: 15.0,
            energy_climb_rate_time_constant_s: 0.0,
            energy_max_flight_path_deg: 20.0,
            energy_speed_weight: 1.0,
            energy_thrust_integral_gain_per_s: 0.2,
            energy_balance_integral_gain_per_s: 0.2,
            airspeed_gain_per_s: 1.0,
            roll_gain_per_s: 2.0,
            pitch_gain_per_s: 2.0,
            yaw_gain_per_s: 1.0,
            roll_rate_gain_per_s: 10.0,
            pitch_rate_gain_per_s: 10.0,
            yaw_rate_gain_per_s: 5.0,
            airspeed_prefilter_omega_rps: 1.0,
            airspeed_prefilter_zeta: 0.9,
            roll_prefilter_omega_rps: 2.0,
            roll_prefilter_zeta: 0.9,
            pitch_prefilter_omega_rps: 2.0,
            pitch_prefilter_zeta: 0.9,
            heading_prefilter_omega_rps: 1.5,
            heading_prefilter_zeta: 0.9,
            attitude_prefilters_follow_ramps: true,
            rate_filter_omega_rps: 30.0,
            rate_filter_zeta: 0.8,
            alpha_feedforward: true,
            max_alpha_ref_deg: 15.0,
            max_alpha_deg: 18.0,
            min_alpha_deg: -8.0,
            max_bank_deg: 30.0,
            bank_limit: BankLimit::Command,
            flight_path_limits: true,
            thrust_margin_fraction: 0.05,
            climb_waits_for_speed: false,
            limited_descent_keeps_horizontal_speed: false,
            descent_waits_for_speed: false,
            weave_period_s: 0.0,
            weave_half_width_ft: 0.0,
            weave_deficit_fps: 0.0,
            weave_lead_ft: 5.0,
            weave_outside_turn_dps: 1.72,
            min_airspeed_cmd_fps: 35.0,
            max_airspeed_cmd_fps: 65.0,
            min_control_airspeed_fps: 15.0,
            wind_compensation: true,
            wind_filter_time_constant_s: 1.0,
            rbf_enabled: true,
            rbf_width: 1.0,
            drag_adaptation_gain: 0.1,
            roll_adaptation_gain: 1.0,
            pitch_adaptation_gain: 1.0,
            yaw_adaptation_gain: 1.0,
            drag_weight_max: 2.0,
            moment_weight_max: 3.0,
            weight_epsilon: 0.5,
            freeze_adaptation_on_saturation: true,
        }
    }
}

impl AutopilotSection {
    /// Checks every value; keys are named as under `[autopilot]`.
    pub fn validate(&self) -> Check {
        self.validate_gains()?;
        self.validate_filters()?;
        self.validate_attitude_limits()?;
        self.validate_throttle_and_airspeed()?;
        check::in_closed(
            "autopilot.wind_filter_time_constant_s",
            self.wind_filter_time_constant_s,
            1e-3,
            1e3,
        )?;
        check::in_closed("autopilot.weave_period_s", self.weave_period_s, 0.0, 1e3)?;
        check::in_closed(
            "autopilot.weave_half_width_ft",
            self.weave_half_width_ft,
            0.0,
            1e3,
        )?;
        check::in_closed(
            "autopilot.weave_deficit_fps",
            self.weave_deficit_fps,
            0.0,
            20.0,
        )?;
        check::in_closed("autopilot.weave_lead_ft", self.weave_lead_ft, 0.1, 100.0)?;
        check::in_closed(
            "autopilot.weave_outside_turn_dps",
            self.weave_outside_turn_dps,
            0.0,
            90.0,
        )?;
        // The deficit is left along the slot's line, which only S-turns by geometry fly by.
        check::require(
            self.weave_deficit_fps == 0.0 || self.weave_half_width_ft > 0.0,
            "autopilot.weave_deficit_fps",
            self.weave_deficit_fps,
            "0 without S-turns by geometry (autopilot.weave_half_width_ft = 0)",
        )?;
        self.validate_energy()?;
        self.validate_rbf()
    }

    /// The energy loop's limits, priority and integral gains.
    fn validate_energy(&self) -> Check {
        all_in_closed(
            &[
                (
                    "autopilot.energy_max_climb_rate_fps",
                    self.energy_max_climb_rate_fps,
                ),
                (
                    "autopilot.energy_max_descent_rate_fps",
                    self.energy_max_descent_rate_fps,
                ),
            ],
            0.0,
            200.0,
        )?;
        check::in_closed(
            "autopilot.energy_climb_rate_time_constant_s",
            self.energy_climb_rate_time_constant_s,
            0.0,
            10.0,
        )?;
        check::in_closed(
            "autopilot.energy_max_flight_path_deg",
            self.energy_max_flight_path_deg,
            1.0,
            60.0,
        )?;
        check::in_closed(
            "autopilot.energy_speed_weight",
            self.energy_speed_weight,
            0.0,
            2.0,
        )?;
        all_in_closed(
            &[
                (
                    "autopilot.energy_thrust_integral_gain_per_s",
                    self.energy_thrust_integral_gain_per_s,
                ),
                (
                    "autopilot.energy_balance_integral_gain_per_s",
                    self.energy_balance_integral_gain_per_s,
                ),
            ],
            0.0,
            100.0,
        )
    }

    /// The error-dynamics gains of (7.20), (7.24) and (7.25).
    fn validate_gains(&self) -> Check {
        all_in_closed(
            &[
                ("autopilot.airspeed_gain_per_s", self.airspeed_gain_per_s),
                ("autopilot.roll_gain_per_s", self.roll_gain_per_s),
                ("autopilot.pitch_gain_per_s", self.pitch_gain_per_s),
                ("autopilot.yaw_gain_per_s", self.yaw_gain_per_s),
                ("autopilot.roll_rate_gain_per_s", self.roll_rate_gain_per_s),
                (
                    "autopilot.pitch_rate_gain_per_s",
                    self.pitch_rate_gain_per_s,
                ),
                ("autopilot.yaw_rate_gain_per_s", self.yaw_rate_gain_per_s),
            ],
            1e-3,
            1e3,
        )
    }

    /// The prefilters' and the rate command filter's natural frequencies, then their damping
    /// ratios.
    fn validate_filters(&self) -> Check {
        all_in_closed(
            &[
                (
                    "autopilot.airspeed_prefilter_omega_rps",
                    self.airspeed_prefilter_omega_rps,
                ),
                (
                    "autopilot.roll_prefilter_omega_rps",
                    self.roll_prefilter_omega_rps,
                ),
                (
                    "autopilot.pitch_prefilter_omega_rps",
                    self.pitch_prefilter_omega_rps,
                ),
                (
                    "autopilot.heading_prefilter_omega_rps",
                    self.heading_prefilter_omega_rps,
                ),
                (
                    "autopilot.rate_filter_omega_rps",
                    self.rate_filter_omega_rps,
                ),
            ],
            1e-3,
            1e3,
        )?;
        all_in_closed(
            &[
                (
                    "autopilot.airspeed_prefilter_zeta",
                    self.airspeed_prefilter_zeta,
                ),
                ("autopilot.roll_prefilter_zeta", self.roll_prefilter_zeta),
                ("autopilot.pitch_prefilter_zeta", self.pitch_prefilter_zeta),
                (
                    "autopilot.heading_prefilter_zeta",
                    self.heading_prefilter_zeta,
                ),
                ("autopilot.rate_filter_zeta", self.rate_filter_zeta),
            ],
            0.1,
            10.0,
        )
    }

    /// The α reference and envelope and the bank limit.
    fn validate_attitude_limits(&self) -> Check {
        check::in_closed(
            "autopilot.max_alpha_ref_deg",
            self.max_alpha_ref_deg,
            0.0,
            25.0,
        )?;
        check::in_closed("autopilot.max_alpha_deg", self.max_alpha_deg, 1.0, 40.0)?;
        check::in_closed("autopilot.min_alpha_deg", self.min_alpha_deg, -40.0, -1.0)?;
        check::require(
            self.max_alpha_ref_deg <= self.max_alpha_deg,
            "autopilot.max_alpha_ref_deg",
            self.max_alpha_ref_deg,
            format!("<= autopilot.max_alpha_deg = {}", self.max_alpha_deg),
        )?;
        check::in_closed("autopilot.max_bank_deg", self.max_bank_deg, 1.0, 80.0)
    }

    /// The flight-path limits' throttle margin and the airspeed command and control limits.
    fn validate_throttle_and_airspeed(&self) -> Check {
        check::in_closed(
            "autopilot.thrust_margin_fraction",
            self.thrust_margin_fraction,
            0.0,
            0.45,
        )?;
        check::in_closed(
            "autopilot.min_airspeed_cmd_fps",
            self.min_airspeed_cmd_fps,
            0.0,
            500.0,
        )?;
        check::require(
            self.max_airspeed_cmd_fps.is_finite()
                && self.max_airspeed_cmd_fps > self.min_airspeed_cmd_fps
                && self.max_airspeed_cmd_fps <= 500.0,
            "autopilot.max_airspeed_cmd_fps",
            self.max_airspeed_cmd_fps,
            format!(
                "(autopilot.min_airspeed_cmd_fps = {}, 500]",
                self.min_airspeed_cmd_fps
            ),
        )?;
        check::in_closed(
            "autopilot.min_control_airspeed_fps",
            self.min_control_airspeed_fps,
            1.0,
            500.0,
        )
    }

    /// The RBF networks (7.23), (7.28): width, adaptation gains and projection bounds.
    fn validate_rbf(&self) -> Check {
        check::in_closed("autopilot.rbf_width", self.rbf_width, 0.05, 100.0)?;
        all_in_closed(
            &[
                ("autopilot.drag_adaptation_gain", self.drag_adaptation_gain),
                ("autopilot.roll_adaptation_gain", self.roll_adaptation_gain),
                (
                    "autopilot.pitch_adaptation_gain",
                    self.pitch_adaptation_gain,
                ),
                ("autopilot.yaw_adaptation_gain", self.yaw_adaptation_gain),
            ],
            0.0,
            1e4,
        )?;
        check::in_closed("autopilot.drag_weight_max", self.drag_weight_max, 0.0, 1e4)?;
        check::in_closed(
            "autopilot.moment_weight_max",
            self.moment_weight_max,
            0.0,
            1e4,
        )?;
        check::in_closed("autopilot.weight_epsilon", self.weight_epsilon, 1e-6, 1e4)
    }
}

/// Every `(key, value)` in [lo, hi], checked in order (the first failure is reported).
fn all_in_closed(keyed_values: &[(&str, f64)], lo: f64, hi: f64) -> Check {
    for &(key, value) in keyed_values {
        check::in_closed(key, value, lo, hi)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_valid_and_round_trip() {
        let section = AutopilotSection::default();
        assert!(section.validate().is_ok());
        let text = toml::to_string(&section).expect("serialisable");
        let back: AutopilotSection = toml::from_str(&text).expect("parses");
        assert_eq!(back, section);
    }

    #[test]
    fn unknown_key_and_bad_value_are_named() {
        let err = toml::from_str::<AutopilotSection>("k_v = 1.0").expect_err("unknown key");
        assert!(err.to_string().contains("k_v"), "{err}");
        let section = AutopilotSection {
            rate_filter_zeta: 0.0,
            ..AutopilotSection::default()
        };
        let err = section.validate().expect_err("out of range");
        assert_eq!(err.key, "autopilot.rate_filter_zeta");
    }
}
