//! A study's `plots/*.png`: each outcome against each axis (the median over replicates and
//! the other axes with a box from the 25th to the 75th percentile and a dot per case; runs
//! that stopped early or lost the target for good are left out of the medians and drawn as
//! red rings), a heat map of each outcome over the first two axes with its colour scale, the
//! rate of runs that lost the target or did not complete against each axis, the
//! distribution of each outcome when a study has no axes, and, for the apparent-size study,
//! the apparent size over yaw and pitch for each roll. Pixel outcomes are also drawn as
//! angles (`*_deg`, [`angles`]); axes and outcomes are labelled in words with units
//! ([`labels`]).

use super::layout::{AxisLayout, StudyLayout};
use super::results::CaseRecord;
use super::spec::StudyKind;
use crate::output::plots::{PlotError, font_available};
use heatmap::heatmap;
use labels::label;
use lines::{Line, LineChart, Point, XAxis, draw_lines};
use std::path::Path;

pub mod angles;
pub mod heatmap;
pub mod labels;
pub mod lines;

/// The most lines one outcome-against-axis chart draws (one per value of the other axis).
const MAX_LINES: usize = 8;

/// Draws every plot of a study into `dir`; what could not be drawn is returned as warnings.
pub fn draw_study_plots(layout: &StudyLayout, records: &[CaseRecord], dir: &Path) -> Vec<String> {
    let mut warnings = Vec::new();
    if !font_available() {
        warnings.push(PlotError::NoFont.to_string());
        return warnings;
    }
    if let Err(e) = std::fs::create_dir_all(dir) {
        warnings.push(format!("cannot create {}: {e}", dir.display()));
        return warnings;
    }
    let (outcomes, records) = with_angle_outcomes(layout, records, &mut warnings);
    let records = records.as_slice();
    let mut results = Vec::new();
    for outcome in &outcomes {
        if layout.axes.is_empty() {
            results.push(distribution(
                &dir.join(format!("{}_cdf.png", file_part(outcome))),
                records,
                outcome,
            ));
        }
        for (k, axis) in layout.axes.iter().enumerate() {
            let path = dir.join(format!(
                "{}_vs_{}.png",
                file_part(outcome),
                file_part(&axis.name)
            ));
            results.push(outcome_vs_axis(&path, layout, records, outcome, k));
        }
        if layout.axes.len() >= 2 && layout.kind == StudyKind::Sweep {
            let path = dir.join(format!("heatmap_{}.png", file_part(outcome)));
            let (x, y) = (&layout.axes[0], &layout.axes[1]);
            let title = format!(
                "{}: median over {} and {}",
                label(outcome),
                label(&x.name),
                label(&y.name)
            );
            results.push(heatmap(&path, &title, (x, y), records, outcome));
        }
    }
    if layout.kind == StudyKind::Sweep && !layout.axes.is_empty() {
        results.push(loss_rates(
            &dir.join("lost_target_rate.png"),
            layout,
            records,
        ));
    }
    if layout.kind == StudyKind::ApparentSize {
        results.extend(apparent_size_maps(dir, layout, records));
    }
    warnings.extend(
        results
            .into_iter()
            .filter_map(Result::err)
            .map(|e| e.to_string()),
    );
    warnings
}

/// The outcomes to plot, each pixel outcome of a sweep followed by its angle, and the
/// records with the angles.
fn with_angle_outcomes(
    layout: &StudyLayout,
    records: &[CaseRecord],
    warnings: &mut Vec<String>,
) -> (Vec<String>, Vec<CaseRecord>) {
    let outcomes = layout.outcomes_to_plot(records, warnings);
    if layout.kind != StudyKind::Sweep {
        return (outcomes, records.to_vec());
    }
    let pixels: Vec<String> = outcomes
        .iter()
        .filter(|o| angles::angle_name(o).is_some())
        .cloned()
        .collect();
    let records = angles::with_angles(layout, records, &pixels);
    let mut all = Vec::new();
    for outcome in outcomes {
        let angle =
            angles::angle_name(&outcome).filter(|a| records.iter().any(|r| r.number(a).is_some()));
        all.push(outcome);
        all.extend(angle);
    }
    (all, records)
}

