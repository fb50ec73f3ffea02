//! Makes a recorded track for `target.motion = "csv"` from a run's telemetry: the follower's
//! flown path (its position, velocity and 6-DOF attitude) or the target's, resampled.
//!
//! ```text
//! cargo run --release --example track_from_telemetry -- TELEMETRY.csv TRACK.csv \
//!     [--of follower|target] [--rate-hz 10] [--note "where the run came from"]
//! ```
//!
//! The track has the columns t_s, n_ft, e_ft, d_ft, vn_fps, ve_fps, vd_fps, phi_deg,
//! theta_deg, psi_deg (src/world/trajectory/recorded.rs reads them), one row every 1/rate s of
//! the telemetry's time (the telemetry row at or just after each instant), and starts with
//! comment lines saying what it was made from.

use anyhow::{Context, bail};
use std::io::Write;
use std::path::PathBuf;

/// Whose path the track is.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Whose {
    Follower,
    Target,
}

struct Options {
    telemetry: PathBuf,
    track: PathBuf,
    whose: Whose,
    rate_hz: f64,
    note: Option<String>,
}

fn options() -> anyhow::Result<Options> {
    let mut args = std::env::args().skip(1);
    let mut positional = Vec::new();
    let (mut whose, mut rate_hz, mut note) = (Whose::Follower, 10.0_f64, None);
    while let Some(arg) = args.next() {
        let mut value = || args.next().with_context(|| format!("{arg} needs a value"));
        match arg.as_str() {
            "--of" => {
                whose = match value()?.as_str() {
                    "follower" => Whose::Follower,
                    "target" => Whose::Target,
                    other => bail!("--of {other}: expected follower or target"),
                }
            }
            "--rate-hz" => rate_hz = value()?.parse().context("--rate-hz")?,
            "--note" => note = Some(value()?),
            _ => positional.push(PathBuf::from(arg)),
        }
    }
    let [telemetry, track] = <[PathBuf; 2]>::try_from(positional).map_err(|_| {
        anyhow::anyhow!("usage: track_from_telemetry TELEMETRY.csv TRACK.csv [--of follower|target] [--rate-hz 10] [--note TEXT]")
    })?;
    if !(rate_hz.is_finite() && rate_hz > 0.0) {
        bail!("--rate-hz {rate_hz}: expected a positive rate");
    }
    Ok(Options {
        telemetry,
        track,
        whose,
        rate_hz,
        note,
    })
}

/// The telemetry columns a track row is made of: position parts (summed, per axis),
/// velocity, attitude in radians.
fn sources(
    whose: Whose,
) -> (
    [&'static [&'static str]; 3],
    [&'static str; 3],
    [&'static str; 3],
) {
    match whose {
        Whose::Follower => (
            [&["fol_n_ft"], &["fol_e_ft"], &["fol_d_ft"]],
            ["fol_vn_fps", "fol_ve_fps", "fol_vd_fps"],
            ["phi_rad", "theta_rad", "psi_rad"],
        ),
        // R_T = R_F + R.
        Whose::Target => (
            [
                &["fol_n_ft", "rel_n_ft"],
                &["fol_e_ft", "rel_e_ft"],
                &["fol_d_ft", "rel_d_ft"],
            ],
            ["tgt_vn_fps", "tgt_ve_fps", "tgt_vd_fps"],
            ["tgt_phi_rad", "tgt_theta_rad", "tgt_psi_rad"],
        ),
    }
}

/// One track row (t_s, n, e, d, vn, ve, vd, φ, θ, ψ in degrees) of a telemetry record.
fn track_row(
    record: &csv::StringRecord,
    column: &dyn Fn(&str) -> anyhow::Result<usize>,
    whose: Whose,
) -> anyhow::Result<[f64; 10]> {
    let value = |name: &str| -> anyhow::Result<f64> {
        let text = record.get(column(name)?).unwrap_or("");
        text.parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .with_context(|| format!("{name} = `{text}` is not a number"))
    };
    let (position, velocity, attitude) = sources(whose);
    let mut row = [0.0; 10];
    row[0] = value("t_s")?;
    for axis in 0..3 {
        row[1 + axis] = position[axis]
            .iter()
            .map(|n| value(n))
            .sum::<anyhow::Result<f64>>()?;
        row[4 + axis] = value(velocity[axis])?;
        row[7 + axis] = value(attitude[axis])?.to_degrees();
    }
    Ok(row)
}

fn main() -> anyhow::Result<()> {
    let o = options()?;
    let mut reader = csv::Reader::from_path(&o.telemetry)
        .with_context(|| format!("reading {}", o.telemetry.display()))?;
    let header = reader.headers()?.clone();
    let column = |name: &str| {
        header
            .iter()
            .position(|h| h == name)
            .with_context(|| format!("{} has no column {name}", o.telemetry.display()))
    };
    let period_s = 1.0 / o.rate_hz;
    let mut rows = Vec::new();
    for record in reader.records() {
        let record = record?;
        let row = track_row(&record, &column, o.whose)?;
        // The telemetry's row at or just after each multiple of the period.
        if row[0] >= rows.len() as f64 * period_s - 1e-6 {
            rows.push(row);
        }
    }
    let mut out = std::io::BufWriter::new(std::fs::File::create(&o.track)?);
    let whose = match o.whose {
        Whose::Follower => "follower",
        Whose::Target => "target",
    };
    writeln!(
        out,
        "# made by examples/track_from_telemetry.rs: the {whose}'s flown path, every {period_s} s"
    )?;
    if let Some(note) = &o.note {
        writeln!(out, "# {note}")?;
    }
    writeln!(
        out,
        "t_s,n_ft,e_ft,d_ft,vn_fps,ve_fps,vd_fps,phi_deg,theta_deg,psi_deg"
    )?;
    for row in &rows {
        let fields: Vec<String> = row.iter().map(|x| format!("{x:.4}")).collect();
        writeln!(out, "{}", fields.join(","))?;
    }
    out.flush()?;
    eprintln!("{} rows written to {}", rows.len(), o.track.display());
    Ok(())
}
