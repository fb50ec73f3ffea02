//! The 6-DOF follower's flight envelope over a run, recorded at every tick: the numbers the
//! seed's Figures 7.5-7.6 and 7.12-7.13 are read for (surfaces inside their limits, α and β
//! small, airspeed range).

use super::aircraft::AircraftActuation;

/// α and β are judged after this time, s (the first 5 s, when the guidance's first transient
/// has passed).
pub const ANGLES_FROM_S: f64 = 5.0;

/// Ticks at which the controller's command to an actuator was clamped to its limit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
pub struct LimitTicks {
    /// Throttle outside [0, 1].
    pub throttle: u64,
    /// Elevator beyond its limit.
    pub elevator: u64,
    /// Aileron beyond its limit.
    pub aileron: u64,
    /// Rudder beyond its limit.
    pub rudder: u64,
}

/// Extremes and limit hits of the 6-DOF follower over a run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlightEnvelope {
    /// Ticks recorded.
    pub ticks: u64,
    /// Largest |α| at t ≥ [`ANGLES_FROM_S`], rad.
    pub max_abs_alpha_rad: f64,
    /// Largest |β| at t ≥ [`ANGLES_FROM_S`], rad.
    pub max_abs_beta_rad: f64,
    /// Lowest and highest airspeed, ft/s.
    pub airspeed_range_fps: [f64; 2],
    /// Largest |δe|, |δa|, |δr| (actuator positions), rad.
    pub max_abs_surfaces_rad: [f64; 3],
    /// Lowest and highest throttle position.
    pub throttle_range: [f64; 2],
    /// Ticks with a clamped command, per actuator.
    pub limit_ticks: LimitTicks,
    /// Ticks at which a limit shaped the commanded flight path γ_c: the thrust range (and,
    /// with the energy loop, its climb-rate and flight-path limits).
    pub flight_path_limited_ticks: u64,
}

impl Default for FlightEnvelope {
    fn default() -> Self {
        Self {
            ticks: 0,
            max_abs_alpha_rad: 0.0,
            max_abs_beta_rad: 0.0,
            airspeed_range_fps: [f64::INFINITY, f64::NEG_INFINITY],
            max_abs_surfaces_rad: [0.0; 3],
            throttle_range: [f64::INFINITY, f64::NEG_INFINITY],
            limit_ticks: LimitTicks::default(),
            flight_path_limited_ticks: 0,
        }
    }
}

impl FlightEnvelope {
    /// Adds the instant `t_s`.
    pub fn record(&mut self, t_s: f64, a: &AircraftActuation) {
        self.ticks += 1;
        let air = &a.air_data;
        if t_s >= ANGLES_FROM_S {
            self.max_abs_alpha_rad = self.max_abs_alpha_rad.max(air.alpha_rad.abs());
            self.max_abs_beta_rad = self.max_abs_beta_rad.max(air.beta_rad.abs());
        }
        self.airspeed_range_fps = [
            self.airspeed_range_fps[0].min(air.airspeed_fps),
            self.airspeed_range_fps[1].max(air.airspeed_fps),
        ];
        let p = &a.actuators;
        for (max, value) in
            self.max_abs_surfaces_rad
                .iter_mut()
                .zip([p.elevator_rad, p.aileron_rad, p.rudder_rad])
        {
            *max = max.max(value.abs());
        }
        self.throttle_range = [
            self.throttle_range[0].min(p.throttle),
            self.throttle_range[1].max(p.throttle),
        ];
        let s = &a.autopilot.saturation;
        let l = &mut self.limit_ticks;
        l.throttle += u64::from(s.throttle);
        l.elevator += u64::from(s.elevator);
        l.aileron += u64::from(s.aileron);
        l.rudder += u64::from(s.rudder);
        self.flight_path_limited_ticks += u64::from(a.autopilot.flight_path_limited);
    }
}