/// Whether a case counts towards the medians: it flew to its end and did not lose the
/// target for good (a run cut short or flying blind measures something else).
pub fn counts(record: &CaseRecord) -> bool {
    record.ended_ok() && !record.lost_target()
}

/// A name fit for a file: letters, digits, `_` and `-`; everything else `_`.
fn file_part(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// The median and the 25th and 75th percentiles of finite values (None without any).
pub fn quartiles(values: &[f64]) -> Option<[f64; 3]> {
    let mut sorted: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
    if sorted.is_empty() {
        return None;
    }
    sorted.sort_by(f64::total_cmp);
    let at = |q: f64| {
        let position = q * (sorted.len() - 1) as f64;
        let (lo, hi) = (position.floor() as usize, position.ceil() as usize);
        sorted[lo] + (sorted[hi] - sorted[lo]) * (position - lo as f64)
    };
    Some([at(0.25), at(0.5), at(0.75)])
}

/// A tick's number with at most six decimals and no trailing zeros: plotters' ticks are
/// round numbers stepped in floating point (1.2000000000000002 is 1.2).
pub fn tick_label(x: f64) -> String {
    let fixed = format!("{x:.6}");
    let trimmed = fixed.trim_end_matches('0').trim_end_matches('.');
    if trimmed == "-0" {
        "0".to_string()
    } else {
        trimmed.to_string()
    }
}

/// The finite values' range, widened by `margin` of its span each side (and never empty).
pub fn padded_range(values: impl Iterator<Item = f64>, margin: f64) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    let span = (hi - lo).max(1e-6 * hi.abs().max(1.0));
    (lo - margin * span, hi + margin * span)
}

/// Outcome against axis `k`: the median and quartiles over the counted rows at each of its
/// values, one line per value of the other axis when there are two axes (and at most
/// [`MAX_LINES`] values), one line over everything else otherwise; the rows that do not
/// count ([`counts`]) apart.
fn outcome_vs_axis(
    path: &Path,
    layout: &StudyLayout,
    records: &[CaseRecord],
    outcome: &str,
    k: usize,
) -> Result<(), PlotError> {
    let axis = &layout.axes[k];
    let other = (layout.axes.len() == 2)
        .then(|| &layout.axes[1 - k])
        .filter(|o| o.values.len() <= MAX_LINES);
    let counted: Vec<&CaseRecord> = records.iter().filter(|r| counts(r)).collect();
    let groups: Vec<(String, Vec<&CaseRecord>)> = match other {
        Some(o) => (0..o.values.len())
            .map(|v| {
                let rows = counted
                    .iter()
                    .copied()
                    .filter(|r| o.index_of(r) == Some(v))
                    .collect();
                let name = format!("{} = {}", label(&o.name), o.value_labels()[v]);
                (name, rows)
            })
            .collect(),
        None => vec![(String::new(), counted)],
    };
    let lines: Vec<Line> = groups
        .into_iter()
        .map(|(label, rows)| Line {
            label,
            points: axis_points(axis, &rows, outcome),
        })
        .collect();
    let stopped = stopped_cases(axis, records, outcome);
    let note = format!(
        "stopped early or lost the target ({}): not in the medians",
        stopped.len()
    );
    let x_axis = XAxis::of(axis);
    let chart = LineChart {
        title: format!("{} (median, box 25-75%, dot per case)", label(outcome)),
        x_axis: &x_axis,
        y_label: label(outcome),
        lines,
        stopped: (stopped, note),
    };
    draw_lines(path, &chart)
}

