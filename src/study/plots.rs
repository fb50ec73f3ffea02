//! A study's `plots/*.png`: each outcome against each axis (the median over replicates and
//! the other axes, bars from the 25th to the 75th percentile), a heatmap of each outcome over
//! the first two axes, the rate of runs that lost the target or did not complete against
//! each axis, the distribution of each outcome when a study has no axes, and, for the
//! apparent-size study, the apparent size over yaw and pitch for each roll.

use super::layout::{AxisLayout, StudyLayout};
use super::results::CaseRecord;
use super::spec::StudyKind;
use crate::output::plots::text::{LegendEntry, Sample, draw_legend};
use crate::output::plots::{PlotError, draw_error, font_available};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

const PALETTE: [RGBColor; 8] = [
    RGBColor(20, 60, 200),
    RGBColor(210, 40, 40),
    RGBColor(20, 150, 60),
    RGBColor(240, 150, 0),
    RGBColor(120, 50, 170),
    RGBColor(0, 160, 170),
    RGBColor(120, 120, 120),
    RGBColor(170, 110, 40),
];

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
    let outcomes = layout.outcomes_to_plot(records, &mut warnings);
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
            let title = format!("{outcome} (median) over {} and {}", x.name, y.name);
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

/// A point of a line: x, the value (a median) and optional bars (low, high).
type Point = (f64, f64, Option<(f64, f64)>);

/// One line of a chart.
struct Line {
    label: String,
    points: Vec<Point>,
}

/// Which rows count towards a rate.
type RowTest<'a> = &'a dyn Fn(&CaseRecord) -> bool;

/// The x axis of a chart: numbers, or named categories at 0, 1, 2...
struct XAxis {
    label: String,
    categories: Option<Vec<String>>,
}

impl XAxis {
    fn of(axis: &AxisLayout) -> Self {
        Self {
            label: axis.name.clone(),
            categories: (!axis.is_numeric()).then(|| axis.value_labels()),
        }
    }

    fn format(&self, x: f64) -> String {
        match &self.categories {
            Some(names) if x >= -1e-9 && (x - x.round()).abs() < 1e-9 => {
                names.get(x.round() as usize).cloned().unwrap_or_default()
            }
            Some(_) => String::new(),
            None => tick_label(x),
        }
    }
}

/// A tick's number with at most six decimals and no trailing zeros: plotters' ticks are
/// round numbers stepped in floating point (1.2000000000000002 is 1.2).
fn tick_label(x: f64) -> String {
    let fixed = format!("{x:.6}");
    let trimmed = fixed.trim_end_matches('0').trim_end_matches('.');
    if trimmed == "-0" {
        "0".to_string()
    } else {
        trimmed.to_string()
    }
}

