//! Line charts of a study: per line, the median at each axis value with a box from the 25th
//! to the 75th percentile and a dot per case, and, apart, the cases left out of the medians
//! (runs that stopped early or lost the target) as red rings.

use super::super::layout::AxisLayout;
use super::labels::label;
use super::{padded_range, tick_label};
use crate::output::plots::text::{LegendEntry, Sample, draw_legend, legend_height_px};
use crate::output::plots::{Chart, PlotError, draw_error, draw_png, draw_y_description};
use plotters::prelude::*;
use std::path::Path;

use crate::output::plots::PALETTE;

/// The colour of the cases left out of the medians.
pub const STOPPED: RGBColor = RGBColor(220, 0, 0);

/// A point of a line: x, the median, the 25th and 75th percentiles when there is a spread,
/// and the value of each case counted.
#[derive(Debug, Clone, PartialEq)]
pub struct Point {
    /// Where it sits on the x axis.
    pub x: f64,
    /// The median (or the value).
    pub median: f64,
    /// The 25th and 75th percentiles.
    pub spread: Option<(f64, f64)>,
    /// Each case's value.
    pub cases: Vec<f64>,
}

/// One line of a chart.
#[derive(Debug, Clone, PartialEq)]
pub struct Line {
    /// Legend text (empty: no entry).
    pub label: String,
    /// Its points.
    pub points: Vec<Point>,
}

/// The x axis of a chart: numbers, or named categories at 0, 1, 2...
pub struct XAxis {
    /// Description, with unit.
    pub label: String,
    /// Category names (None: numbers).
    pub categories: Option<Vec<String>>,
}

