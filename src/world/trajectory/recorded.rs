//! `target.motion = "csv"` (docs/equations.md, Trajectory sources for the target): a
//! recorded track played back. The file is CSV with a header naming its columns: `t_s`,
//! `n_ft`, `e_ft`, `d_ft`, optionally `vn_fps`, `ve_fps`, `vd_fps` (the velocity; all three
//! or none) and `phi_deg`, `theta_deg`, `psi_deg` (the attitude; all three or none), in any
//! order; blank lines and lines starting with `#` are skipped. Times strictly increase; the
//! run starts at the first row, which is moved to `target.initial_position_ft` (the track's
//! shape, not its place, is what is recorded). Velocities not given are the finite
//! differences of the positions, and accelerations those of the velocities; the track is
//! interpolated between rows as a [`SampledTrack`]. Every flaw is an error naming the file
//! and its line.

use super::sampled::{Knot, SampledTrack};
use crate::frames::{EulerAngles, Vec3};
use std::path::{Path, PathBuf};

/// Largest track file, bytes (64 MiB, as a mesh): about a million rows.
const MAX_TRACK_BYTES: u64 = 64 << 20;
const TIME: &str = "t_s";
const POSITION: [&str; 3] = ["n_ft", "e_ft", "d_ft"];
const VELOCITY: [&str; 3] = ["vn_fps", "ve_fps", "vd_fps"];
const ATTITUDE: [&str; 3] = ["phi_deg", "theta_deg", "psi_deg"];

/// Why a track could not be used.
#[derive(Debug, thiserror::Error)]
pub enum TrackError {
    /// The file could not be read.
    #[error("{}: cannot read the track: {source}", path.display())]
    Unreadable {
        /// The file.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// The file is larger than [`MAX_TRACK_BYTES`].
    #[error("{}: the track has {bytes} bytes, above the limit of {MAX_TRACK_BYTES}", path.display())]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// Its size.
        bytes: u64,
    },
    /// A line of the file is wrong, or the track as a whole (then at its last line).
    #[error("{}:{line}: {message}", path.display())]
    Invalid {
        /// The file.
        path: PathBuf,
        /// The line, from 1.
        line: usize,
        /// What is wrong and what is allowed.
        message: String,
    },
}

/// One row of a track.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Row {
    line: usize,
    t_s: f64,
    position_ned_ft: Vec3,
    velocity_ned_fps: Option<Vec3>,
    attitude: Option<EulerAngles>,
}

/// Where each column is in a row.
#[derive(Debug, Clone, PartialEq)]
struct Columns {
    names: Vec<String>,
    time: usize,
    position: [usize; 3],
    velocity: Option<[usize; 3]>,
    attitude: Option<[usize; 3]>,
}

/// A failure at a line: the line and the message.
type LineError = (usize, String);

impl Columns {
    /// The header's columns: the required ones present, each known and named once, each
    /// optional group whole or absent.
    fn of(header: &str) -> Result<Self, String> {
        let names: Vec<String> = header.split(',').map(|n| n.trim().to_string()).collect();
        let known = [&[TIME][..], &POSITION, &VELOCITY, &ATTITUDE].concat();
        for (i, name) in names.iter().enumerate() {
            if !known.contains(&name.as_str()) {
                return Err(format!(
                    "unknown column `{name}`: allowed {}",
                    known.join(", ")
                ));
            }
            if names[..i].contains(name) {
                return Err(format!("column `{name}` appears twice"));
            }
        }
        let find = |name: &str| names.iter().position(|n| n == name);
        let group = |group: [&str; 3], required: bool| -> Result<Option<[usize; 3]>, String> {
            let found = group.map(find);
            if !required && found.iter().all(Option::is_none) {
                return Ok(None);
            }
            match found.iter().position(Option::is_none) {
                Some(i) => Err(format!(
                    "missing column `{}` (columns {} come together)",
                    group[i],
                    group.join(", ")
                )),
                None => Ok(Some(found.map(|i| i.unwrap_or_default()))),
            }
        };
        let time = find(TIME).ok_or_else(|| format!("missing column `{TIME}`"))?;
        let position = group(POSITION, true)?.unwrap_or_default();
        Ok(Self {
            time,
            position,
            velocity: group(VELOCITY, false)?,
            attitude: group(ATTITUDE, false)?,
            names,
        })
    }

