//! A run's figures: the panels of the seed's figures for the run's law and sensor, drawn as
//! its [`super::figure_set::FigureSet`] says.
//!
//! Every run: `relative_position.png` (R vs R_c, seed Figs 4.3 / 4.6, 5.3, 6.2, 6.5, 6.8),
//! `parameter_estimates.png` (b̂ and b̂ d̂ vs V_T for the velocity law, Figs 4.4, 6.3, 6.6; b̂
//! and ‖d̂‖ for the acceleration law, Figs 5.4, 6.9) and `velocity.png` (V_F vs V_T, Figs
//! 4.5 / 4.7, 6.1, 6.4). Acceleration law: `acceleration.png` (a_F vs a_T, Figs 5.2, 6.7) and
//! `target_acceleration.png` (Fig 5.1). Noisy sensor: `measurement.png` (r* against the
//! noise-free r; the seed shows no such figure). A Kalman filter:
//! `size_estimate.png` (its b̂ with the ±3σ_b band against the true b and, in camera runs,
//! the size each frame's silhouette implies; the excitation's amplitude). 6-DOF follower: the
//! Chapter 7 figures of [`super::aircraft_figures`].

use super::figure_set::{FigureNumbers, FigureSet, MotionEstimate};
use super::plots::{
    EXTRA, HIGHLIGHT, Panel, PlotError, REFERENCE, Series, TRUTH, draw_error, draw_figure,
    moving_mean, padded_range,
};
use crate::frames::Vec3;
use crate::scenario::Scenario;
use crate::sim::Snapshot;
use std::path::Path;

const AXES: [&str; 3] = ["x (north)", "y (east)", "z (down)"];

fn component(logged: &[Snapshot], f: impl Fn(&Snapshot) -> Vec3, axis: usize) -> Vec<f64> {
    logged.iter().map(|s| f(s)[axis]).collect()
}

/// Draws the figures of this run's [`FigureSet`] into `dir`.
pub fn draw_all(dir: &Path, scenario: &Scenario, logged: &[Snapshot]) -> Result<(), PlotError> {
    std::fs::create_dir_all(dir).map_err(draw_error(dir))?;
    let t: Vec<f64> = logged.iter().map(|s| s.t_s).collect();
    let set = FigureSet::of(scenario, logged);
    let numbers = &set.numbers;
    let size_ft = scenario.target.size_ft;
    draw_figure(
        &dir.join("relative_position.png"),
        &format!(
            "Relative position and reference command ({})",
            numbers.relative
        ),
        &t,
        &relative_position_panels(logged),
    )?;
    draw_figure(
        &dir.join("parameter_estimates.png"),
        &format!("Parameter estimates ({})", numbers.estimates),
        &t,
        &estimate_panels(set.motion_estimate, size_ft, logged),
    )?;
    let velocity = versus_target(
        logged,
        "V",
        "ft/s",
        ("V_F (follower)", |s| s.follower_velocity_ned_fps),
        ("V_T (target)", |s| s.target.velocity_ned_fps),
    );
    draw_figure(
        &dir.join("velocity.png"),
        &format!("Follower and target velocity ({})", numbers.velocity),
        &t,
        &velocity,
    )?;
    if let Some(with_mean) = set.acceleration {
        draw_acceleration_figures(dir, numbers, with_mean, &t, logged)?;
    }
    if let Some(noise) = &set.measurement {
        draw_measurement_figure(dir, noise, size_ft, &t, logged)?;
    }
    if let Some(focal_px) = set.size {
        draw_size_figure(dir, size_ft, focal_px, &t, logged)?;
    }
    if set.aircraft {
        super::aircraft_figures::draw_aircraft_figures(dir, &t, logged)?;
    }
    Ok(())
}

/// `relative_position.png`: R against R_c and the excited R*_c, per NED axis. R_c is drawn
/// last and dashed, so that it shows where it lies on R*_c (the excitation is small).
fn relative_position_panels(logged: &[Snapshot]) -> Vec<Panel> {
    (0..3)
        .map(|i| Panel {
            y_range: None,
            y_label: format!("R{}, ft", AXES[i]),
            series: vec![
                Series::new(
                    "R (true)",
                    component(logged, |s| s.relative_ned_ft, i),
                    TRUTH,
                ),
                Series::new(
                    "R*_c (with excitation)",
                    component(logged, |s| s.excited_command_ned_ft, i),
                    EXTRA,
                ),
                Series::new("R_c", component(logged, |s| s.command_ned_ft, i), REFERENCE).dashed(3),
            ],
        })
        .collect()
}

