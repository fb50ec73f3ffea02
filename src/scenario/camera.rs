//! `[camera]`: the follower's camera, its renderer and its image pipeline (sensor `camera`).

use super::check::{self, Check};
use serde::{Deserialize, Serialize};

/// The sky behind the target.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SkyKind {
    /// One colour, `sky_rgb`.
    Uniform,
    /// From `sky_top_rgb` at the top row to `sky_bottom_rgb` at the bottom row.
    Gradient,
}

/// Which blob the image pipeline measures when it finds several.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BlobChoice {
    /// The largest.
    Largest,
    /// The one nearest the previous frame's centroid (the largest on the first frame or after
    /// a loss).
    Nearest,
    /// The one nearest where the target is expected, inside a gate of `selection_gate_deg`
    /// plus half the expected maximal length (`expected_length`): the estimator's predicted line of sight (before
    /// the target is first measured, the gimbal's cue; without either, the previous frame's
    /// centroid turned by the camera's rotation since); none when no blob lies inside the
    /// gate, or when a blob centred in it but reaching beyond it (the tracked aircraft joined
    /// to another) is more like the prediction than every blob inside. The largest only with
    /// no expectation at all.
    Predicted,
}

/// Where the image pipeline's expectation of the target's maximal length in the next frame
/// comes from: the `predicted` selection's gate and size term, and the `motion`
/// segmentation's ring and the memory's exclusion about the target.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LengthExpectation {
    /// The last frame measured `Ok`: a fragment measured short shrinks what the next frame
    /// looks for.
    LastMeasured,
    /// The larger of the estimator's span at its predicted range, 1/|r̂| rad (r̂ = R̂/b̂, so
    /// the angle does not depend on b̂'s error), and the last `Ok` length (alone before the
    /// first estimate): a fragment measured short, whose length the filter's innovation
    /// gate keeps out, does not shrink what the next frame looks for, nor does a prediction
    /// that lags a closing target (docs/findings.md, The estimator's word on the target's
    /// length).
    Estimated,
}

/// What a merge (`selection = "predicted"`: the tracked aircraft's blob joined to another's,
/// told by the gate's square or `selection_merge_ratio`) measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MergeMeasurement {
    /// Nothing: the frame is not measured and the estimator coasts until the blobs part.
    Unmeasured,
    /// The joined blob, status `merged`: the Kalman filter fuses its bearing alone, the
    /// centroid's σ widened to half of how much longer it is than the predicted length
    /// (docs/equations.md, A merge's bearing); it is not a measurement of the aircraft alone
    /// (a lost frame, never trusted).
    Bearing,
}

/// The point of the silhouette its bearing and elevation are measured to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BearingPoint {
    /// The coverage-weighted centroid (the seed's (yI, zI)).
    Centroid,
    /// The midpoint of the maximal length's ends: for an aircraft seen from behind, the wing
    /// tips' midpoint, at the depth of the points the length is measured between.
    LengthMidpoint,
}

/// Which pixels of each frame are drawn, read back and measured.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CameraPipeline {
    /// Only a tracking window around where the target is predicted to be, from the last
    /// measurement and the follower's attitude (`vision::tracking`); the whole image at
    /// acquisition, after a lost frame, and again, in the same frame, when the target reaches
    /// the window's edge (a frame to be saved, `output.frames_every`, is measured in its
    /// window and only then drawn whole for the saved image). The camera's cost
    /// then follows the target, not the image size, and the measurements are the whole
    /// image's: to the bit on a noise-free uniform sky (formation.toml flies the same
    /// telemetry), within 0.004 px on a gradient sky, and with pixel noise by less than a new
    /// draw of the noise changes them (`tests/camera_window.rs`).
    Window,
    /// Every frame whole: the reference the window is compared with.
    Whole,
}

/// How the image pipeline tells target pixels from background pixels.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SegmentationKind {
    /// A colour distance to a smooth colour surface fitted to the border of the measured
    /// pixels: exact on a uniform or gradient sky, not on textured ground or cloud.
    Threshold,
    /// A colour distance to the background each pixel is explained by: the previous frame's
    /// pixel at the same direction (the background at infinity maps between frames by
    /// K R K⁻¹, R the camera's rotation between them from the follower's navigation attitude
    /// and gimbal angles), away from the previous frame's target, or the nearest colour of the
    /// measured pixels' border (`vision::reference`, docs/findings.md, The scene and the
    /// vision against it).
    Motion,
}

/// The default `camera.mesh`: the seed's target, shipped in `assets/` and built into the
/// program.
pub const DEFAULT_MESH: &str = "assets/target_aircraft.obj";

