//! Which figures a run draws: the panels of the seed's Figures 4.3-4.7 (relative position vs
//! command, parameter estimates, follower vs target velocity).

use super::plots::{EXTRA, Panel, PlotError, REFERENCE, Series, TRUTH, draw_figure};
use crate::frames::Vec3;
use crate::scenario::Scenario;
use crate::sim::Snapshot;
use std::path::Path;

const AXES: [&str; 3] = ["x (north)", "y (east)", "z (down)"];

fn component(logged: &[Snapshot], f: impl Fn(&Snapshot) -> Vec3, axis: usize) -> Vec<f64> {
    logged.iter().map(|s| f(s)[axis]).collect()
}

/// Draws every figure that applies to this run into `dir`.
pub fn draw_all(dir: &Path, scenario: &Scenario, logged: &[Snapshot]) -> Result<(), PlotError> {
    std::fs::create_dir_all(dir).map_err(|e| PlotError::Draw {
        path: dir.display().to_string(),
        reason: e.to_string(),
    })?;
    let t: Vec<f64> = logged.iter().map(|s| s.t_s).collect();

    let relative: Vec<Panel> = (0..3)
        .map(|i| Panel {
            y_label: format!("R{}, ft", AXES[i]),
            series: vec![
                Series::new(
                    "R (true)",
                    component(logged, |s| s.relative_ned_ft, i),
                    TRUTH,
                ),
                Series::new("R_c", component(logged, |s| s.command_ned_ft, i), REFERENCE),
                Series::new(
                    "R*_c (with excitation)",
                    component(logged, |s| s.excited_command_ned_ft, i),
                    EXTRA,
                ),
            ],
        })
        .collect();
    draw_figure(
        &dir.join("relative_position.png"),
        "Relative position and reference command (seed Fig 4.3 / 4.6)",
        &t,
        &relative,
    )?;

    let mut estimates = vec![Panel {
        y_label: "b, ft".to_string(),
        series: vec![
            Series::new(
                "b estimate",
                logged.iter().map(|s| s.b_hat_ft).collect(),
                TRUTH,
            ),
            Series::new(
                "b true",
                vec![scenario.target.size_ft; logged.len()],
                REFERENCE,
            ),
        ],
    }];
    estimates.extend((0..3).map(|i| Panel {
        y_label: format!("V_T{}, ft/s", AXES[i]),
        series: vec![
            Series::new(
                "b̂ d̂ (estimate)",
                component(logged, |s| s.d_hat * s.b_hat_ft, i),
                TRUTH,
            ),
            Series::new(
                "V_T (true)",
                component(logged, |s| s.target.velocity_ned_fps, i),
                REFERENCE,
            ),
        ],
    }));
    draw_figure(
        &dir.join("parameter_estimates.png"),
        "Parameter estimates (seed Fig 4.4)",
        &t,
        &estimates,
    )?;

    let velocity: Vec<Panel> = (0..3)
        .map(|i| Panel {
            y_label: format!("V{}, ft/s", AXES[i]),
            series: vec![
                Series::new(
                    "V_F (guidance)",
                    component(logged, |s| s.follower_velocity_ned_fps, i),
                    TRUTH,
                ),
                Series::new(
                    "V_T (target)",
                    component(logged, |s| s.target.velocity_ned_fps, i),
                    REFERENCE,
                ),
            ],
        })
        .collect();
    draw_figure(
        &dir.join("velocity.png"),
        "Guidance law and target's velocity (seed Fig 4.5 / 4.7)",
        &t,
        &velocity,
    )
}
