//! Text on plots with real hats (b̂, d̂) and the legend box that uses it.
//!
//! The plotters font renderer places each glyph at its pen position without its side
//! bearing and without mark positioning, so a combining circumflex (U+0302) lands after its
//! letter, where it reads as `b^`. Here the letters are drawn without their marks and each
//! hat is drawn as a chevron centred over its letter, above the letter's ascender.

use super::{PlotError, draw_error};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::FontTransform;
use std::path::Path;

/// The combining circumflex that marks an estimate (b̂).
const COMBINING_HAT: char = '\u{0302}';

/// `text` without its combining hats, and the char positions (in the text returned) of the
/// letters that carry one.
pub fn split_hats(text: &str) -> (String, Vec<usize>) {
    let mut plain = String::with_capacity(text.len());
    let mut hats = Vec::new();
    let mut count = 0usize;
    for c in text.chars() {
        if c == COMBINING_HAT {
            if count > 0 {
                hats.push(count - 1);
            }
        } else {
            plain.push(c);
            count += 1;
        }
    }
    (plain, hats)
}

/// Text as [`draw_text`] draws it: size and direction.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TextLayout {
    /// Font size, px.
    pub size_px: u32,
    /// Read bottom to top (a y-axis description) instead of left to right.
    pub upward: bool,
}

/// Draws `text` in black with its top-left corner (in reading direction) at `pos`, each
/// hatted letter with a chevron over it.
pub fn draw_text<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    text: &str,
    pos: (i32, i32),
    style: TextLayout,
    path: &Path,
) -> Result<(), PlotError>
where
    DB::ErrorType: 'static,
{
    let (plain, hats) = split_hats(text);
    let transform = if style.upward {
        FontTransform::Rotate270
    } else {
        FontTransform::None
    };
    let font = ("sans-serif", style.size_px).into_font();
    let font = font.transform(transform.clone());
    area.draw(&Text::new(plain.clone(), pos, font.color(&BLACK)))
        .map_err(draw_error(path))?;
    let size = f64::from(style.size_px);
    let flat = plotters::style::TextStyle::from(("sans-serif", style.size_px).into_font());
    let width_of = |s: &str| {
        area.estimate_text_size(s, &flat)
            .map(|(w, _)| f64::from(w))
            .map_err(draw_error(path))
    };
    for k in hats {
        let before: String = plain.chars().take(k).collect();
        let letter: String = plain.chars().skip(k).take(1).collect();
        let (x0, w) = (width_of(&before)?, width_of(&letter)?);
        // Glyph-local coordinates: x along the text, y down. The renderer draws a glyph's
        // ink from the pen position (without its left side bearing), about 0.77 of its
        // advance wide, with the baseline half the size below `pos` and an ascender's top
        // 0.65 of the size above it.
        let (top, rise) = (size * (0.5 - 0.72), 0.18 * size);
        let centre = x0 + 0.385 * w;
        let half = (0.25 * w).max(2.0);
        let local = [
            (centre - half, top),
            (centre, top - rise),
            (centre + half, top),
        ];
        let points: Vec<(i32, i32)> = local
            .iter()
            .map(|&(x, y)| {
                let (dx, dy) = transform.transform(x.round() as i32, y.round() as i32);
                (pos.0 + dx, pos.1 + dy)
            })
            .collect();
        let stroke = BLACK.stroke_width((style.size_px / 12).max(1));
        area.draw(&PathElement::new(points, stroke))
            .map_err(draw_error(path))?;
    }
    Ok(())
}

/// How a legend entry's sample is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Sample {
    /// A line of this width, px; dashed when `dashed`.
    Line {
        /// Stroke width, px.
        width_px: u32,
        /// Dashed.
        dashed: bool,
    },
    /// A filled circle.
    Dot,
    /// A hollow circle (e.g. a case that stopped early).
    Ring,
}

/// One legend entry: its text, colour and sample.
#[derive(Debug, Clone, PartialEq)]
pub struct LegendEntry {
    /// Text (hats allowed).
    pub label: String,
    /// Colour.
    pub color: RGBColor,
    /// Sample drawn beside the text.
    pub sample: Sample,
}

const LEGEND_FONT_PX: u32 = 13;
const ROW_PX: i32 = 18;
const SAMPLE_PX: i32 = 24;

/// The height of a legend of `entries` entries, px.
pub fn legend_height_px(entries: usize) -> u32 {
    (ROW_PX * entries as i32 + 10) as u32
}

