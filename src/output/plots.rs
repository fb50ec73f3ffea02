//! `plots/*.png`: the seed's figure panels, drawn with plotters on a bitmap.

use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::FontStyle;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;
use text::{LegendEntry, Sample, TextLayout, draw_legend, draw_text};

pub mod text;

/// Why a figure could not be drawn.
#[derive(Debug, thiserror::Error)]
pub enum PlotError {
    /// No TrueType font to label axes with.
    #[error("plots need a TrueType font; install one: apt-get install -y fonts-dejavu-core")]
    NoFont,
    /// Drawing or writing the PNG failed.
    #[error("cannot draw {}: {source}", path.display())]
    Draw {
        /// The file (or the folder it goes in).
        path: PathBuf,
        /// What the drawing backend or the file system said.
        source: Box<dyn std::error::Error + Send + Sync>,
    },
    /// The drawn PNG could not be written (no part of it is left behind).
    #[error("cannot write {}: {}", path.display(), super::io_reason(source))]
    Write {
        /// The file.
        path: PathBuf,
        /// What the file system said.
        source: std::io::Error,
    },
}

impl PlotError {
    /// The file the error is about (None for a missing font).
    pub fn path(&self) -> Option<&Path> {
        match self {
            Self::NoFont => None,
            Self::Draw { path, .. } | Self::Write { path, .. } => Some(path),
        }
    }
}

/// Encodes an RGB `buffer` of `size` pixels as PNG into `path`; a file the disk does not take
/// whole is removed, so no cut-off image stays.
fn write_png(path: &Path, buffer: &[u8], size: (u32, u32)) -> Result<(), PlotError> {
    let mut png = Vec::new();
    let mut encoder = png::Encoder::new(&mut png, size.0, size.1);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_compression(png::Compression::Fast);
    encoder.set_filter(png::Filter::Adaptive);
    let mut writer = encoder.write_header().map_err(draw_error(path))?;
    writer.write_image_data(buffer).map_err(draw_error(path))?;
    writer.finish().map_err(draw_error(path))?;
    std::fs::write(path, &png).map_err(|source| {
        let _ = std::fs::remove_file(path);
        PlotError::Write {
            path: path.to_path_buf(),
            source,
        }
    })
}

/// Wraps a drawing or file-system error of the file (or folder) `path`.
pub fn draw_error<E: std::error::Error + Send + Sync + 'static>(
    path: &Path,
) -> impl Fn(E) -> PlotError + '_ {
    move |e| PlotError::Draw {
        path: path.to_path_buf(),
        source: Box::new(e),
    }
}

/// One curve of a panel.
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend text.
    pub label: String,
    /// Values, one per time sample.
    pub values: Vec<f64>,
    /// Colour.
    pub color: RGBColor,
    /// Stroke width, px.
    pub width_px: u32,
    /// Drawn dashed (so that a curve under it still shows).
    pub dashed: bool,
}

impl Series {
    /// A solid curve, 2 px wide, with a label and colour.
    pub fn new(label: impl Into<String>, values: Vec<f64>, color: RGBColor) -> Self {
        Self {
            label: label.into(),
            values,
            color,
            width_px: 2,
            dashed: false,
        }
    }

    /// The same curve dashed and `width_px` wide.
    pub fn dashed(self, width_px: u32) -> Self {
        Self {
            width_px,
            dashed: true,
            ..self
        }
    }

    /// Its legend entry.
    fn legend(&self) -> LegendEntry {
        LegendEntry {
            label: self.label.clone(),
            color: self.color,
            sample: Sample::Line {
                width_px: self.width_px,
                dashed: self.dashed,
            },
        }
    }
}

/// One panel (stacked vertically in a figure).
#[derive(Debug, Clone)]
pub struct Panel {
    /// Y-axis caption, with unit.
    pub y_label: String,
    /// Curves, drawn in order (the last on top).
    pub series: Vec<Series>,
    /// The y range shown (None: every value's range); values outside it are not drawn.
    pub y_range: Option<(f64, f64)>,
}

impl Panel {
    /// A panel showing every value of its curves.
    pub fn new(y_label: impl Into<String>, series: Vec<Series>) -> Self {
        Self {
            y_label: y_label.into(),
            series,
            y_range: None,
        }
    }
}

/// Line colours of a set of like curves (a study's cases, a group's aircraft), one palette
/// for every figure.
pub const PALETTE: [RGBColor; 8] = [
    RGBColor(20, 60, 200),
    RGBColor(210, 40, 40),
    RGBColor(20, 150, 60),
    RGBColor(240, 150, 0),
    RGBColor(120, 50, 170),
    RGBColor(0, 160, 170),
    RGBColor(120, 120, 120),
    RGBColor(170, 110, 40),
];

