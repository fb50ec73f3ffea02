//! Heat maps: the median of an outcome in each cell of two axes, its value written in the
//! cell, beside a colour scale that says which colour is which value.

use super::super::layout::AxisLayout;
use super::super::results::CaseRecord;
use super::labels::label;
use super::lines::STOPPED;
use super::{counts, padded_range, quartiles, tick_label};
use crate::output::plots::{PlotError, draw_error, draw_png, draw_y_description};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::Path;

/// Width of the colour scale's part of the image, px.
const SCALE_AREA_PX: u32 = 150;

/// The colour of `t` in 0..1: blue (low) to yellow (high).
pub fn colour(t: f64) -> RGBColor {
    let t = t.clamp(0.0, 1.0);
    let mix = |a: f64, b: f64| (a + (b - a) * t).round() as u8;
    RGBColor(mix(30.0, 250.0), mix(40.0, 220.0), mix(140.0, 40.0))
}

/// One cell of a heat map: the median over the cases that count, and how many did not.
#[derive(Debug, Clone, Copy, Default)]
struct Cell {
    median: Option<f64>,
    left_out: usize,
}

/// The median of `outcome` in each cell of two axes over the cases that count (those that
/// stopped early or lost the target are left out, and their number written in the cell),
/// coloured and written in the cell, and the colour scale.
pub fn heatmap(
    path: &Path,
    title: &str,
    (x_axis, y_axis): (&AxisLayout, &AxisLayout),
    records: &[CaseRecord],
    outcome: &str,
) -> Result<(), PlotError> {
    let (nx, ny) = (x_axis.values.len(), y_axis.values.len());
    let mut cells = vec![Cell::default(); nx * ny];
    for (i, cell) in cells.iter_mut().enumerate() {
        let (x, y) = (i % nx, i / nx);
        let rows = records
            .iter()
            .filter(|r| x_axis.index_of(r) == Some(x) && y_axis.index_of(r) == Some(y));
        let (counted, left_out): (Vec<&CaseRecord>, Vec<&CaseRecord>) =
            rows.partition(|r| counts(r));
        let values: Vec<f64> = counted.iter().filter_map(|r| r.number(outcome)).collect();
        *cell = Cell {
            median: quartiles(&values).map(|q| q[1]),
            left_out: left_out.len(),
        };
    }
    let (lo, hi) = padded_range(cells.iter().filter_map(|c| c.median), 0.0);
    draw_png(path, (900 + SCALE_AREA_PX, 700), |root| {
        let (grid, scale) = root.split_horizontally(900);
        draw_cells(&grid, path, title, (x_axis, y_axis), &cells, (lo, hi))?;
        draw_scale(&scale, path, &label(outcome), (lo, hi))
    })
}

/// The colour scale: a bar from `lo` (bottom) to `hi` (top) with its values.
fn draw_scale(
    area: &DrawingArea<BitMapBackend, Shift>,
    path: &Path,
    outcome_label: &str,
    (lo, hi): (f64, f64),
) -> Result<(), PlotError> {
    let hi = if hi > lo { hi } else { lo + 1.0 };
    let mut chart = ChartBuilder::on(area)
        .margin_top(50)
        .margin_bottom(57)
        .margin_right(10)
        .y_label_area_size(90)
        .build_cartesian_2d(0.0..1.0, lo..hi)
        .map_err(draw_error(path))?;
    let format = |v: &f64| tick_label(*v);
    chart
        .configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .y_label_style(("sans-serif", 13))
        .y_label_formatter(&format)
        .draw()
        .map_err(draw_error(path))?;
    const STEPS: usize = 200;
    let step = (hi - lo) / STEPS as f64;
    chart
        .draw_series((0..STEPS).map(|k| {
            let v0 = lo + step * k as f64;
            let t = (k as f64 + 0.5) / STEPS as f64;
            Rectangle::new([(0.0, v0), (1.0, v0 + step)], colour(t).filled())
        }))
        .map_err(draw_error(path))?;
    draw_y_description(area, &chart, outcome_label, path)
}

/// The grid of [`heatmap`]: a cell per pair of values, blue (low) to yellow (high).
fn draw_cells(
    area: &DrawingArea<BitMapBackend, Shift>,
    path: &Path,
    title: &str,
    (x_axis, y_axis): (&AxisLayout, &AxisLayout),
    cells: &[Cell],
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
    let (x_label, y_label) = (label(&x_axis.name), label(&y_axis.name));
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(x_label.as_str())
        .x_labels(nx)
        .y_labels(ny)
        .x_label_formatter(&|v| name(&x_names, *v))
        .y_label_formatter(&|v| name(&y_names, *v))
        .draw()
        .map_err(draw_error(path))?;
    draw_y_description(area, &chart, &y_label, path)?;
    let font_px = if nx * ny > 100 { 11 } else { 15 };
    for (i, cell) in cells.iter().enumerate() {
        let (x, y) = ((i % nx) as f64, (i / nx) as f64);
        let centre = Pos::new(HPos::Center, VPos::Center);
        if let Some(value) = cell.median {
            let corners = [(x - 0.5, y - 0.5), (x + 0.5, y + 0.5)];
            let t = (value - lo) / (hi - lo).max(1e-12);
            let style = ("sans-serif", font_px)
                .into_font()
                .color(&BLACK)
                .pos(centre);
            chart
                .draw_series([
                    Rectangle::new(corners, colour(t).filled()).into_dyn(),
                    Text::new(format!("{value:.3}"), (x, y), style).into_dyn(),
                ])
                .map_err(draw_error(path))?;
        }
        if cell.left_out > 0 {
            let style = ("sans-serif", font_px)
                .into_font()
                .color(&STOPPED)
                .pos(centre);
            let text = format!("{} left out", cell.left_out);
            chart
                .draw_series([Text::new(text, (x, y - 0.25), style)])
                .map_err(draw_error(path))?;
        }
    }
    Ok(())
}