/// Draws lines with their bars on one chart.
fn draw_lines(
    path: &Path,
    title: &str,
    x_axis: &XAxis,
    y_label: &str,
    lines: &[Line],
) -> Result<(), PlotError> {
    let xs = lines.iter().flat_map(|l| l.points.iter().map(|p| p.0));
    let ys = lines.iter().flat_map(|l| {
        l.points.iter().flat_map(|p| {
            [p.1]
                .into_iter()
                .chain(p.2.map(|b| b.0))
                .chain(p.2.map(|b| b.1))
        })
    });
    let (x0, x1) = padded_range(xs, 0.05);
    let (y0, y1) = padded_range(ys, 0.08);
    let root = BitMapBackend::new(path, (900, 560)).into_drawing_area();
    root.fill(&WHITE).map_err(draw_error(path))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 22))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(75)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(draw_error(path))?;
    let format_x = |x: &f64| x_axis.format(*x);
    chart
        .configure_mesh()
        .x_desc(x_axis.label.as_str())
        .y_desc(y_label)
        .x_label_formatter(&format_x)
        .x_labels(x_axis.categories.as_ref().map_or(10, |c| c.len().max(2)))
        .light_line_style(WHITE.mix(0.0))
        .draw()
        .map_err(draw_error(path))?;
    for (k, line) in lines.iter().enumerate() {
        let color = PALETTE[k % PALETTE.len()];
        let points: Vec<(f64, f64)> = line.points.iter().map(|p| (p.0, p.1)).collect();
        chart
            .draw_series(LineSeries::new(points.clone(), color.stroke_width(2)))
            .map_err(draw_error(path))?
            .label(line.label.as_str())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
            });
        chart
            .draw_series(points.iter().map(|&p| Circle::new(p, 3, color.filled())))
            .map_err(draw_error(path))?;
        let bars = line
            .points
            .iter()
            .filter_map(|p| p.2.map(|(lo, hi)| (p.0, lo, hi)));
        chart
            .draw_series(
                bars.map(|(x, lo, hi)| {
                    PathElement::new(vec![(x, lo), (x, hi)], color.stroke_width(1))
                }),
            )
            .map_err(draw_error(path))?;
    }
    if lines.len() > 1 || lines.iter().any(|l| !l.label.is_empty()) {
        let entries: Vec<LegendEntry> = lines
            .iter()
            .enumerate()
            .map(|(k, l)| LegendEntry {
                label: l.label.clone(),
                color: PALETTE[k % PALETTE.len()],
                sample: Sample::Line {
                    width_px: 2,
                    dashed: false,
                },
            })
            .collect();
        draw_legend(&chart.plotting_area().strip_coord_spec(), &entries, path)?;
    }
    root.present().map_err(draw_error(path))
}

/// The finite values' range, widened by `margin` of its span each side (and never empty).
fn padded_range(values: impl Iterator<Item = f64>, margin: f64) -> (f64, f64) {
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

/// Outcome against axis `k`: the median and quartiles over the rows at each of its values,
/// one line per value of the other axis when there are two axes (and at most
/// [`MAX_LINES`] values), one line over everything else otherwise.
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
    let groups: Vec<(String, Vec<&CaseRecord>)> = match other {
        Some(o) => (0..o.values.len())
            .map(|v| {
                let rows = records
                    .iter()
                    .filter(|r| o.index_of(r) == Some(v))
                    .collect();
                (format!("{} = {}", o.name, o.value_labels()[v]), rows)
            })
            .collect(),
        None => vec![(String::new(), records.iter().collect())],
    };
    let lines: Vec<Line> = groups
        .into_iter()
        .map(|(label, rows)| Line {
            label,
            points: (0..axis.values.len())
                .filter_map(|v| {
                    let values: Vec<f64> = rows
                        .iter()
                        .filter(|r| axis.index_of(r) == Some(v))
                        .filter_map(|r| r.number(outcome))
                        .collect();
                    quartiles(&values)
                        .map(|[q1, median, q3]| (axis.x_of(v), median, Some((q1, q3))))
                })
                .collect(),
        })
        .collect();
    let title = format!("{outcome} against {} (median, 25-75%)", axis.name);
    draw_lines(path, &title, &XAxis::of(axis), outcome, &lines)
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
            .map(|(k, v)| (*v, (k + 1) as f64 / n, None))
            .collect(),
    };
    let x_axis = XAxis {
        label: outcome.to_string(),
        categories: None,
    };
    let title = format!("{outcome}: fraction of cases at or below");
    draw_lines(path, &title, &x_axis, "fraction of cases", &[line])
}

/// The fraction of runs that lost the target for good, and of runs that did not complete
/// (diverged or failed), against each axis.
fn loss_rates(path: &Path, layout: &StudyLayout, records: &[CaseRecord]) -> Result<(), PlotError> {
    let rate = |rows: &[&CaseRecord], test: RowTest| {
        (!rows.is_empty())
            .then(|| rows.iter().filter(|r| test(r)).count() as f64 / rows.len() as f64)
    };
    let lost = |r: &CaseRecord| r.lost_target();
    let stopped = |r: &CaseRecord| !r.ended_ok();
    let tests: [(&str, RowTest); 2] =
        [("lost the target", &lost), ("diverged or failed", &stopped)];
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
                        rate(&rows, test).map(|y| (axis.x_of(v), y, None))
                    })
                    .collect(),
            })
            .collect();
        let file = if k == 0 {
            path.to_path_buf()
        } else {
            path.with_file_name(format!("lost_target_rate_vs_{}.png", file_part(&axis.name)))
        };
        let title = format!("runs that lost the target, against {}", axis.name);
        draw_lines(&file, &title, &XAxis::of(axis), "fraction of runs", &lines)?;
    }
    Ok(())
}