/// Draws the legend box in the top right corner of `plot` (a chart's plotting area), or
/// with its top left corner at `at`.
pub fn draw_legend<DB: DrawingBackend>(
    plot: &DrawingArea<DB, Shift>,
    entries: &[LegendEntry],
    at: Option<(i32, i32)>,
    path: &Path,
) -> Result<(), PlotError>
where
    DB::ErrorType: 'static,
{
    if entries.is_empty() {
        return Ok(());
    }
    let font = plotters::style::TextStyle::from(("sans-serif", LEGEND_FONT_PX).into_font());
    let mut text_w = 0;
    for entry in entries {
        let (w, _) = plot
            .estimate_text_size(&split_hats(&entry.label).0, &font)
            .map_err(draw_error(path))?;
        text_w = text_w.max(w as i32);
    }
    let (plot_w, _) = plot.dim_in_pixel();
    let box_w = SAMPLE_PX + text_w + 24;
    let box_h = legend_height_px(entries.len()) as i32;
    let (x0, y0) = at.unwrap_or((plot_w as i32 - box_w - 8, 8));
    let frame = [(x0, y0), (x0 + box_w, y0 + box_h)];
    plot.draw(&Rectangle::new(frame, WHITE.mix(0.85).filled()))
        .map_err(draw_error(path))?;
    plot.draw(&Rectangle::new(frame, BLACK.stroke_width(1)))
        .map_err(draw_error(path))?;
    for (k, entry) in entries.iter().enumerate() {
        let y = y0 + 6 + ROW_PX * k as i32;
        draw_sample(plot, entry, (x0 + 6, y + ROW_PX / 2 - 1), path)?;
        let style = TextLayout {
            size_px: LEGEND_FONT_PX,
            upward: false,
        };
        draw_text(plot, &entry.label, (x0 + 12 + SAMPLE_PX, y), style, path)?;
    }
    Ok(())
}

/// A legend entry's sample with its left end at `(x, y)`.
fn draw_sample<DB: DrawingBackend>(
    plot: &DrawingArea<DB, Shift>,
    entry: &LegendEntry,
    (x, y): (i32, i32),
    path: &Path,
) -> Result<(), PlotError>
where
    DB::ErrorType: 'static,
{
    let color = entry.color;
    let centre = (x + SAMPLE_PX / 2, y);
    let result = match entry.sample {
        Sample::Line { width_px, dashed } => {
            let ends = vec![(x, y), (x + SAMPLE_PX, y)];
            let style = color.stroke_width(width_px);
            if dashed {
                plot.draw(&plotters::element::DashedPathElement::new(
                    ends, 6, 3, style,
                ))
            } else {
                plot.draw(&PathElement::new(ends, style))
            }
        }
        Sample::Dot => plot.draw(&Circle::new(centre, 4, color.filled())),
        Sample::Ring => plot.draw(&Circle::new(centre, 5, color.stroke_width(2))),
    };
    result.map_err(draw_error(path))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The columns and rows of the dark pixels of `text` drawn at (10, 30) at 26 px.
    fn ink(text: &str) -> (Vec<usize>, Vec<usize>) {
        assert!(super::super::font_available(), "tests need DejaVu Sans");
        let (w, h) = (80usize, 60usize);
        let mut buffer = vec![255u8; w * h * 3];
        {
            let area =
                BitMapBackend::with_buffer(&mut buffer, (w as u32, h as u32)).into_drawing_area();
            let style = TextLayout {
                size_px: 26,
                upward: false,
            };
            draw_text(&area, text, (10, 30), style, Path::new("test")).unwrap();
            area.present().unwrap();
        }
        let dark: Vec<(usize, usize)> = (0..w * h)
            .filter(|i| buffer[3 * i] < 128)
            .map(|i| (i % w, i / w))
            .collect();
        (
            dark.iter().map(|p| p.0).collect(),
            dark.iter().map(|p| p.1).collect(),
        )
    }

    /// b̂ is b with a hat over it: its ink spans b's columns (the hat does not trail
    /// after the letter, as `b^`), centred within a pixel or two, and reaches above b.
    #[test]
    fn hat_sits_over_its_letter() {
        let (b_x, b_y) = ink("b");
        let (hat_x, hat_y) = ink("b̂");
        let range = |v: &[usize]| (*v.iter().min().unwrap(), *v.iter().max().unwrap());
        let ((b0, b1), (h0, h1)) = (range(&b_x), range(&hat_x));
        eprintln!("b columns {b0}..{b1}, b̂ columns {h0}..{h1}");
        assert!(h0 >= b0 && h1 <= b1, "hat outside b's columns");
        let hat_top_x: Vec<usize> = hat_x
            .iter()
            .zip(&hat_y)
            .filter(|(_, y)| **y < range(&b_y).0)
            .map(|(x, _)| *x)
            .collect();
        assert!(!hat_top_x.is_empty(), "no hat above b");
        let (t0, t1) = range(&hat_top_x);
        let centre_offset = (t0 + t1) as f64 / 2.0 - (b0 + b1) as f64 / 2.0;
        assert!(
            centre_offset.abs() <= 2.0,
            "hat off centre by {centre_offset} px"
        );
        assert!(range(&hat_y).0 + 2 < range(&b_y).0, "hat not above b");
    }

    #[test]
    fn hats_are_split_from_their_letters() {
        assert_eq!(
            split_hats("b̂ d̂ (estimate)"),
            ("b d (estimate)".to_string(), vec![0, 2])
        );
        assert_eq!(split_hats("‖d̂‖"), ("‖d‖".to_string(), vec![1]));
        assert_eq!(split_hats("R_c"), ("R_c".to_string(), vec![]));
    }
}