/// Colours for measured/true (blue) and command/reference (red) curves, and a third.
pub const TRUTH: RGBColor = RGBColor(20, 60, 200);
/// Command or reference curves.
pub const REFERENCE: RGBColor = RGBColor(210, 40, 40);
/// A third curve (e.g. a command with excitation).
pub const EXTRA: RGBColor = RGBColor(120, 120, 120);
/// A curve drawn over a noisy one (e.g. its moving mean).
pub const HIGHLIGHT: RGBColor = RGBColor(240, 150, 0);

/// The centred moving mean of `values` over `window` samples (shorter at the ends; NaN
/// samples are skipped).
pub fn moving_mean(values: &[f64], window: usize) -> Vec<f64> {
    let half = window / 2;
    (0..values.len())
        .map(|i| {
            let lo = i.saturating_sub(half);
            let hi = (i + half + 1).min(values.len());
            let (sum, n) = values[lo..hi]
                .iter()
                .filter(|v| v.is_finite())
                .fold((0.0, 0usize), |(s, n), v| (s + v, n + 1));
            if n == 0 { f64::NAN } else { sum / n as f64 }
        })
        .collect()
}

const FONT_PATHS: [&str; 4] = [
    "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/TTF/DejaVuSans.ttf",
    "/usr/share/fonts/truetype/liberation/LiberationSans-Regular.ttf",
];

/// Registers a system font with plotters once; false when none was found.
pub fn font_available() -> bool {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    *REGISTERED.get_or_init(|| {
        FONT_PATHS.iter().any(|path| {
            std::fs::read(path).ok().is_some_and(|bytes| {
                let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
                plotters::style::register_font("sans-serif", FontStyle::Normal, bytes).is_ok()
            })
        })
    })
}

/// Space right of a chart, px: half the widest x tick label ("140.0") and a little more,
/// so that the last tick's label is not cut off at the image's edge.
pub const RIGHT_MARGIN_PX: u32 = 32;

/// Space left of a chart for the y tick labels and the y-axis description, px.
const Y_LABEL_AREA_PX: u32 = 70;

/// Draws panels sharing the time axis `t_s` into a PNG.
pub fn draw_figure(
    path: &Path,
    title: &str,
    t_s: &[f64],
    panels: &[Panel],
) -> Result<(), PlotError> {
    if !font_available() {
        return Err(PlotError::NoFont);
    }
    let size = (1000, 60 + 260 * panels.len() as u32);
    draw_png(path, size, |root| {
        let root = root
            .clone()
            .titled(title, ("sans-serif", 24))
            .map_err(draw_error(path))?;
        let areas = root.split_evenly((panels.len(), 1));
        let t_end = t_s.last().copied().unwrap_or(1.0).max(1e-6);
        for (panel, area) in panels.iter().zip(areas.iter()) {
            let (lo, hi) = panel.y_range.unwrap_or_else(|| value_range(panel));
            let mut chart = ChartBuilder::on(area)
                .margin(10)
                .margin_right(RIGHT_MARGIN_PX)
                .x_label_area_size(35)
                .y_label_area_size(Y_LABEL_AREA_PX)
                .build_cartesian_2d(0.0..t_end, lo..hi)
                .map_err(draw_error(path))?;
            chart
                .configure_mesh()
                .x_desc("t, s")
                .light_line_style(WHITE.mix(0.0))
                .draw()
                .map_err(draw_error(path))?;
            for series in &panel.series {
                draw_curve(&mut chart, t_s, series, (lo, hi), path)?;
            }
            draw_y_description(area, &chart, &panel.y_label, path)?;
            let entries: Vec<LegendEntry> = panel.series.iter().map(Series::legend).collect();
            draw_legend(
                &chart.plotting_area().strip_coord_spec(),
                &entries,
                None,
                path,
            )?;
        }
        Ok(())
    })
}

/// Draws into `path`, a PNG of `size` px: `draw` draws on a white canvas in memory, which
/// is then written in one piece (see `write_png`).
pub fn draw_png(
    path: &Path,
    size: (u32, u32),
    draw: impl FnOnce(&DrawingArea<BitMapBackend, Shift>) -> Result<(), PlotError>,
) -> Result<(), PlotError> {
    let mut buffer = vec![0u8; 3 * size.0 as usize * size.1 as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buffer, size).into_drawing_area();
        root.fill(&WHITE).map_err(draw_error(path))?;
        draw(&root)?;
        root.present().map_err(draw_error(path))?;
    }
    write_png(path, &buffer, size)
}

/// A chart whose both axes are numbers.
pub type Chart<'a, 'b> =
    ChartContext<'a, BitMapBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// One curve, broken where a value is missing or outside `(lo, hi)` (so that it is not