    /// A data line's values, each a finite number.
    fn row(&self, line: usize, text: &str) -> Result<Row, String> {
        let fields: Vec<&str> = text.split(',').map(str::trim).collect();
        if fields.len() != self.names.len() {
            return Err(format!(
                "{} fields, but the header names {} columns",
                fields.len(),
                self.names.len()
            ));
        }
        let mut values = Vec::with_capacity(fields.len());
        for (field, name) in fields.iter().zip(&self.names) {
            match field.parse::<f64>() {
                Ok(x) if x.is_finite() => values.push(x),
                _ => return Err(format!("{name} = `{field}` is not a finite number")),
            }
        }
        let vector = |at: [usize; 3]| Vec3::new(values[at[0]], values[at[1]], values[at[2]]);
        let attitude = self.attitude.map(|at| {
            let deg = vector(at);
            EulerAngles::new(deg.x.to_radians(), deg.y.to_radians(), deg.z.to_radians())
        });
        if let Some(a) = attitude.filter(|a| a.theta_rad.abs() > std::f64::consts::FRAC_PI_2) {
            let theta_deg = a.theta_rad.to_degrees();
            return Err(format!("theta_deg = {theta_deg} is outside [-90, 90]"));
        }
        Ok(Row {
            line,
            t_s: values[self.time],
            position_ned_ft: vector(self.position),
            velocity_ned_fps: self.velocity.map(vector),
            attitude,
        })
    }
}

/// The rows of a track's text, each checked, times strictly increasing, at least two, and
/// spanning at least `duration_s`.
fn parse(text: &str, duration_s: f64) -> Result<Vec<Row>, LineError> {
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
    let (header_line, header) = lines.next().ok_or((
        1,
        format!(
            "no header line: expected columns {TIME}, {}",
            POSITION.join(", ")
        ),
    ))?;
    let columns = Columns::of(header).map_err(|m| (header_line, m))?;
    let mut rows: Vec<Row> = Vec::new();
    for (line, text) in lines {
        let row = columns.row(line, text).map_err(|m| (line, m))?;
        if let Some(previous) = rows.last().filter(|p| row.t_s <= p.t_s) {
            let message = format!(
                "t_s = {} is not after the previous row's {} (line {})",
                row.t_s, previous.t_s, previous.line
            );
            return Err((line, message));
        }
        rows.push(row);
    }
    let last_line = rows.last().map_or(header_line, |r| r.line);
    if rows.len() < 2 {
        let message = format!("the track has {} row(s); at least 2 are needed", rows.len());
        return Err((last_line, message));
    }
    let span_s = rows[rows.len() - 1].t_s - rows[0].t_s;
    if span_s < duration_s {
        let message = format!(
            "the track covers {span_s} s (t_s {} to {}), shorter than run.duration_s = \
             {duration_s} s",
            rows[0].t_s,
            rows[rows.len() - 1].t_s
        );
        return Err((last_line, message));
    }
    Ok(rows)
}

/// The derivative of `values` at `times`: second-order finite differences (central on the
/// uneven grid inside, one-sided at the ends; first order with two points).
fn derivatives(times: &[f64], values: &[Vec3]) -> Vec<Vec3> {
    let n = times.len();
    if n == 2 {
        let slope = (values[1] - values[0]) / (times[1] - times[0]);
        return vec![slope; 2];
    }
    // The three-point derivative at `at` (0, 1 or 2) of the points i, i+1, i+2.
    let three = |i: usize, at: usize| {
        let (t0, t1, t2) = (times[i], times[i + 1], times[i + 2]);
        let t = [t0, t1, t2][at];
        // The derivative of the Lagrange basis of each point at t.
        let w0 = ((t - t1) + (t - t2)) / ((t0 - t1) * (t0 - t2));
        let w1 = ((t - t0) + (t - t2)) / ((t1 - t0) * (t1 - t2));
        let w2 = ((t - t0) + (t - t1)) / ((t2 - t0) * (t2 - t1));
        values[i] * w0 + values[i + 1] * w1 + values[i + 2] * w2
    };
    (0..n)
        .map(|j| match j {
            0 => three(0, 0),
            j if j == n - 1 => three(n - 3, 2),
            j => three(j - 1, 1),
        })
        .collect()
}

/// The knots of parsed rows, the first moved to `start`, and their attitudes if recorded.
fn knots_of(rows: &[Row], start: Vec3) -> (Vec<Knot>, Option<Vec<EulerAngles>>) {
    let (t0, p0) = (rows[0].t_s, rows[0].position_ned_ft);
    let times: Vec<f64> = rows.iter().map(|r| r.t_s - t0).collect();
    let positions: Vec<Vec3> = rows
        .iter()
        .map(|r| r.position_ned_ft - p0 + start)
        .collect();
    let velocities: Vec<Vec3> = match rows.iter().map(|r| r.velocity_ned_fps).collect() {
        Some(given) => given,
        None => derivatives(&times, &positions),
    };
    let accels = derivatives(&times, &velocities);
    let knots = (0..rows.len())
        .map(|i| Knot {
            t_s: times[i],
            position_ned_ft: positions[i],
            velocity_ned_fps: velocities[i],
            accel_ned_fps2: accels[i],
        })
        .collect();
    (knots, rows.iter().map(|r| r.attitude).collect())
}

