//! `telemetry.csv`: one row per logged tick, written as the run goes so that a run that stops
//! early keeps what it logged.

use crate::estimation::{TargetEstimate, TargetMotionEstimate};
use crate::follower::AircraftActuation;
use crate::frames::{EulerAngles, Vec3, wrap_angle_rad};
use crate::guidance::signals::{AccelerationGuidanceOutput, FollowerCommand};
use crate::sim::Snapshot;
use crate::vision::{BlobStatus, ImageMeasurement};
use std::fs::File;
use std::io::{Seek, SeekFrom, Write};
use std::path::Path;

/// One telemetry row: column names and values, in column order.
pub type Row = Vec<(&'static str, f64)>;

/// Appends a 3-vector under three names.
fn push3(row: &mut Row, names: [&'static str; 3], v: &Vec3) {
    row.extend(names.into_iter().zip(v.iter().copied()));
}

/// The named values of one telemetry row, in column order.
pub fn row_of(s: &Snapshot) -> Row {
    let mut row = Vec::with_capacity(96);
    truth_columns(s, &mut row);
    guidance_columns(s, &mut row);
    camera_columns(s, &mut row);
    if let FollowerCommand::Acceleration(_) = s.guidance.command {
        row.extend(acceleration_columns(s.guidance.acceleration.as_ref()));
    }
    if let Some(aircraft) = &s.aircraft {
        row.extend(aircraft_columns(aircraft));
    }
    if let Some(filter) = &s.filter {
        filter_columns(filter, &mut row);
    }
    if let Some(g) = &s.gimbal {
        row.push(("gimbal_pan_rad", g.angles.pan_rad));
        row.push(("gimbal_tilt_rad", g.angles.tilt_rad));
        row.push(("gimbal_pan_cmd_rad", g.command.pan_rad));
        row.push(("gimbal_tilt_cmd_rad", g.command.tilt_rad));
    }
    row
}

/// The Kalman filter's estimate (runs with a filter, flying on it or beside the adaptive law;
/// empty cells before its first measurement).
fn filter_columns(f: &Option<TargetEstimate>, row: &mut Row) {
    let none = Vec3::repeat(f64::NAN);
    row.push(("kf_b_hat_ft", f.map_or(f64::NAN, |f| f.b_hat_ft)));
    row.push(("kf_b_sigma_ft", f.map_or(f64::NAN, |f| f.b_sigma_ft)));
    push3(
        row,
        ["kf_r_x", "kf_r_y", "kf_r_z"],
        &f.map_or(none, |f| f.r),
    );
    let d = f.map_or(none, |f| f.d_per_s);
    push3(row, ["kf_d_x_per_s", "kf_d_y_per_s", "kf_d_z_per_s"], &d);
    let a = f.map_or(none, |f| f.a_per_s2);
    push3(row, ["kf_a_x_per_s2", "kf_a_y_per_s2", "kf_a_z_per_s2"], &a);
}

/// Time, relative position, target and follower states.
fn truth_columns(s: &Snapshot, row: &mut Row) {
    row.push(("t_s", s.t_s));
    let attitude = |a: &EulerAngles| Vec3::new(a.phi_rad, a.theta_rad, a.psi_rad);
    let target = &s.target;
    #[rustfmt::skip]
    let groups: [([&'static str; 3], Vec3); 7] = [
        (["rel_n_ft", "rel_e_ft", "rel_d_ft"], s.relative_ned_ft),
        (["tgt_vn_fps", "tgt_ve_fps", "tgt_vd_fps"], target.velocity_ned_fps),
        (["tgt_an_fps2", "tgt_ae_fps2", "tgt_ad_fps2"], target.accel_ned_fps2),
        (["tgt_phi_rad", "tgt_theta_rad", "tgt_psi_rad"], attitude(&target.attitude)),
        (["fol_n_ft", "fol_e_ft", "fol_d_ft"], s.follower_position_ned_ft),
        (["fol_vn_fps", "fol_ve_fps", "fol_vd_fps"], s.follower_velocity_ned_fps),
        (["phi_rad", "theta_rad", "psi_rad"], attitude(&s.follower_attitude)),
    ];
    for (names, v) in groups {
        push3(row, names, &v);
    }
}

/// Command, excitation, estimates, the r the guidance was given and the scaled command.
fn guidance_columns(s: &Snapshot, row: &mut Row) {
    push3(row, ["cmd_n_ft", "cmd_e_ft", "cmd_d_ft"], &s.command_ned_ft);
    push3(
        row,
        ["cmd_exc_n_ft", "cmd_exc_e_ft", "cmd_exc_d_ft"],
        &s.excited_command_ned_ft,
    );
    row.push(("excitation_amp", s.excitation_amplitude));
    row.push(("b_hat_ft", s.b_hat_ft));
    // d̂ is a scaled velocity (1/s) in the velocity law, a filtered acceleration bound (ft/s)
    // in the acceleration law: the column names carry the law's unit.
    let d_names = match s.target_motion {
        TargetMotionEstimate::ScaledVelocity(_) => {
            ["d_hat_x_per_s", "d_hat_y_per_s", "d_hat_z_per_s"]
        }
        TargetMotionEstimate::FilteredAccelerationBound(_) => {
            ["d_hat_x_fps", "d_hat_y_fps", "d_hat_z_fps"]
        }
    };
    push3(row, d_names, &s.target_motion.vector());
    let none = Vec3::repeat(f64::NAN);
    push3(
        row,
        ["r_meas_x", "r_meas_y", "r_meas_z"],
        &s.r_measured.unwrap_or(none),
    );
    push3(
        row,
        ["r_cmd_x", "r_cmd_y", "r_cmd_z"],
        &s.guidance.r_command,
    );
}

/// The last camera frame: its time, measurement, status and truth (empty cells without one).
fn camera_columns(s: &Snapshot, row: &mut Row) {
    let image = |m: Option<ImageMeasurement>| {
        m.map_or(Vec3::repeat(f64::NAN), |m| {
            Vec3::new(m.y_i_px, m.z_i_px, m.b_i_px)
        })
    };
    row.push(("frame_t_s", s.frame.map_or(f64::NAN, |f| f.t_s)));
    push3(
        row,
        ["y_i_px", "z_i_px", "b_i_px"],
        &image(s.frame.and_then(|f| f.measured)),
    );
    let status = s.frame.map_or(f64::NAN, |f| status_code(f.status));
    row.push(("meas_status", status));
    let truth = image(s.frame.and_then(|f| f.truth));
    push3(row, ["y_i_true_px", "z_i_true_px", "b_i_true_px"], &truth);
}

/// The 6-DOF follower's columns (appended to its runs' rows): air data, body rates, actuator
/// positions, the V_F the autopilot flies, its references V_c, V_m, γ_c, φ_c, θ_c, ψ_c, the
/// filtered rate commands ω_f, the actuator commands and the gust (seed Figs 7.1-7.13).
fn aircraft_columns(a: &AircraftActuation) -> Vec<(&'static str, f64)> {
    let air = &a.air_data;
    let out = &a.autopilot;
    let p = &a.actuators;
    let c = &out.controls;
    let [vcn, vce, vcd] = [0, 1, 2].map(|i| a.velocity_cmd_ned_fps[i]);
    let [pf, qf, rf] = [0, 1, 2].map(|i| out.rate_cmd_filtered_rps[i]);
    let [gu, gv, gw] = [0, 1, 2].map(|i| a.gust_body_fps[i]);
    vec![
        ("airspeed_fps", air.airspeed_fps),
        ("alpha_rad", air.alpha_rad),
        ("beta_rad", air.beta_rad),
        ("p_rps", air.body_rates_rps.x),
        ("q_rps", air.body_rates_rps.y),
        ("r_rps", air.body_rates_rps.z),
        ("throttle", p.throttle),
        ("elevator_rad", p.elevator_rad),
        ("aileron_rad", p.aileron_rad),
        ("rudder_rad", p.rudder_rad),
        ("vf_cmd_n_fps", vcn),
        ("vf_cmd_e_fps", vce),
        ("vf_cmd_d_fps", vcd),
        ("airspeed_cmd_fps", out.airspeed_cmd_fps),
        ("airspeed_ref_fps", out.airspeed_ref_fps),
        ("flight_path_cmd_rad", out.flight_path_cmd_rad),
        ("phi_cmd_rad", out.euler_cmd.phi_rad),
        ("theta_cmd_rad", out.euler_cmd.theta_rad),
        ("psi_cmd_rad", wrap_angle_rad(out.euler_cmd.psi_rad)),
        ("p_cmd_rps", pf),
        ("q_cmd_rps", qf),
        ("r_cmd_rps", rf),
        ("throttle_cmd", c.throttle),
        ("elevator_cmd_rad", c.elevator_rad),
        ("aileron_cmd_rad", c.aileron_rad),
        ("rudder_cmd_rad", c.rudder_rad),
        ("gust_u_fps", gu),
        ("gust_v_fps", gv),
        ("gust_w_fps", gw),
    ]
}

/// The acceleration law's signals (appended to its runs' rows, empty cells when the law gave
/// none): a_F (5.38), the reference model's and the observer's outputs y_m and C ẑ, the
/// combined output y_a, the virtual control w_f and b̂'.
fn acceleration_columns(a: Option<&AccelerationGuidanceOutput>) -> Vec<(&'static str, f64)> {
    let v = |f: fn(&AccelerationGuidanceOutput) -> crate::frames::Vec3| {
        a.map_or([f64::NAN; 3], |a| {
            let x = f(a);
            [x.x, x.y, x.z]
        })
    };
    let [an, ae, ad] = v(|a| a.accel_cmd_ned_fps2);
    let [mx, my, mz] = v(|a| a.y_model);
    let [ox, oy, oz] = v(|a| a.y_observer);
    let [yx, yy, yz] = v(|a| a.y_combined);
    let [wx, wy, wz] = v(|a| a.virtual_control_fps);
    vec![
        ("fol_an_fps2", an),
        ("fol_ae_fps2", ae),
        ("fol_ad_fps2", ad),
        ("y_model_x", mx),
        ("y_model_y", my),
        ("y_model_z", mz),
        ("y_observer_x", ox),
        ("y_observer_y", oy),
        ("y_observer_z", oz),
        ("y_a_x", yx),
        ("y_a_y", yy),
        ("y_a_z", yz),
        ("w_f_x_fps", wx),
        ("w_f_y_fps", wy),
        ("w_f_z_fps", wz),
        ("b_hat_rate_fps", a.map_or(f64::NAN, |a| a.b_hat_rate_fps)),
    ]
}

/// `meas_status` codes: 0 ok, 1 not found, 2 truncated (touches the border), 3 too small.
pub fn status_code(status: BlobStatus) -> f64 {
    match status {
        BlobStatus::Ok => 0.0,
        BlobStatus::NotFound => 1.0,
        BlobStatus::Truncated => 2.0,
        BlobStatus::TooSmall => 3.0,
    }
}

/// Rows are handed to the file in blocks of about this many bytes.
const BLOCK_BYTES: usize = 64 * 1024;

/// Where telemetry goes: a file that can be cut back to a length.
pub trait RowSink: Write {
    /// Cuts the sink back to its first `len` bytes and continues writing there.
    fn truncate_to(&mut self, len: u64) -> std::io::Result<()>;
}

impl RowSink for File {
    fn truncate_to(&mut self, len: u64) -> std::io::Result<()> {
        self.set_len(len)?;
        self.seek(SeekFrom::Start(len)).map(|_| ())
    }
}

/// Streams rows to a CSV file (formatted by the `csv` crate); the header is the first row's
/// names. Rows are gathered in blocks; a block the file does not take whole (a full disk) is
/// cut back off, so the file never ends in a cut-off row.
#[derive(Debug)]
pub struct TelemetryWriter<S: RowSink = File> {
    rows: csv::Writer<Vec<u8>>,
    sink: S,
    /// Bytes of whole rows the sink holds.
    committed_bytes: u64,
    columns: usize,
}

impl TelemetryWriter<File> {
    /// Creates (truncates) the file.
    pub fn create(path: &Path) -> std::io::Result<Self> {
        Ok(Self::new(File::create(path)?))
    }
}

impl<S: RowSink> TelemetryWriter<S> {
    /// A writer into `sink`, which must be empty.
    pub fn new(sink: S) -> Self {
        Self {
            rows: csv::Writer::from_writer(Vec::new()),
            sink,
            committed_bytes: 0,
            columns: 0,
        }
    }

    /// Appends one row (writing the header before the first). Non-finite values are written
    /// as empty cells.
    pub fn write(&mut self, row: &[(&'static str, f64)]) -> std::io::Result<()> {
        if self.columns == 0 {
            self.rows.write_record(row.iter().map(|(name, _)| *name))?;
            self.columns = row.len();
        }
        if row.len() != self.columns {
            // A row that does not fit the header would corrupt the CSV: refuse it.
            return Err(std::io::Error::new(
                std::io::ErrorKind::InvalidData,
                format!(
                    "telemetry row has {} columns, the header {}",
                    row.len(),
                    self.columns
                ),
            ));
        }
        let cells = row.iter().map(|(_, value)| {
            if value.is_finite() {
                value.to_string()
            } else {
                String::new()
            }
        });
        self.rows.write_record(cells)?;
        if self.rows.get_ref().len() >= BLOCK_BYTES {
            self.flush()?;
        }
        Ok(())
    }

    /// Hands the rows gathered so far to the sink and flushes it; on failure the sink is cut
    /// back to the rows it held whole before.
    pub fn flush(&mut self) -> std::io::Result<()> {
        let rows = std::mem::replace(&mut self.rows, csv::Writer::from_writer(Vec::new()));
        let block = rows.into_inner().map_err(|e| e.into_error())?;
        match self.sink.write_all(&block).and_then(|()| self.sink.flush()) {
            Ok(()) => {
                self.committed_bytes += block.len() as u64;
                Ok(())
            }
            Err(e) => {
                // The error that stopped the run is the one to report; a failed cut-back
                // cannot be mended here.
                let _ = self.sink.truncate_to(self.committed_bytes);
                Err(e)
            }
        }
    }

    /// The sink.
    #[cfg(test)]
    fn sink(&self) -> &S {
        &self.sink
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A row whose columns do not match the header is refused, in every build, and the
    /// rows written before it stay intact.
    #[test]
    fn mismatched_row_is_refused() {
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("t.csv");
        let mut w = TelemetryWriter::create(&path).expect("create");
        w.write(&[("a", 1.0), ("b", 2.0)]).expect("first row");
        assert!(w.write(&[("a", 1.0)]).is_err());
        w.flush().expect("flush");
        let text = std::fs::read_to_string(&path).expect("read");
        assert_eq!(text, "a,b\n1,2\n");
    }

    /// A sink that takes `room` bytes and then fails as a full disk does, after taking part
    /// of the block it was given.
    struct FullDisk {
        bytes: Vec<u8>,
        room: usize,
    }

    impl Write for FullDisk {
        fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
            let free = self.room.saturating_sub(self.bytes.len());
            if free == 0 {
                return Err(std::io::ErrorKind::StorageFull.into());
            }
            let n = free.min(buf.len());
            self.bytes.extend_from_slice(&buf[..n]);
            Ok(n)
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }

    impl RowSink for FullDisk {
        fn truncate_to(&mut self, len: u64) -> std::io::Result<()> {
            self.bytes.truncate(len as usize);
            Ok(())
        }
    }

    /// A disk that fills up in the middle of a row: the file keeps whole rows only.
    #[test]
    fn full_disk_leaves_no_cut_off_row() {
        let mut w = TelemetryWriter::new(FullDisk {
            bytes: Vec::new(),
            room: 200_000,
        });
        let mut failed = None;
        for i in 0..100_000 {
            let t = f64::from(i) * 0.001;
            if let Err(e) = w.write(&[("t_s", t), ("x", 1.0 / 3.0), ("y", -t)]) {
                failed = Some(e);
                break;
            }
        }
        let failed = failed.expect("the disk fills up");
        assert_eq!(failed.kind(), std::io::ErrorKind::StorageFull);
        let text = String::from_utf8(w.sink().bytes.clone()).expect("utf-8");
        assert!(
            text.len() > 100_000 && text.ends_with('\n'),
            "{}",
            text.len()
        );
        assert!(text.lines().all(|l| l.split(',').count() == 3));
    }
}