/// `parameter_estimates.png`: b̂ against b, then the law's estimates of the target's motion
/// (b̂ d̂ against V_T for the velocity law, ‖d̂‖ for the acceleration law).
fn estimate_panels(motion: MotionEstimate, size_ft: f64, logged: &[Snapshot]) -> Vec<Panel> {
    let b_panel = Panel {
        y_range: None,
        y_label: "b, ft".to_string(),
        series: vec![
            Series::new(
                "b̂ (estimate)",
                logged.iter().map(|s| s.b_hat_ft).collect(),
                TRUTH,
            ),
            Series::new("b (true)", vec![size_ft; logged.len()], REFERENCE),
        ],
    };
    match motion {
        MotionEstimate::ScaledVelocity => velocity_law_estimates(b_panel, logged),
        MotionEstimate::AccelerationBound => vec![
            b_panel,
            Panel {
                y_range: None,
                y_label: "‖d̂‖, ft/s".to_string(),
                series: vec![Series::new(
                    "estimate of ‖d_T‖",
                    logged
                        .iter()
                        .map(|s| s.target_motion.vector().norm())
                        .collect(),
                    TRUTH,
                )],
            },
        ],
    }
}

/// Velocity law: b̂ and b̂ d̂ (the estimate of V_T) against V_T.
fn velocity_law_estimates(b_panel: Panel, logged: &[Snapshot]) -> Vec<Panel> {
    let mut estimates = vec![b_panel];
    estimates.extend((0..3).map(|i| Panel {
        y_range: None,
        y_label: format!("V_T{}, ft/s", AXES[i]),
        series: vec![
            Series::new(
                "b̂ d̂ (estimate)",
                component(logged, |s| s.target_motion.vector() * s.b_hat_ft, i),
                TRUTH,
            ),
            Series::new(
                "V_T (true)",
                component(logged, |s| s.target.velocity_ned_fps, i),
                REFERENCE,
            ),
        ],
    }));
    estimates
}

/// Three panels of a follower quantity against the target's.
fn versus_target(
    logged: &[Snapshot],
    symbol: &str,
    unit: &str,
    follower: (&str, fn(&Snapshot) -> Vec3),
    target: (&str, fn(&Snapshot) -> Vec3),
) -> Vec<Panel> {
    (0..3)
        .map(|i| Panel {
            y_range: None,
            y_label: format!("{symbol}{}, {unit}", AXES[i]),
            series: vec![
                Series::new(follower.0, component(logged, follower.1, i), TRUTH),
                Series::new(target.0, component(logged, target.1, i), REFERENCE),
            ],
        })
        .collect()
}

/// Acceleration law: a_F against a_T (with `with_mean`, also a_F's 1 s moving mean, which
/// shows whether it follows a_T under a sensor's noise), and a_T alone.
fn draw_acceleration_figures(
    dir: &Path,
    numbers: &FigureNumbers,
    with_mean: bool,
    t: &[f64],
    logged: &[Snapshot],
) -> Result<(), PlotError> {
    let mut accel = versus_target(
        logged,
        "a",
        "ft/s²",
        ("a_F (guidance law)", |s| {
            s.follower_accel_ned_fps2()
                .unwrap_or(Vec3::from_element(f64::NAN))
        }),
        ("a_T (target)", |s| s.target.accel_ned_fps2),
    );
    if with_mean {
        let step_s = match (t.first(), t.get(1)) {
            (Some(a), Some(b)) if b > a => b - a,
            _ => 1.0,
        };
        let window = (1.0 / step_s).round().max(1.0) as usize;
        for panel in &mut accel {
            let mean = moving_mean(&panel.series[0].values, window);
            panel
                .series
                .push(Series::new("a_F, 1 s moving mean", mean, HIGHLIGHT));
        }
    }
    draw_figure(
        &dir.join("acceleration.png"),
        &format!(
            "Guidance law and target's acceleration ({})",
            numbers.acceleration
        ),
        t,
        &accel,
    )?;
    let target: Vec<Panel> = (0..3)
        .map(|i| Panel {
            y_range: None,
            y_label: format!("a_T{}, ft/s²", AXES[i]),
            series: vec![Series::new(
                "a_T",
                component(logged, |s| s.target.accel_ned_fps2, i),
                REFERENCE,
            )],
        })
        .collect();
    draw_figure(
        &dir.join("target_acceleration.png"),
        "Target's acceleration profile (seed Fig 5.1)",
        t,
        &target,
    )
}

/// Noisy sensor: the measured r* against the noise-free r = R/b; `noise` as the title says it.
fn draw_measurement_figure(
    dir: &Path,
    noise: &str,
    size_ft: f64,
    t: &[f64],
    logged: &[Snapshot],
) -> Result<(), PlotError> {
    let panels: Vec<Panel> = (0..3)
        .map(|i| Panel {
            y_range: None,
            y_label: format!("r{}", AXES[i]),
            series: vec![
                Series::new(
                    "r* (measured)",
                    component(
                        logged,
                        |s| s.r_measured.unwrap_or(Vec3::from_element(f64::NAN)),
                        i,
                    ),
                    EXTRA,
                ),
                Series::new(
                    "r = R / b (noise-free)",
                    logged
                        .iter()
                        .map(|s| s.relative_ned_ft[i] / size_ft)
                        .collect(),
                    TRUTH,
                ),
            ],
        })
        .collect();
    draw_figure(
        &dir.join("measurement.png"),
        &format!("Measured and noise-free scaled relative position ({noise})"),
        t,
        &panels,
    )
}

/// The part of the run `size_estimate.png`'s y axis is fitted to: the filter's transient
/// before it (σ_b of the first guess, b̂ far off) would squeeze the band that matters into a
/// few pixels.
const SIZE_TRANSIENT_FRACTION: f64 = 0.25;