impl XAxis {
    /// The axis of a study axis.
    pub fn of(axis: &AxisLayout) -> Self {
        Self {
            label: label(&axis.name),
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

/// What one chart shows.
pub struct LineChart<'a> {
    /// Title.
    pub title: String,
    /// The x axis.
    pub x_axis: &'a XAxis,
    /// The y-axis description.
    pub y_label: String,
    /// The lines.
    pub lines: Vec<Line>,
    /// The cases left out of the lines (x, value), with the legend's words for them.
    pub stopped: (Vec<(f64, f64)>, String),
}

/// How far each line's points are moved sideways so that their boxes do not overlap, and
/// the boxes' half width, in x units: the lines share 40% of the smallest spacing of the x
/// values, a box taking 80% of its share.
pub fn dodge(lines: &[Line]) -> (f64, f64) {
    let mut xs: Vec<f64> = lines
        .iter()
        .flat_map(|l| l.points.iter().map(|p| p.x))
        .collect();
    xs.sort_by(f64::total_cmp);
    xs.dedup();
    let spacing = xs
        .windows(2)
        .map(|w| w[1] - w[0])
        .fold(f64::INFINITY, f64::min);
    let spacing = if spacing.is_finite() { spacing } else { 1.0 };
    let share = 0.4 * spacing / lines.len().max(1) as f64;
    (share, 0.4 * share)
}

/// The y range: the lines' medians, boxes and cases (the stopped cases only when there is
/// nothing else, so that one far-off case does not flatten the rest).
fn y_range(chart: &LineChart) -> (f64, f64) {
    let counted = chart.lines.iter().flat_map(|l| {
        l.points.iter().flat_map(|p| {
            [p.median]
                .into_iter()
                .chain(p.spread.map(|s| s.0))
                .chain(p.spread.map(|s| s.1))
                .chain(p.cases.iter().copied())
        })
    });
    let counted: Vec<f64> = counted.collect();
    if counted.iter().any(|v| v.is_finite()) {
        padded_range(counted.into_iter(), 0.08)
    } else {
        padded_range(chart.stopped.0.iter().map(|p| p.1), 0.08)
    }
}

/// Draws a [`LineChart`] into `path`.
pub fn draw_lines(path: &Path, chart_spec: &LineChart) -> Result<(), PlotError> {
    let lines = &chart_spec.lines;
    let xs = lines
        .iter()
        .flat_map(|l| l.points.iter().map(|p| p.x))
        .chain(chart_spec.stopped.0.iter().map(|p| p.0));
    let (x0, x1) = padded_range(xs, 0.05);
    let (y0, y1) = y_range(chart_spec);
    let n_entries = lines.iter().filter(|l| !l.label.is_empty()).count()
        + usize::from(!chart_spec.stopped.0.is_empty());
    let legend_px = if n_entries > 0 {
        legend_height_px(n_entries) + 8
    } else {
        0
    };
    draw_png(path, (900, 560 + legend_px), |image| {
        let (root, below) = image.split_vertically(560);
        let mut chart = ChartBuilder::on(&root)
            .caption(&chart_spec.title, ("sans-serif", 20))
            .margin(12)
            .margin_right(30)
            .x_label_area_size(45)
            .y_label_area_size(75)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(draw_error(path))?;
        let x_axis = chart_spec.x_axis;
        let format_x = |x: &f64| x_axis.format(*x);
        chart
            .configure_mesh()
            .x_desc(x_axis.label.as_str())
            .x_label_formatter(&format_x)
            .x_labels(x_axis.categories.as_ref().map_or(10, |c| c.len().max(2)))
            .light_line_style(WHITE.mix(0.0))
            .draw()
            .map_err(draw_error(path))?;
        let has_boxes = lines
            .iter()
            .any(|l| l.points.iter().any(|p| p.spread.is_some()));
        let (share, half) = if has_boxes { dodge(lines) } else { (0.0, 0.0) };
        let mut entries = Vec::new();
        for (k, line) in lines.iter().enumerate() {
            let color = PALETTE[k % PALETTE.len()];
            let shift = share * (k as f64 - 0.5 * (lines.len() as f64 - 1.0));
            draw_line(&mut chart, line, color, (shift, half), path)?;
            if !line.label.is_empty() {
                entries.push(LegendEntry {
                    label: line.label.clone(),
                    color,
                    sample: Sample::Line {
                        width_px: 2,
                        dashed: false,
                    },
                });
            }
        }
        if !chart_spec.stopped.0.is_empty() {
            draw_stopped(&mut chart, &chart_spec.stopped.0, (y0, y1), path)?;
            entries.push(LegendEntry {
                label: chart_spec.stopped.1.clone(),
                color: STOPPED,
                sample: Sample::Ring,
            });
        }
        draw_y_description(&root, &chart, &chart_spec.y_label, path)?;
        // Under the chart, where it hides no case.
        draw_legend(&below, &entries, Some((87, 0)), path)
    })
}

/// One line: its medians joined, and at each point a box from the 25th to the 75th
/// percentile (`half` wide each side) and a dot per case, all moved by `shift`.
fn draw_line(
    chart: &mut Chart,
    line: &Line,
    color: RGBColor,
    (shift, half): (f64, f64),
    path: &Path,
) -> Result<(), PlotError> {
    let medians: Vec<(f64, f64)> = line
        .points
        .iter()
        .map(|p| (p.x + shift, p.median))
        .collect();
    chart
        .draw_series(LineSeries::new(medians.clone(), color.stroke_width(2)))
        .map_err(draw_error(path))?;
    for p in &line.points {
        let x = p.x + shift;
        if let Some((q1, q3)) = p.spread {
            let corners = [(x - half, q1), (x + half, q3)];
            chart
                .draw_series([
                    Rectangle::new(corners, color.mix(0.25).filled()),
                    Rectangle::new(corners, color.stroke_width(2)),
                ])
                .map_err(draw_error(path))?;
        }
        let dots = p
            .cases
            .iter()
            .map(|v| Circle::new((x, *v), 2, color.mix(0.6).filled()));
        chart.draw_series(dots).map_err(draw_error(path))?;
    }
    chart
        .draw_series(medians.iter().map(|&m| Circle::new(m, 4, color.filled())))
        .map_err(draw_error(path))?;
    Ok(())
}

/// The stopped cases as red rings; one outside the y range sits on its edge with its value.
fn draw_stopped(
    chart: &mut Chart,
    stopped: &[(f64, f64)],
    (y0, y1): (f64, f64),
    path: &Path,
) -> Result<(), PlotError> {
    for &(x, v) in stopped {
        let y = v.clamp(y0, y1);
        chart
            .draw_series([Circle::new((x, y), 5, STOPPED.stroke_width(2))])
            .map_err(draw_error(path))?;
        if y != v {
            let arrow = if v > y1 { "↑" } else { "↓" };
            let text = format!("{arrow} {}", tick_label((v * 10.0).round() / 10.0));
            let style = ("sans-serif", 12).into_font().color(&STOPPED);
            chart
                .draw_series([Text::new(text, (x, y), style)])
                .map_err(draw_error(path))?;
        }
    }
    Ok(())
}