/// Largest focal length, px (a field of view of about 0.04° at 640 px).
pub const MAX_FOCAL_PX: f64 = 1e6;

/// `[camera]` section.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CameraSection {
    /// Image width, px.
    pub width_px: u32,
    /// Image height, px.
    pub height_px: u32,
    /// Horizontal field of view, deg (used when `focal_px` is 0).
    pub hfov_deg: f64,
    /// Focal length, px; 0 derives it from `hfov_deg`.
    pub focal_px: f64,
    /// Frames per second; its period must be a whole number of `run.dt_s`.
    pub rate_hz: f64,
    /// Frames between taking a picture and its measurement reaching the guidance.
    pub latency_frames: u32,
    /// Samples per pixel: 1 or 4 (anti-aliased edges, sub-pixel centroid).
    pub msaa_samples: u32,
    /// Sky model.
    pub sky: SkyKind,
    /// Uniform sky colour, RGB 0-255.
    pub sky_rgb: [u8; 3],
    /// Gradient sky, top row colour.
    pub sky_top_rgb: [u8; 3],
    /// Gradient sky, bottom row colour.
    pub sky_bottom_rgb: [u8; 3],
    /// Per-pixel Gaussian noise, grey levels (0 = none).
    pub noise_std_grey: f64,
    /// Target mesh (OBJ), scaled so that its maximal dimension is `target.size_ft`; a relative
    /// path is looked up from the scenario file's folder (the default one, when that folder
    /// has none, is the shipped mesh).
    pub mesh: String,
    /// Blob selection.
    pub selection: BlobChoice,
    /// `selection = "predicted"`: the gate's radius about the expected position, deg, beyond
    /// half the expected maximal length.
    pub selection_gate_deg: f64,
    /// `selection = "predicted"`: how much a blob's size counts beside its distance. A blob
    /// whose box's longer side is this ratio off the expected maximal length weighs as much as one
    /// at the gate's edge; 0: sizes are not compared, the nearest inside the gate is taken.
    /// 1.5: beside a teammate or a crosser of another size in the image, a wrong blob near the
    /// prediction is not taken for the target (docs/findings.md, Group tracking).
    pub selection_length_ratio: f64,
    /// `selection = "predicted"`: a blob shorter than this fraction of the expected maximal
    /// length is a fragment, and its size counts as this fraction's: fragments are told apart
    /// by their distance from the prediction alone (0: every size counts as it is).
    pub selection_fragment_fraction: f64,
    /// `selection = "predicted"`: a blob whose box's longer side exceeds this ratio of the
    /// expected maximal length is the tracked aircraft joined to another (a merge), never taken
    /// for the aircraft alone; while it is the blob most like the prediction the frame measures
    /// what `merges` says, as for a blob reaching beyond the gate (0: merges are told by the
    /// gate's square alone).
    pub selection_merge_ratio: f64,
    /// `selection = "predicted"`: what a merge measures: `unmeasured` (default) or `bearing`
    /// (see [`MergeMeasurement`]).
    pub merges: MergeMeasurement,
    /// Where the expected maximal length comes from: `last_measured` (default) or
    /// `estimated` (see [`LengthExpectation`]).
    pub expected_length: LengthExpectation,
    /// Blobs with fewer mask pixels are too small to measure.
    pub min_pixel_count: u32,
    /// Mask pixels up to this far apart (px, in u and v) are one blob: 2 bridges the broken
    /// lines a distant wing seen edge-on rasterises to.
    pub link_radius_px: u32,
    /// Bring each held measurement forward to the current time with the follower's own known
    /// displacement and the estimated target drift (see `sim`); false holds r* as measured.
    pub compensate_delay: bool,
    /// The camera's fixed pitch on the body, deg, positive up (an optional mounting rotation
    /// the seed's Chapter 3 leaves out; 0: camera = body). A fixed camera on an aircraft that
    /// flies at an angle of attack looks above its flight path by α; a camera pitched down by
    /// about the α of its usual speeds keeps a target at its own level near the image's centre.
    pub mount_pitch_deg: f64,
    /// The pan/tilt gimbal, when the camera rides one.
    pub gimbal: super::GimbalSection,
    /// The point of the silhouette the bearing and elevation (yI, zI) are measured to. The
    /// seed's is the centroid; an extended target's centroid is not at the depth of the points
    /// its maximal length spans (the wing tips, seen from behind), and as the follower moves
    /// it shifts by parallax a few percent more than the target's reference point, which a
    /// filter that learns the range from the follower's own motion reads as a smaller target
    /// (docs/findings.md, The bearing point).
    pub bearing_point: BearingPoint,
    /// A candidate pixel joins the target mask when at least this fraction of it is covered,
    /// in (0, 1]; lower keeps thin parts (a wing seen edge-on) connected.
    pub mask_coverage: f64,
    /// Which pixels are drawn, read back and measured: `window` (default: the camera's cost
    /// follows the target, not the image) or `whole` (the reference it is compared with).
    pub pipeline: CameraPipeline,
    /// Bin a frame whose target is predicted longer than this many pixels (0: never): it is
    /// drawn and measured at the coarsest whole binning k (k x k pixels to one, k dividing the
    /// image's width and height, at most 8) with k ≤ ⌈length / this⌉, and the measurement
    /// carried back to the image's pixels (`sensing::binning`). The camera's cost then stops
    /// growing with the target's size beyond this length, at the accuracy of a 1/k-resolution
    /// camera for those frames; with `pipeline = "window"` only.
    pub measure_max_length_px: f64,
    /// How target pixels are told from background: `threshold` (default: against a colour
    /// surface fitted to the border) or `motion` (against the rotation-compensated previous
    /// frame and the border's colours, for a textured world behind the target).
    pub segmentation: SegmentationKind,
    /// `segmentation = "motion"`: a pixel the remembered background does not explain is
    /// target only as a mixture of a background colour around it and a shade of the target's
    /// colour (learned from the blobs measured on it), to within this angle in RGB, deg; 0
    /// (default): colours are not tested. A field's edge the memory mislaid, or a road, is a
    /// mixture of two ground colours, off the plane of the background and a target of another
    /// colour (docs/equations.md, Scene; docs/findings.md, The target's colour as the
    /// pixel's explanation).
    pub target_colour_tolerance_deg: f64,
    /// An occlusion: frames taken in [start, end) s show no target (as if a cloud or the
    /// follower's own airframe hid it), to force a loss; [0, 0] for none.
    pub occlusion_s: [f64; 2],
}