/// The median of `outcome` in each cell of two axes, coloured and written in the cell.
fn heatmap(
    path: &Path,
    title: &str,
    (x_axis, y_axis): (&AxisLayout, &AxisLayout),
    records: &[CaseRecord],
    outcome: &str,
) -> Result<(), PlotError> {
    let (nx, ny) = (x_axis.values.len(), y_axis.values.len());
    let mut cells = vec![None; nx * ny];
    for (i, cell) in cells.iter_mut().enumerate() {
        let (x, y) = (i % nx, i / nx);
        let values: Vec<f64> = records
            .iter()
            .filter(|r| x_axis.index_of(r) == Some(x) && y_axis.index_of(r) == Some(y))
            .filter_map(|r| r.number(outcome))
            .collect();
        *cell = quartiles(&values).map(|q| q[1]);
    }
    let (lo, hi) = padded_range(cells.iter().flatten().copied(), 0.0);
    let root = BitMapBackend::new(path, (900, 700)).into_drawing_area();
    root.fill(&WHITE).map_err(draw_error(path))?;
    draw_cells(&root, path, title, (x_axis, y_axis), &cells, (lo, hi))?;
    root.present().map_err(draw_error(path))
}

/// The grid of [`heatmap`]: a cell per pair of values, blue (low) to yellow (high).
fn draw_cells(
    area: &DrawingArea<BitMapBackend, Shift>,
    path: &Path,
    title: &str,
    (x_axis, y_axis): (&AxisLayout, &AxisLayout),
    cells: &[Option<f64>],
    (lo, hi): (f64, f64),
) -> Result<(), PlotError> {
    let (nx, ny) = (x_axis.values.len(), y_axis.values.len());
    let (x_names, y_names) = (x_axis.value_labels(), y_axis.value_labels());
    let mut chart = ChartBuilder::on(area)
        .caption(title, ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(75)
        .build_cartesian_2d(-0.5..nx as f64 - 0.5, -0.5..ny as f64 - 0.5)
        .map_err(draw_error(path))?;
    let name = |names: &[String], v: f64| {
        names
            .get(v.round().max(0.0) as usize)
            .cloned()
            .unwrap_or_default()
    };
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(x_axis.name.as_str())
        .y_desc(y_axis.name.as_str())
        .x_labels(nx)
        .y_labels(ny)
        .x_label_formatter(&|v| name(&x_names, *v))
        .y_label_formatter(&|v| name(&y_names, *v))
        .draw()
        .map_err(draw_error(path))?;
    let colour = |v: f64| {
        let t = ((v - lo) / (hi - lo).max(1e-12)).clamp(0.0, 1.0);
        let mix = |a: f64, b: f64| (a + (b - a) * t).round() as u8;
        RGBColor(mix(30.0, 250.0), mix(40.0, 220.0), mix(140.0, 40.0))
    };
    let font_px = if nx * ny > 100 { 11 } else { 15 };
    for (i, value) in cells.iter().enumerate() {
        let (x, y) = ((i % nx) as f64, (i / nx) as f64);
        let Some(value) = value else { continue };
        let corners = [(x - 0.5, y - 0.5), (x + 0.5, y + 0.5)];
        chart
            .draw_series([Rectangle::new(corners, colour(*value).filled())])
            .map_err(draw_error(path))?;
        let text = format!("{:.3}", value);
        let style = ("sans-serif", font_px).into_font().color(&BLACK).pos(
            plotters::style::text_anchor::Pos::new(
                plotters::style::text_anchor::HPos::Center,
                plotters::style::text_anchor::VPos::Center,
            ),
        );
        chart
            .draw_series([Text::new(text, (x, y), style)])
            .map_err(draw_error(path))?;
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
    use super::tick_label;

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