/// drawn flattened along the chart's edge).
fn draw_curve(
    chart: &mut Chart,
    t_s: &[f64],
    series: &Series,
    (lo, hi): (f64, f64),
    path: &Path,
) -> Result<(), PlotError> {
    let style = series.color.stroke_width(series.width_px);
    for run in visible_runs(t_s, &series.values, (lo, hi)) {
        if series.dashed {
            chart
                .draw_series(DashedLineSeries::new(run, 10, 6, style))
                .map_err(draw_error(path))?;
        } else {
            chart
                .draw_series(LineSeries::new(run, style))
                .map_err(draw_error(path))?;
        }
    }
    Ok(())
}

/// The stretches of (t, value) with a value inside `(lo, hi)`.
pub fn visible_runs(t_s: &[f64], values: &[f64], (lo, hi): (f64, f64)) -> Vec<Vec<(f64, f64)>> {
    let mut runs = vec![Vec::new()];
    for (t, v) in t_s.iter().zip(values) {
        if v.is_finite() && (lo..=hi).contains(v) {
            if let Some(run) = runs.last_mut() {
                run.push((*t, *v));
            }
        } else if runs.last().is_some_and(|r| !r.is_empty()) {
            runs.push(Vec::new());
        }
    }
    runs.retain(|r| !r.is_empty());
    runs
}

/// The y-axis description, read upward, centred beside the chart's plotting area (drawn
/// here rather than by plotters, so that hats sit on their letters).
pub fn draw_y_description(
    area: &DrawingArea<BitMapBackend, plotters::coord::Shift>,
    chart: &Chart,
    label: &str,
    path: &Path,
) -> Result<(), PlotError> {
    let style = TextLayout {
        size_px: 13,
        upward: true,
    };
    let font = TextStyle::from(("sans-serif", style.size_px).into_font());
    let (width, _) = area
        .estimate_text_size(&text::split_hats(label).0, &font)
        .map_err(draw_error(path))?;
    let (area_x, area_y) = area.get_base_pixel();
    let (_, plot_y) = chart.plotting_area().get_pixel_range();
    let centre = (plot_y.start + plot_y.end) / 2 - area_y;
    let pos = (
        chart.plotting_area().get_pixel_range().0.start - area_x - Y_LABEL_AREA_PX as i32 + 4,
        centre + width as i32 / 2,
    );
    draw_text(area, label, pos, style, path)
}

/// The panel's finite value range with a 5% margin (and a minimum span).
fn value_range(panel: &Panel) -> (f64, f64) {
    let values = panel.series.iter().flat_map(|s| s.values.iter().copied());
    padded_range(values, 0.05)
}

/// The finite values' range widened by `margin` of its span each side (and a minimum span);
/// (-1, 1) without any.
pub fn padded_range(values: impl Iterator<Item = f64>, margin: f64) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if !lo.is_finite() {
        return (-1.0, 1.0);
    }
    let span = (hi - lo).max(1e-3 * hi.abs().max(1.0));
    (lo - margin * span, hi + margin * span)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::image::CameraImage;

    /// The last x tick's label (140.0 at the end of a 140 s run) is drawn whole: it ends
    /// inside the image, with white columns between it and the right edge.
    #[test]
    fn last_x_tick_label_is_not_cut_off() {
        assert!(font_available(), "tests need DejaVu Sans");
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("f.png");
        let t: Vec<f64> = (0..=1400).map(|k| f64::from(k) * 0.1).collect();
        let panel = Panel::new("y, ft", vec![Series::new("y", t.clone(), TRUTH)]);
        draw_figure(&path, "t", &t, &[panel]).unwrap();
        let png = CameraImage::read_png(&path).unwrap();
        let (w, h) = (png.width_px, png.height_px);
        let dark = |x: u32, y: u32| png.pixel(x, y).unwrap()[..3].iter().all(|c| *c < 128);
        let last_dark_column = (0..w).rev().find(|&x| (0..h).any(|y| dark(x, y))).unwrap();
        assert!(
            last_dark_column + 4 < w,
            "ink reaches column {last_dark_column} of {w}"
        );
        // The label row: under the plotting area, above the "t, s" description.
        let label_rows = h - 60..h - 25;
        let label_ink = (w - 45..w).any(|x| label_rows.clone().any(|y| dark(x, y)));
        assert!(label_ink, "no tick label near the right edge");
    }

    #[test]
    fn curves_break_outside_the_range() {
        let t = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0];
        let v = [1.0, 9.0, 1.5, f64::NAN, 2.0, 2.5];
        let runs = visible_runs(&t, &v, (0.0, 5.0));
        assert_eq!(
            runs,
            vec![
                vec![(0.0, 1.0)],
                vec![(2.0, 1.5)],
                vec![(4.0, 2.0), (5.0, 2.5)]
            ]
        );
    }

    #[test]
    fn moving_mean_is_centred() {
        let m = moving_mean(&[0.0, 3.0, 6.0, f64::NAN, 12.0], 3);
        assert_eq!(m[0], 1.5);
        assert_eq!(m[1], 3.0);
        assert_eq!(m[2], 4.5);
        assert_eq!(m[3], 9.0);
        assert_eq!(m[4], 12.0);
    }
}
