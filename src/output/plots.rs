//! `plots/*.png`: the seed's figure panels, drawn with plotters on a bitmap.

use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::FontStyle;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

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
    use image::ImageEncoder;
    let mut png = Vec::new();
    image::codecs::png::PngEncoder::new(&mut png)
        .write_image(buffer, size.0, size.1, image::ExtendedColorType::Rgb8)
        .map_err(draw_error(path))?;
    std::fs::write(path, &png).map_err(|source| {
        let _ = std::fs::remove_file(path);
        PlotError::Write {
            path: path.to_path_buf(),
            source,
        }
    })
}

/// The chart's legend, top right on a half-white box: the same on every figure.
pub fn draw_legend<'a, DB: DrawingBackend + 'a>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    path: &Path,
) -> Result<(), PlotError>
where
    DB::ErrorType: 'static,
{
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(draw_error(path))
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
}

impl Series {
    /// A curve with a label and colour.
    pub fn new(label: impl Into<String>, values: Vec<f64>, color: RGBColor) -> Self {
        Self {
            label: label.into(),
            values,
            color,
        }
    }
}

/// One panel (stacked vertically in a figure).
#[derive(Debug, Clone)]
pub struct Panel {
    /// Y-axis caption, with unit.
    pub y_label: String,
    /// Curves.
    pub series: Vec<Series>,
}

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
    // Drawn in memory and written in one piece (see `write_png`).
    let mut buffer = vec![0u8; 3 * size.0 as usize * size.1 as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buffer, size).into_drawing_area();
        root.fill(&WHITE).map_err(draw_error(path))?;
        let root = root
            .titled(title, ("sans-serif", 24))
            .map_err(draw_error(path))?;
        let areas = root.split_evenly((panels.len(), 1));
        let t_end = t_s.last().copied().unwrap_or(1.0).max(1e-6);
        for (panel, area) in panels.iter().zip(areas.iter()) {
            let (lo, hi) = value_range(panel);
            let mut chart = ChartBuilder::on(area)
                .margin(10)
                .x_label_area_size(35)
                .y_label_area_size(70)
                .build_cartesian_2d(0.0..t_end, lo..hi)
                .map_err(draw_error(path))?;
            chart
                .configure_mesh()
                .x_desc("t, s")
                .y_desc(panel.y_label.as_str())
                .light_line_style(WHITE.mix(0.0))
                .draw()
                .map_err(draw_error(path))?;
            for series in &panel.series {
                let color = series.color;
                let points = t_s
                    .iter()
                    .zip(&series.values)
                    .filter(|(_, v)| v.is_finite())
                    .map(|(t, v)| (*t, *v));
                chart
                    .draw_series(LineSeries::new(points, color.stroke_width(2)))
                    .map_err(draw_error(path))?
                    .label(series.label.as_str())
                    .legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                    });
            }
            draw_legend(&mut chart, path)?;
        }
        root.present().map_err(draw_error(path))?;
    }
    write_png(path, &buffer, size)
}

/// The panel's finite value range with a 5% margin (and a minimum span).
fn value_range(panel: &Panel) -> (f64, f64) {
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    for v in panel
        .series
        .iter()
        .flat_map(|s| s.values.iter())
        .filter(|v| v.is_finite())
    {
        lo = lo.min(*v);
        hi = hi.max(*v);
    }
    if !lo.is_finite() {
        return (-1.0, 1.0);
    }
    let span = (hi - lo).max(1e-3 * hi.abs().max(1.0));
    (lo - 0.05 * span, hi + 0.05 * span)
}

#[cfg(test)]
mod tests {
    use super::*;

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
