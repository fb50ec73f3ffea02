//! The controller's design data, checked and built once from the aircraft and the
//! `[autopilot]` section; the control steps read it.

use super::prefilter::{IntegralPrefilter, SecondOrderFilter, SmoothIntegralPrefilter};
use super::rbf::RbfBasis;
use crate::frames::Mat3;
use crate::projection::BallBound;
use crate::scenario::AutopilotSection;
use crate::scenario::check::{InvalidValue, require};
use crate::world::aircraft::AircraftParams;

/// The Chapter 7 control law for one aircraft: its nominal model, the gains, the prefilters,
/// the command filter, the RBF basis and the networks' projection bounds. Each step of
/// [`super::Autopilot::derivative`] is a method of it, in the module of its concept.
#[derive(Debug, Clone)]
pub(super) struct ControlLaw {
    pub(super) params: AircraftParams,
    pub(super) inertia_slug_ft2: Mat3,
    pub(super) gains: AutopilotSection,
    pub(super) airspeed_filter: IntegralPrefilter,
    pub(super) roll_filter: SmoothIntegralPrefilter,
    pub(super) pitch_filter: SmoothIntegralPrefilter,
    pub(super) heading_filter: SmoothIntegralPrefilter,
    pub(super) rate_filter: SecondOrderFilter,
    pub(super) basis: RbfBasis,
    pub(super) drag_bound: BallBound,
    pub(super) moment_bound: BallBound,
}

impl ControlLaw {
    /// The control law for the aircraft `params` (its nominal model) with the gains of `section`.
    /// Fails on an invalid section or aircraft, or when aileron and rudder cannot be solved for
    /// separately (the lateral block of (7.19) is singular).
    pub(super) fn new(
        params: &AircraftParams,
        section: &AutopilotSection,
    ) -> Result<Self, InvalidValue> {
        section.validate()?;
        params.validate()?;
        let a = &params.aero;
        let lateral_det =
            a.c_roll_da_per_rad * a.c_yaw_dr_per_rad - a.c_roll_dr_per_rad * a.c_yaw_da_per_rad;
        require(
            lateral_det.abs() > 1e-9,
            "aero.c_roll_da_per_rad",
            a.c_roll_da_per_rad,
            "a value with C_lδa C_nδr - C_lδr C_nδa != 0 (aileron and rudder must be separable)",
        )?;
        Ok(Self {
            params: params.clone(),
            inertia_slug_ft2: params.mass.inertia_slug_ft2(),
            gains: section.clone(),
            airspeed_filter: IntegralPrefilter {
                omega_rps: section.airspeed_prefilter_omega_rps,
                zeta: section.airspeed_prefilter_zeta,
            },
            roll_filter: SmoothIntegralPrefilter {
                omega_rps: section.roll_prefilter_omega_rps,
                zeta: section.roll_prefilter_zeta,
                follows_ramps: section.attitude_prefilters_follow_ramps,
            },
            pitch_filter: SmoothIntegralPrefilter {
                omega_rps: section.pitch_prefilter_omega_rps,
                zeta: section.pitch_prefilter_zeta,
                follows_ramps: section.attitude_prefilters_follow_ramps,
            },
            heading_filter: SmoothIntegralPrefilter {
                omega_rps: section.heading_prefilter_omega_rps,
                zeta: section.heading_prefilter_zeta,
                follows_ramps: section.attitude_prefilters_follow_ramps,
            },
            rate_filter: SecondOrderFilter {
                omega_rps: section.rate_filter_omega_rps,
                zeta: section.rate_filter_zeta,
            },
            basis: RbfBasis::axis_star(section.rbf_width),
            drag_bound: BallBound {
                max_norm: section.drag_weight_max,
                epsilon: section.weight_epsilon,
            },
            moment_bound: BallBound {
                max_norm: section.moment_weight_max,
                epsilon: section.weight_epsilon,
            },
        })
    }
}