/// The median, quartiles and values of `outcome` over `rows` at each value of `axis`.
pub fn axis_points(axis: &AxisLayout, rows: &[&CaseRecord], outcome: &str) -> Vec<Point> {
    (0..axis.values.len())
        .filter_map(|v| {
            let values: Vec<f64> = rows
                .iter()
                .filter(|r| axis.index_of(r) == Some(v))
                .filter_map(|r| r.number(outcome))
                .collect();
            quartiles(&values).map(|[q1, median, q3]| Point {
                x: axis.x_of(v),
                median,
                spread: Some((q1, q3)),
                cases: values,
            })
        })
        .collect()
}

/// Where the cases that do not count sit: (x on `axis`, value of `outcome`).
pub fn stopped_cases(axis: &AxisLayout, records: &[CaseRecord], outcome: &str) -> Vec<(f64, f64)> {
    records
        .iter()
        .filter(|r| !counts(r))
        .filter_map(|r| Some((axis.x_of(axis.index_of(r)?), r.number(outcome)?)))
        .collect()
}

/// The empirical distribution of an outcome over every case.
fn distribution(path: &Path, records: &[CaseRecord], outcome: &str) -> Result<(), PlotError> {
    let mut values: Vec<f64> = records.iter().filter_map(|r| r.number(outcome)).collect();
    values.sort_by(f64::total_cmp);
    let n = values.len() as f64;
    let line = Line {
        label: format!("{} cases", values.len()),
        points: values
            .iter()
            .enumerate()
            .map(|(k, v)| Point {
                x: *v,
                median: (k + 1) as f64 / n,
                spread: None,
                cases: vec![],
            })
            .collect(),
    };
    let x_axis = XAxis {
        label: label(outcome),
        categories: None,
    };
    let chart = LineChart {
        title: format!("{}: fraction of cases at or below", label(outcome)),
        x_axis: &x_axis,
        y_label: "fraction of cases".into(),
        lines: vec![line],
        stopped: (vec![], String::new()),
    };
    draw_lines(path, &chart)
}

/// Which rows count towards a rate.
type RowTest<'a> = &'a dyn Fn(&CaseRecord) -> bool;

/// The fraction of runs that lost the target for good, and of runs that did not complete
/// (stopped early, diverged or failed), against each axis.
fn loss_rates(path: &Path, layout: &StudyLayout, records: &[CaseRecord]) -> Result<(), PlotError> {
    let rate = |rows: &[&CaseRecord], test: RowTest| {
        (!rows.is_empty())
            .then(|| rows.iter().filter(|r| test(r)).count() as f64 / rows.len() as f64)
    };
    let lost = |r: &CaseRecord| r.lost_target();
    let stopped = |r: &CaseRecord| !r.ended_ok();
    let tests: [(&str, RowTest); 2] = [
        ("lost the target", &lost),
        ("did not fly to the end", &stopped),
    ];
    for (k, axis) in layout.axes.iter().enumerate() {
        let lines: Vec<Line> = tests
            .iter()
            .map(|(label, test)| Line {
                label: label.to_string(),
                points: (0..axis.values.len())
                    .filter_map(|v| {
                        let rows: Vec<&CaseRecord> = records
                            .iter()
                            .filter(|r| axis.index_of(r) == Some(v))
                            .collect();
                        rate(&rows, test).map(|y| Point {
                            x: axis.x_of(v),
                            median: y,
                            spread: None,
                            cases: vec![],
                        })
                    })
                    .collect(),
            })
            .collect();
        let file = if k == 0 {
            path.to_path_buf()
        } else {
            path.with_file_name(format!("lost_target_rate_vs_{}.png", file_part(&axis.name)))
        };
        let x_axis = XAxis::of(axis);
        let chart = LineChart {
            title: format!("runs that lost the target, against {}", label(&axis.name)),
            x_axis: &x_axis,
            y_label: "fraction of runs".into(),
            lines,
            stopped: (vec![], String::new()),
        };
        draw_lines(&file, &chart)?;
    }
    Ok(())
}