/// The track in the CSV file `path`, starting at `start` (R_T(0), NED, ft) and covering at
/// least `duration_s`.
pub fn read_track(path: &Path, start: Vec3, duration_s: f64) -> Result<SampledTrack, TrackError> {
    let unreadable = |source| TrackError::Unreadable {
        path: path.to_path_buf(),
        source,
    };
    let bytes = std::fs::metadata(path).map_err(unreadable)?.len();
    if bytes > MAX_TRACK_BYTES {
        return Err(TrackError::TooLarge {
            path: path.to_path_buf(),
            bytes,
        });
    }
    let text = std::fs::read_to_string(path).map_err(unreadable)?;
    let invalid = |(line, message): LineError| TrackError::Invalid {
        path: path.to_path_buf(),
        line,
        message,
    };
    let rows = parse(&text, duration_s).map_err(invalid)?;
    let (knots, attitudes) = knots_of(&rows, start);
    SampledTrack::new(knots, attitudes).ok_or_else(|| {
        invalid((
            rows[rows.len() - 1].line,
            "the track's times are not increasing".into(),
        ))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str =
        "# a comment\nt_s, n_ft, e_ft, d_ft\n0, 0, 0, 0\n\n1, 10, 0, 0\n2, 20, 0, 1\n";

    fn error(text: &str) -> LineError {
        parse(text, 1.0).unwrap_err()
    }

    #[test]
    fn good_track_parses() {
        let rows = parse(GOOD, 2.0).unwrap();
        assert_eq!(rows.len(), 3);
        assert_eq!(rows[2].line, 6);
        assert_eq!(rows[2].position_ned_ft, Vec3::new(20.0, 0.0, 1.0));
    }

    /// Each flaw is reported at its line.
    #[test]
    fn flaws_name_their_line() {
        let (line, m) = error("t_s,n_ft,e_ft,d_ft\n0,0,0,0\n2,0,0,0\n1,0,0,0\n");
        assert_eq!(line, 4, "{m}");
        assert!(m.contains("not after"), "{m}");
        let (line, m) = error("t_s,n_ft,e_ft,d_ft\n0,0,0,0\n1,nan,0,0\n");
        assert!(line == 3 && m.contains("n_ft = `nan`"), "{m}");
        let (line, m) = error("t_s,n_ft,e_ft,d_ft\n0,0,0,0\n1,0,x,0\n");
        assert!(line == 3 && m.contains("e_ft = `x`"), "{m}");
        let (line, m) = error("t_s,n_ft,d_ft\n0,0,0\n1,0,0\n");
        assert!(line == 1 && m.contains("missing column `e_ft`"), "{m}");
        let (line, m) = error("t_s,n_ft,e_ft,d_ft,vn_fps\n0,0,0,0,1\n1,0,0,0,1\n");
        assert!(line == 1 && m.contains("`ve_fps`"), "{m}");
        let (line, m) = error("t_s,n_ft,e_ft,d_ft\n0,0,0,0\n");
        assert!(line == 2 && m.contains("1 row(s)"), "{m}");
        let (line, m) = error("t_s,n_ft,e_ft,d_ft\n0,0,0,0\n0.5,0,0,0\n");
        assert!(
            line == 3 && m.contains("shorter than run.duration_s = 1"),
            "{m}"
        );
        let (line, m) = error("t_s,n_ft,e_ft,d_ft,x\n");
        assert!(line == 1 && m.contains("unknown column `x`"), "{m}");
        let (line, m) = error("t_s,n_ft,e_ft,d_ft\n0,0,0\n");
        assert!(line == 2 && m.contains("3 fields"), "{m}");
        assert_eq!(error("# nothing\n").0, 1);
    }

    /// The finite differences are exact for quadratics, on an uneven grid too.
    #[test]
    fn derivatives_exact_for_quadratics() {
        let times = [0.0, 0.3, 1.0, 1.1, 2.5];
        let f = |t: f64| Vec3::new(t * t, 3.0 * t - 1.0, -0.5 * t * t + t);
        let df = |t: f64| Vec3::new(2.0 * t, 3.0, -t + 1.0);
        let values: Vec<Vec3> = times.iter().map(|t| f(*t)).collect();
        for (t, d) in times.iter().zip(derivatives(&times, &values)) {
            assert!((d - df(*t)).norm() < 1e-12, "t {t}: {d:?}");
        }
    }

    /// The first row is moved to the start and the rest with it.
    #[test]
    fn track_starts_at_start() {
        let rows = parse(GOOD, 2.0).unwrap();
        let start = Vec3::new(200.0, 50.0, 30.0);
        let (knots, attitudes) = knots_of(&rows, start);
        assert_eq!(knots[0].position_ned_ft, start);
        assert_eq!(knots[2].position_ned_ft, start + Vec3::new(20.0, 0.0, 1.0));
        assert!(attitudes.is_none());
    }
}