impl Default for CameraSection {
    fn default() -> Self {
        Self {
            width_px: 640,
            height_px: 480,
            hfov_deg: 60.0,
            focal_px: 0.0,
            rate_hz: 30.0,
            latency_frames: 1,
            msaa_samples: 1,
            sky: SkyKind::Uniform,
            sky_rgb: [175, 200, 230],
            sky_top_rgb: [150, 180, 225],
            sky_bottom_rgb: [215, 225, 235],
            noise_std_grey: 0.0,
            mesh: DEFAULT_MESH.to_string(),
            selection: BlobChoice::Nearest,
            selection_gate_deg: 3.0,
            selection_length_ratio: 1.5,
            selection_fragment_fraction: 0.0,
            selection_merge_ratio: 0.0,
            merges: MergeMeasurement::Unmeasured,
            expected_length: LengthExpectation::LastMeasured,
            min_pixel_count: 4,
            mask_coverage: 0.5,
            compensate_delay: true,
            mount_pitch_deg: 0.0,
            gimbal: super::GimbalSection::default(),
            bearing_point: BearingPoint::Centroid,
            link_radius_px: 2,
            pipeline: CameraPipeline::Window,
            measure_max_length_px: 0.0,
            occlusion_s: [0.0, 0.0],
            segmentation: SegmentationKind::Threshold,
            target_colour_tolerance_deg: 0.0,
        }
    }
}

impl CameraSection {
    /// L_CB of the fixed mount: the §0 DCM at (0, pitch, 0).
    pub fn camera_from_body(&self) -> crate::frames::Mat3 {
        crate::frames::EulerAngles::new(0.0, self.mount_pitch_deg.to_radians(), 0.0).body_from_ned()
    }

    /// Checks that the frame period is a whole number of simulation steps `dt_s` (only a
    /// camera run takes frames).
    pub fn validate_rate(&self, dt_s: f64) -> Check {
        let ticks = 1.0 / (self.rate_hz * dt_s);
        check::require(
            ticks >= 1.0 - 1e-9 && (ticks - ticks.round()).abs() < 1e-6 * ticks,
            "camera.rate_hz",
            self.rate_hz,
            format!("a rate whose period is a whole number of run.dt_s = {dt_s} s"),
        )
    }