/// The apparent-size study: the size the measured length implies over yaw and pitch, the
/// median over ranges, one map per roll.
fn apparent_size_maps(
    dir: &Path,
    layout: &StudyLayout,
    records: &[CaseRecord],
) -> Vec<Result<(), PlotError>> {
    let by_key = |key: &str| {
        layout
            .axes
            .iter()
            .find(|a| a.keys.len() == 1 && a.keys[0] == key)
    };
    let (Some(yaw), Some(pitch)) = (by_key("view.yaw_deg"), by_key("view.pitch_deg")) else {
        return vec![];
    };
    let rolls: Vec<(String, Vec<CaseRecord>)> = match by_key("view.roll_deg") {
        Some(roll) => (0..roll.values.len())
            .map(|v| {
                let rows = records
                    .iter()
                    .filter(|r| roll.index_of(r) == Some(v))
                    .cloned()
                    .collect();
                (roll.value_labels()[v].clone(), rows)
            })
            .collect(),
        None => vec![("0".to_string(), records.to_vec())],
    };
    rolls
        .iter()
        .map(|(roll, rows)| {
            let path = dir.join(format!("apparent_size_roll_{}.png", file_part(roll)));
            let title = format!(
                "size implied by the measured length, ft (median over ranges), roll {roll} deg"
            );
            heatmap(&path, &title, (yaw, pitch), rows, "size_measured_ft")
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::plots::PALETTE;
    use crate::render::image::CameraImage;
    use plotters::style::RGBColor;
    use serde_json::Value;

    fn hfov_axis() -> AxisLayout {
        AxisLayout {
            name: "camera.hfov_deg".into(),
            keys: vec!["camera.hfov_deg".into()],
            values: vec![vec!["30".into()], vec!["45".into()], vec!["60".into()]],
        }
    }

    /// A case at `hfov` with `rms` ft, its status, and whether it lost the target for good.
    fn case(hfov: &str, status: &str, lost: bool, rms: f64) -> CaseRecord {
        CaseRecord {
            case: 0,
            point: 0,
            replicate: 0,
            settings: vec![("camera.hfov_deg".into(), hfov.into())],
            status: status.into(),
            message: None,
            columns: vec![
                ("lost_target".into(), Value::Bool(lost)),
                ("rms_error_last20s_norm_ft".into(), Value::from(rms)),
            ],
        }
    }

    /// The three 30° runs of the field-of-view study that stop as lost after 5 s (175 ft
    /// off) are not in the medians; they are drawn apart, where they are.
    #[test]
    fn stopped_and_lost_cases_are_left_out_of_the_medians() {
        let records = [
            case("30", "lost", true, 175.0),
            case("30", "completed", true, 90.0),
            case("30", "completed", false, 2.0),
            case("45", "completed", false, 1.0),
            case("45", "completed", false, 3.0),
            case("60", "diverged", false, 50.0),
        ];
        let counted: Vec<&CaseRecord> = records.iter().filter(|r| counts(r)).collect();
        let points = axis_points(&hfov_axis(), &counted, "rms_error_last20s_norm_ft");
        let medians: Vec<(f64, f64)> = points.iter().map(|p| (p.x, p.median)).collect();
        assert_eq!(medians, [(30.0, 2.0), (45.0, 2.0)]);
        assert_eq!(points[1].spread, Some((1.5, 2.5)));
        let stopped = stopped_cases(&hfov_axis(), &records, "rms_error_last20s_norm_ft");
        assert_eq!(stopped, [(30.0, 175.0), (30.0, 90.0), (60.0, 50.0)]);
    }

    /// The plot's pixels, RGB, by column and row.
    fn read_png(path: &Path) -> (u32, u32, impl Fn(u32, u32) -> [u8; 3]) {
        let png = CameraImage::read_png(path).expect("plot written");
        let (w, h) = (png.width_px, png.height_px);
        let rgb = move |x, y| {
            let [r, g, b, _] = png.pixel(x, y).expect("inside the plot");
            [r, g, b]
        };
        (w, h, rgb)
    }

    /// The spread of a point is a box many pixels wide, not a hairline.
    #[test]
    fn spread_boxes_are_visible() {
        assert!(font_available(), "tests need DejaVu Sans");
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("lines.png");
        let records: Vec<CaseRecord> = [("30", 1.0), ("30", 3.0), ("45", 2.0), ("45", 6.0)]
            .iter()
            .map(|(h, v)| case(h, "completed", false, *v))
            .collect();
        let layout = StudyLayout {
            study: "s".into(),
            kind: StudyKind::Sweep,
            axes: vec![hfov_axis()],
            replicated: true,
            outcomes: None,
            cases: vec![],
            study_file: String::new(),
            scenario_file: String::new(),
        };
        outcome_vs_axis(&path, &layout, &records, "rms_error_last20s_norm_ft", 0).unwrap();
        let (width, height, pixel) = read_png(&path);
        // The boxes' fill: the line colour at a quarter over white.
        let RGBColor(r, g, b) = PALETTE[0];
        let fill = [r, g, b].map(|c| 0.25 * f64::from(c) + 0.75 * 255.0);
        let filled = |p: [u8; 3]| (0..3).all(|i| (f64::from(p[i]) - fill[i]).abs() < 3.0);
        let columns = (0..width)
            .filter(|x| (0..height).any(|y| filled(pixel(*x, y))))
            .count();
        // Two boxes of 70% of 80% of the spacing of the two values (~ 720 px apart).
        assert!(columns > 100, "{columns} columns carry a box");
    }

    /// A heat map has a colour scale: a column beside the grid runs through the colours of
    /// the scale from low to high (the grid alone shows one colour per cell).
    #[test]
    fn heat_maps_have_a_colour_scale() {
        assert!(font_available(), "tests need DejaVu Sans");
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("heat.png");
        let seeds = AxisLayout {
            name: "run.seed".into(),
            keys: vec!["run.seed".into()],
            values: vec![vec!["1".into()], vec!["2".into()]],
        };
        let records: Vec<CaseRecord> = (0..6)
            .map(|k| {
                let mut r = case(&hfov_axis().values[k % 3][0], "completed", false, k as f64);
                r.settings
                    .push(("run.seed".into(), (1 + k / 3).to_string()));
                r
            })
            .collect();
        let axes = (&hfov_axis(), &seeds);
        heatmap(&path, "t", axes, &records, "rms_error_last20s_norm_ft").unwrap();
        let (width, height, pixel) = read_png(&path);
        let on_scale = |p: &[u8; 3]| {
            (0..=100).any(|k| {
                let RGBColor(r, g, b) = heatmap::colour(f64::from(k) / 100.0);
                let d = |a: u8, b: u8| (i32::from(a) - i32::from(b)).abs();
                d(p[0], r) + d(p[1], g) + d(p[2], b) <= 6
            })
        };
        let best = (0..width)
            .map(|x| {
                let mut colours: Vec<[u8; 3]> = (0..height)
                    .map(|y| pixel(x, y))
                    .filter(|p| on_scale(p))
                    .collect();
                colours.sort_unstable();
                colours.dedup();
                colours.len()
            })
            .max()
            .unwrap();
        assert!(
            best >= 50,
            "at most {best} colours of the scale in one column"
        );
    }

    /// Ticks stepped in floating point print as the round numbers they are.
    #[test]
    fn tick_labels_are_short() {
        assert_eq!(tick_label(1.2000000000000002), "1.2");
        assert_eq!(tick_label(1.4000000000000001), "1.4");
        assert_eq!(tick_label(1920.0), "1920");
        assert_eq!(tick_label(-0.0000001), "0");
        assert_eq!(tick_label(0.25), "0.25");
    }
}