/// The y range of `curves` from `from_s` on, with `include` in it and a 10% margin each
/// side (None when no curve has a value then).
pub fn focus_range(
    t_s: &[f64],
    curves: &[&[f64]],
    include: f64,
    from_s: f64,
) -> Option<(f64, f64)> {
    let after: Vec<f64> = curves
        .iter()
        .flat_map(|values| t_s.iter().zip(values.iter()))
        .filter(|(t, v)| **t >= from_s && v.is_finite())
        .map(|(_, v)| *v)
        .collect();
    (!after.is_empty()).then(|| padded_range(after.into_iter().chain([include]), 0.1))
}

/// Kalman filter: b̂ with its ±3σ_b band against the true b and, given the camera's focal
/// length `focal_px`, the size the frames' silhouettes imply (b_i ‖R‖ / f), and the
/// excitation's amplitude.
fn draw_size_figure(
    dir: &Path,
    size_ft: f64,
    focal_px: Option<f64>,
    t: &[f64],
    logged: &[Snapshot],
) -> Result<(), PlotError> {
    let filter = |f: fn(b_hat: f64, sigma: f64) -> f64| -> Vec<f64> {
        logged
            .iter()
            .map(|s| {
                s.filter
                    .estimate()
                    .map_or(f64::NAN, |e| f(e.b_hat_ft, e.b_sigma_ft))
            })
            .collect()
    };
    let mut size = vec![
        Series::new("b̂ (Kalman)", filter(|b, _| b), TRUTH),
        Series::new("b̂ + 3σ", filter(|b, sigma| b + 3.0 * sigma), EXTRA),
        Series::new("b̂ - 3σ", filter(|b, sigma| b - 3.0 * sigma), EXTRA),
        Series::new("b (true)", vec![size_ft; logged.len()], REFERENCE),
    ];
    if let Some(focal_px) = focal_px {
        let apparent = logged
            .iter()
            .map(|s| {
                s.frame
                    .and_then(|f| f.measured.map(|m| m.apparent_size_ft(focal_px, f.range_ft)))
                    .unwrap_or(f64::NAN)
            })
            .collect();
        // 1 px: a noisy curve drawn wider grows spikes at its sharp turns.
        let mut silhouette = Series::new("silhouette's size", apparent, HIGHLIGHT);
        silhouette.width_px = 1;
        size.push(silhouette);
    }
    let from_s = SIZE_TRANSIENT_FRACTION * t.last().copied().unwrap_or(0.0);
    let band: Vec<&[f64]> = size[..3].iter().map(|s| s.values.as_slice()).collect();
    let panels = [
        Panel {
            y_range: focus_range(t, &band, size_ft, from_s),
            y_label: format!("b, ft (range of t > {from_s:.0} s)"),
            series: size,
        },
        Panel {
            y_range: None,
            y_label: "excitation amplitude".to_string(),
            series: vec![Series::new(
                "a(t)",
                logged.iter().map(|s| s.excitation_amplitude).collect(),
                TRUTH,
            )],
        },
    ];
    draw_figure(
        &dir.join("size_estimate.png"),
        "Size estimate with its ±3σ band, and the excitation's amplitude",
        t,
        &panels,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The size panel's y range leaves out the filter's first guesses (b̂ from 4 ft, σ_b
    /// wide) and spans b̂ ± 3σ after them and the true size, with a margin.
    #[test]
    fn size_range_is_fitted_after_the_transient() {
        let t: Vec<f64> = (0..100).map(f64::from).collect();
        let b_hat: Vec<f64> = t
            .iter()
            .map(|t| if *t < 10.0 { 4.0 } else { 7.9 })
            .collect();
        let sigma = |t: f64| if t < 10.0 { 4.0 } else { 0.05 };
        let plus: Vec<f64> = t
            .iter()
            .zip(&b_hat)
            .map(|(t, b)| b + 3.0 * sigma(*t))
            .collect();
        let minus: Vec<f64> = t
            .iter()
            .zip(&b_hat)
            .map(|(t, b)| b - 3.0 * sigma(*t))
            .collect();
        let (lo, hi) = focus_range(&t, &[&b_hat, &plus, &minus], 8.0, 25.0).unwrap();
        assert!(lo < 7.75 && lo > 7.6, "lo {lo}");
        assert!(hi > 8.05 && hi < 8.2, "hi {hi}");
        assert_eq!(focus_range(&t, &[&b_hat], 8.0, 200.0), None);
    }

    /// R_c is drawn after R*_c (on top of it), dashed and wider, so that it shows where the
    /// two coincide.
    #[test]
    fn command_is_drawn_over_the_excited_command() {
        let panel = &relative_position_panels(&[])[0];
        let names: Vec<&str> = panel.series.iter().map(|s| s.label.as_str()).collect();
        assert_eq!(names, ["R (true)", "R*_c (with excitation)", "R_c"]);
        let (excited, command) = (&panel.series[1], &panel.series[2]);
        assert!(command.dashed && !excited.dashed);
        assert!(command.width_px > excited.width_px);
    }
}