    /// Checks every value, whatever the sensor: a key is refused even where it goes unused.
    pub fn validate(&self) -> Check {
        self.validate_focal_length()?;
        check::int_in("camera.height_px", i64::from(self.height_px), 8, 8192)?;
        check::in_closed("camera.mount_pitch_deg", self.mount_pitch_deg, -90.0, 90.0)?;
        self.gimbal.validate()?;
        check::in_closed("camera.rate_hz", self.rate_hz, 0.01, 10_000.0)?;
        check::int_in(
            "camera.latency_frames",
            i64::from(self.latency_frames),
            0,
            100,
        )?;
        check::require(
            matches!(self.msaa_samples, 1 | 4),
            "camera.msaa_samples",
            self.msaa_samples,
            "1 or 4",
        )?;
        check::in_closed("camera.noise_std_grey", self.noise_std_grey, 0.0, 100.0)?;
        self.validate_selection()?;
        check::require(
            self.target_colour_tolerance_deg == 0.0
                || (self.segmentation == SegmentationKind::Motion
                    && (1.0..=60.0).contains(&self.target_colour_tolerance_deg)),
            "camera.target_colour_tolerance_deg",
            self.target_colour_tolerance_deg,
            "0 (no colour test) or [1, 60] deg with segmentation = \"motion\"",
        )?;
        check::require(
            self.measure_max_length_px == 0.0 || (16.0..=1e5).contains(&self.measure_max_length_px),
            "camera.measure_max_length_px",
            self.measure_max_length_px,
            "0 (never bin) or 16 to 100000 px",
        )?;
        let [hide_s, show_s] = self.occlusion_s;
        check::require(
            hide_s.is_finite() && show_s.is_finite() && 0.0 <= hide_s && hide_s <= show_s,
            "camera.occlusion_s",
            format!("{:?}", self.occlusion_s),
            "[start, end] s with 0 <= start <= end",
        )?;
        check::require(
            !self.mesh.is_empty(),
            "camera.mesh",
            "\"\"",
            "a path to an OBJ file",
        )?;
        check::int_in(
            "camera.min_pixel_count",
            i64::from(self.min_pixel_count),
            1,
            1_000_000,
        )?;
        check::int_in(
            "camera.link_radius_px",
            i64::from(self.link_radius_px),
            1,
            8,
        )?;
        check::in_open(
            "camera.mask_coverage",
            self.mask_coverage,
            0.0,
            1.0 + 1e-12,
            "(0, 1]",
        )
    }

    /// Checks the `predicted` selection's gate and size keys.
    fn validate_selection(&self) -> Check {
        check::in_open(
            "camera.selection_gate_deg",
            self.selection_gate_deg,
            0.0,
            90.0,
            "(0, 90)",
        )?;
        check::require(
            self.selection_length_ratio == 0.0
                || (1.01..=100.0).contains(&self.selection_length_ratio),
            "camera.selection_length_ratio",
            self.selection_length_ratio,
            "0 (sizes not compared) or [1.01, 100]",
        )?;
        check::require(
            (0.0..1.0).contains(&self.selection_fragment_fraction),
            "camera.selection_fragment_fraction",
            self.selection_fragment_fraction,
            "[0, 1)",
        )?;
        check::require(
            self.selection_merge_ratio == 0.0
                || (1.01..=100.0).contains(&self.selection_merge_ratio),
            "camera.selection_merge_ratio",
            self.selection_merge_ratio,
            "0 (merges told by the gate alone) or [1.01, 100]",
        )
    }

    /// Checks the keys [`Self::focal_length_px`] reads (the noisy sensor's noise on pixels
    /// reads them too).
    fn validate_focal_length(&self) -> Check {
        check::int_in("camera.width_px", i64::from(self.width_px), 8, 8192)?;
        check::in_open("camera.hfov_deg", self.hfov_deg, 0.0, 179.0, "(0, 179)")?;
        check::in_closed("camera.focal_px", self.focal_px, 0.0, MAX_FOCAL_PX)?;
        let focal_px = self.focal_length_px();
        check::require(
            focal_px.is_finite() && focal_px <= MAX_FOCAL_PX,
            "camera.hfov_deg",
            self.hfov_deg,
            format!(
                "(0, 179) giving a focal length <= {MAX_FOCAL_PX:e} px (it gives {focal_px:e})"
            ),
        )
    }

    /// Focal length, px: `focal_px`, or from `hfov_deg` when that is 0.
    pub fn focal_length_px(&self) -> f64 {
        if self.focal_px > 0.0 {
            self.focal_px
        } else {
            0.5 * f64::from(self.width_px) / (0.5 * self.hfov_deg.to_radians()).tan()
        }
    }

    /// Simulation ticks between frames.
    pub fn period_ticks(&self, dt_s: f64) -> u64 {
        (1.0 / (self.rate_hz * dt_s)).round().max(1.0) as u64
    }
}
