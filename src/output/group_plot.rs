//! `formation.png` of a group run: every aircraft's track seen from above (north up, east
//! right), with the formation drawn as it stood every 20 s (each follower joined to the
//! aircraft it tracks).

use super::plots::{PALETTE, PlotError, draw_png, font_available};
use crate::sim::group::Group;
use plotters::prelude::*;
use std::path::Path;

/// Seconds between the formation's drawn instants.
const SNAPSHOT_EVERY_S: f64 = 20.0;
/// The plot's size, px.
const SIZE_PX: (u32, u32) = (1000, 1000);

/// A named track: (east, north) points, ft.
struct Track {
    name: String,
    points: Vec<(f64, f64)>,
    /// The instant of each point, s.
    t_s: Vec<f64>,
}

/// The tracks of the targets and then of the followers.
fn tracks(group: &Group) -> Vec<Track> {
    let dt_log_s = group.members()[0].sim.scenario().run.dt_s
        * f64::from(group.members()[0].sim.scenario().run.log_every);
    let mut out: Vec<Track> = (group.target_names().into_iter().enumerate())
        .map(|(i, name)| Track {
            name: name.to_string(),
            points: (group.target_tracks().iter())
                .map(|at| (at[i].y, at[i].x))
                .collect(),
            t_s: (0..group.target_tracks().len())
                .map(|k| k as f64 * dt_log_s)
                .collect(),
        })
        .collect();
    for m in group.members() {
        out.push(Track {
            name: m.name.clone(),
            points: (m.logged.iter())
                .map(|s| (s.follower_position_ned_ft.y, s.follower_position_ned_ft.x))
                .collect(),
            t_s: m.logged.iter().map(|s| s.t_s).collect(),
        });
    }
    out
}

/// The point of `track` nearest in time to `t_s`.
fn at(track: &Track, t_s: f64) -> Option<(f64, f64)> {
    let i = track.t_s.partition_point(|t| *t < t_s);
    track
        .points
        .get(i.min(track.points.len().saturating_sub(1)))
        .copied()
}

/// Draws `formation.png` into `path`.
pub fn draw_formation(path: &Path, group: &Group) -> Result<(), PlotError> {
    if !font_available() {
        return Err(PlotError::NoFont);
    }
    let draw_error = |e: &dyn std::fmt::Display| PlotError::Draw {
        path: path.to_path_buf(),
        source: e.to_string().into(),
    };
    let tracks = tracks(group);
    let all = tracks.iter().flat_map(|t| t.points.iter());
    let (e_lo, e_hi, n_lo, n_hi) = all.fold(
        (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ),
        |(a, b, c, d), &(e, n)| (a.min(e), b.max(e), c.min(n), d.max(n)),
    );
    let pad = 0.05 * (e_hi - e_lo).max(n_hi - n_lo).max(10.0);
    draw_png(path, SIZE_PX, |root| {
        let mut chart = ChartBuilder::on(root)
            .caption("formation from above", ("sans-serif", 24))
            .margin(20)
            .x_label_area_size(40)
            .y_label_area_size(70)
            .build_cartesian_2d(e_lo - pad..e_hi + pad, n_lo - pad..n_hi + pad)
            .map_err(|e| draw_error(&e))?;
        chart
            .configure_mesh()
            .x_desc("east, ft")
            .y_desc("north, ft")
            .draw()
            .map_err(|e| draw_error(&e))?;
        for (k, track) in tracks.iter().enumerate() {
            let colour = PALETTE[k % PALETTE.len()];
            chart
                .draw_series(LineSeries::new(track.points.iter().copied(), colour))
                .map_err(|e| draw_error(&e))?
                .label(track.name.clone())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], colour));
        }
        draw_links(&mut chart, group, &tracks).map_err(|e| draw_error(&e))?;
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()
            .map_err(|e| draw_error(&e))
    })
}

type FormationChart<'a> = ChartContext<
    'a,
    BitMapBackend<'a>,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;

/// Every [`SNAPSHOT_EVERY_S`]: a dot at each aircraft and a line from each follower to the
/// aircraft it tracks.
fn draw_links(
    chart: &mut FormationChart,
    group: &Group,
    tracks: &[Track],
) -> Result<(), Box<dyn std::error::Error>> {
    let end_s = group.time_s();
    let targets = group.target_names().len();
    let mut t_s = 0.0;
    while t_s <= end_s {
        for (j, m) in group.members().iter().enumerate() {
            let leader = tracks.iter().position(|t| t.name == m.tracks);
            let (Some(me), Some(them)) = (
                at(&tracks[targets + j], t_s),
                leader.and_then(|i| at(&tracks[i], t_s)),
            ) else {
                continue;
            };
            chart.draw_series(LineSeries::new([me, them], BLACK.mix(0.5)))?;
            chart.draw_series([me, them].map(|p| Circle::new(p, 3, BLACK.filled())))?;
        }
        t_s += SNAPSHOT_EVERY_S;
    }
    Ok(())
}
