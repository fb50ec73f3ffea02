//! The 6-DOF follower's figures (seed Chapter 7, Figs 7.1-7.13 beside the relative-position
//! and estimate panels of [`super::figures`]): `flight_velocity.png` (the follower's velocity
//! against the V_F the autopilot flies and the target's), `euler_angles.png` (φ, θ, ψ against
//! the references φ_c, θ_c, ψ_c of (7.24)), `body_rates.png` (p, q, r against the filtered
//! rate commands of (7.25)), `surfaces.png` (δe, δa, δr and δT) and `air_data.png` (V against
//! V_c, α and β); seed Figs 7.5-7.6 and 7.12-7.13 show the surfaces well inside their limits
//! and α and β small (docs/equations.md, The 6-DOF follower).

use super::plots::{EXTRA, Panel, PlotError, REFERENCE, Series, TRUTH, draw_figure};
use crate::follower::AircraftActuation;
use crate::sim::Snapshot;
use std::path::Path;

const AXES: [&str; 3] = ["x (north)", "y (east)", "z (down)"];

/// A value of each logged row's aircraft record (NaN where a row has none).
fn series(logged: &[Snapshot], f: impl Fn(&AircraftActuation) -> f64) -> Vec<f64> {
    logged
        .iter()
        .map(|s| s.aircraft.as_ref().map_or(f64::NAN, &f))
        .collect()
}

/// Degrees per radian.
const DEG_PER_RAD: f64 = 180.0 / std::f64::consts::PI;

/// One panel of a quantity (converted to degrees when `deg`) against its command.
fn versus_command(
    logged: &[Snapshot],
    label: &str,
    value: impl Fn(&AircraftActuation) -> f64,
    command: impl Fn(&AircraftActuation) -> f64,
    deg: bool,
) -> Panel {
    let scale = if deg { DEG_PER_RAD } else { 1.0 };
    Panel {
        y_range: None,
        y_label: label.to_string(),
        series: vec![
            Series::new("aircraft", series(logged, |a| value(a) * scale), TRUTH),
            Series::new("command", series(logged, |a| command(a) * scale), REFERENCE),
        ],
    }
}

/// One panel of a single quantity times `scale`, its curve named `name`.
fn single(
    logged: &[Snapshot],
    label: &str,
    name: &str,
    f: fn(&AircraftActuation) -> f64,
    scale: f64,
) -> Panel {
    Panel {
        y_range: None,
        y_label: label.to_string(),
        series: vec![Series::new(name, series(logged, |a| f(a) * scale), TRUTH)],
    }
}

/// The panels of one figure from the logged rows.
type Panels = fn(&[Snapshot]) -> Vec<Panel>;

/// Draws the 6-DOF figures into `dir` (for runs whose telemetry carries aircraft data).
pub fn draw_aircraft_figures(dir: &Path, t: &[f64], logged: &[Snapshot]) -> Result<(), PlotError> {
    let figures: [(&str, &str, Panels); 5] = [
        (
            "flight_velocity.png",
            "Follower velocity, guidance command and target (seed Ch 7)",
            velocity_panels,
        ),
        (
            "euler_angles.png",
            "Euler angles and their references (7.24) (seed Ch 7)",
            euler_panels,
        ),
        (
            "body_rates.png",
            "Body rates and their commands (7.25) (seed Ch 7)",
            body_rate_panels,
        ),
        (
            "surfaces.png",
            "Control surfaces and throttle (seed Figs 7.5-7.6, 7.12-7.13)",
            surface_panels,
        ),
        (
            "air_data.png",
            "Airspeed, angle of attack and sideslip (seed Figs 7.5-7.6, 7.12-7.13)",
            air_data_panels,
        ),
    ];
    for (file, title, panels) in figures {
        draw_figure(&dir.join(file), title, t, &panels(logged))?;
    }
    Ok(())
}

/// `flight_velocity.png`: the follower's velocity, the V_F the autopilot flies and the
/// target's, per NED axis.
fn velocity_panels(logged: &[Snapshot]) -> Vec<Panel> {
    (0..3)
        .map(|i| Panel {
            y_range: None,
            y_label: format!("V{}, ft/s", AXES[i]),
            series: vec![
                Series::new(
                    "follower",
                    logged
                        .iter()
                        .map(|s| s.follower_velocity_ned_fps[i])
                        .collect(),
                    TRUTH,
                ),
                Series::new(
                    "V_F (guidance command)",
                    series(logged, |a| a.velocity_cmd_ned_fps[i]),
                    REFERENCE,
                ),
                Series::new(
                    "V_T (target)",
                    logged
                        .iter()
                        .map(|s| s.target.velocity_ned_fps[i])
                        .collect(),
                    EXTRA,
                ),
            ],
        })
        .collect()
}

/// `euler_angles.png`: φ, θ, ψ against the references of (7.24).
fn euler_panels(logged: &[Snapshot]) -> Vec<Panel> {
    vec![
        versus_command(
            logged,
            "φ, deg",
            |a| a.air_data.euler.phi_rad,
            |a| a.autopilot.euler_cmd.phi_rad,
            true,
        ),
        versus_command(
            logged,
            "θ, deg",
            |a| a.air_data.euler.theta_rad,
            |a| a.autopilot.euler_cmd.theta_rad,
            true,
        ),
        versus_command(
            logged,
            "ψ, deg",
            |a| a.air_data.euler.psi_rad,
            |a| crate::frames::wrap_angle_rad(a.autopilot.euler_cmd.psi_rad),
            true,
        ),
    ]
}

/// `body_rates.png`: p, q, r against the filtered rate commands of (7.25).
fn body_rate_panels(logged: &[Snapshot]) -> Vec<Panel> {
    ["p", "q", "r"]
        .iter()
        .enumerate()
        .map(|(i, name)| {
            versus_command(
                logged,
                &format!("{name}, deg/s"),
                |a| a.air_data.body_rates_rps[i],
                |a| a.autopilot.rate_cmd_filtered_rps[i],
                true,
            )
        })
        .collect()
}

/// `surfaces.png`: δe, δa, δr and δT.
fn surface_panels(logged: &[Snapshot]) -> Vec<Panel> {
    let surface = |label: &str, f: fn(&AircraftActuation) -> f64, scale: f64| {
        single(logged, label, "position", f, scale)
    };
    vec![
        surface(
            "δe, deg (limit ±30)",
            |a| a.actuators.elevator_rad,
            DEG_PER_RAD,
        ),
        surface(
            "δa, deg (limit ±30)",
            |a| a.actuators.aileron_rad,
            DEG_PER_RAD,
        ),
        surface(
            "δr, deg (limit ±20)",
            |a| a.actuators.rudder_rad,
            DEG_PER_RAD,
        ),
        surface("δT (0 to 1)", |a| a.actuators.throttle, 1.0),
    ]
}

/// `air_data.png`: V against V_c, α and β.
fn air_data_panels(logged: &[Snapshot]) -> Vec<Panel> {
    vec![
        versus_command(
            logged,
            "V, ft/s",
            |a| a.air_data.airspeed_fps,
            |a| a.autopilot.airspeed_cmd_fps,
            false,
        ),
        single(
            logged,
            "α, deg",
            "aircraft",
            |a| a.air_data.alpha_rad,
            DEG_PER_RAD,
        ),
        single(
            logged,
            "β, deg",
            "aircraft",
            |a| a.air_data.beta_rad,
            DEG_PER_RAD,
        ),
    ]
}
