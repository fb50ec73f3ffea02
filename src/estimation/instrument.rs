//! The size read from the follower's own excitation used as an instrument
//! (docs/equations.md, The size from the excitation as an instrument).
//!
//! The image gives r = R/b and the navigation the follower's own position p_F in feet, so
//! p_F = p_L − b r, p_L the tracked aircraft's unknown position. Along the excitation's
//! direction E(t), which turns with its frame, the frames' increments keep the relation:
//! y_F = Σ E·Δp_F = y_L − b y_r, y_r = Σ E·Δr (E·p_F itself would move with p_F's distance
//! from the origin as E turns). Both sides are band-passed about the excitation's frequency ω
//! and correlated with the excitation's own phasor ζ(t) = a(t) e^{iωt}, which the follower
//! commands and which the tracked aircraft, flying ahead and looking ahead, cannot answer:
//!
//!   C_F = Σ ζ* y_F',  C_r = Σ ζ* y_r',  b̂ = −Re(C_F C_r*) / |C_r|²
//!
//! The leader's part, C_L = C_F + b C_r, averages out whatever the leader does, its copy of
//! its own leader included, instead of biasing b̂ as the filter's own-motion regression does
//! when the follower's motion is its response to the leader's (docs/findings.md, What sets a
//! link's size error). Its σ is read from the spread of C_L over blocks of a few periods.

use crate::frames::Vec3;

/// The instrument's settings (`[estimator]` `instrument_*`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InstrumentSettings {
    /// ω, the excitation's angular frequency, rad/s.
    pub omega_rps: f64,
    /// The band-pass's quality factor Q.
    pub q: f64,
    /// The interval between samples, s (the camera's frame period).
    pub sample_s: f64,
    /// How long after the first sample the sums start (the band-pass settles), s.
    pub settle_s: f64,
    /// The length of a block the σ is read over, s.
    pub block_s: f64,
    /// The fewest whole blocks before there is an estimate.
    pub min_blocks: usize,
    /// The time constant of the low-pass E passes before the increments are read along it, s
    /// (0: E as given).
    pub direction_time_s: f64,
}

/// The instrument's reading: b̂ and its σ, ft.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InstrumentSize {
    /// b̂, ft.
    pub size_ft: f64,
    /// σ of b̂, ft.
    pub sigma_ft: f64,
}

/// A complex number, (re, im).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct Complex(f64, f64);

impl Complex {
    fn add_scaled(&mut self, z: Complex, x: f64) {
        self.0 += z.0 * x;
        self.1 += z.1 * x;
    }

    /// Re(self · other*).
    fn dot(self, other: Complex) -> f64 {
        self.0 * other.0 + self.1 * other.1
    }

    fn norm_sq(self) -> f64 {
        self.dot(self)
    }
}

/// A causal second-order band-pass of unit gain at its centre (the bilinear transform of
/// (ω/Q) s / (s² + (ω/Q) s + ω²)).
#[derive(Debug, Clone, Copy, PartialEq)]
struct BandPass {
    b0: f64,
    a1: f64,
    a2: f64,
    x: [f64; 2],
    y: [f64; 2],
}

impl BandPass {
    fn new(omega_rps: f64, q: f64, sample_s: f64) -> Self {
        let w = omega_rps * sample_s;
        let alpha = w.sin() / (2.0 * q);
        let a0 = 1.0 + alpha;
        Self {
            b0: alpha / a0,
            a1: -2.0 * w.cos() / a0,
            a2: (1.0 - alpha) / a0,
            x: [0.0; 2],
            y: [0.0; 2],
        }
    }

    fn step(&mut self, input: f64) -> f64 {
        let output = self.b0 * (input - self.x[1]) - self.a1 * self.y[0] - self.a2 * self.y[1];
        self.x = [input, self.x[0]];
        self.y = [output, self.y[0]];
        output
    }
}

/// `direction` less its component along the line of sight `sight` (any length; `direction`
/// as it is for a zero sight), for `estimator.instrument_axis = "across_slot"`: r = ρ û, so
/// E·Δr = Δρ (E·û) + ρ E·Δû, and across the line of sight the increments are the bearing's
/// alone to first order; along it they carry the range's error, which the size model's
/// aspect moves as the swing turns the view (docs/equations.md, The instrument's direction).
pub fn across_sight(direction: &Vec3, sight: &Vec3) -> Vec3 {
    sight
        .try_normalize(1e-9)
        .map_or(*direction, |unit| direction - unit * direction.dot(&unit))
}

/// The running sums of the instrument.
#[derive(Debug, Clone)]
pub struct ExcitationInstrument {
    settings: InstrumentSettings,
    own: BandPass,
    image: BandPass,
    /// The low-pass's gain per frame, 1 - e^(-Δt/τ) (1: E as given), and E after it, NED
    /// (not normalised).
    direction_gain: f64,
    direction: Option<Vec3>,
    /// The last measured (r, p_F ft), NED, and the sums of the increments along E so far
    /// (y_F ft, y_r), held through a frame without a measurement.
    last: Option<(Vec3, Vec3)>,
    sums: (f64, f64),
    first_s: Option<f64>,
    /// (C_F, C_r) over the whole blocks so far, and each block's.
    total: (Complex, Complex),
    blocks: Vec<(Complex, Complex)>,
    /// The block being summed and when it began, s.
    current: (Complex, Complex),
    current_start_s: Option<f64>,
    /// The reading over the whole blocks, kept from the last block's end (it changes only
    /// then, and the excitation asks for it at every tick).
    reading: Option<InstrumentSize>,
}

impl ExcitationInstrument {
    /// An instrument with nothing summed.
    pub fn new(settings: InstrumentSettings) -> Self {
        let band = BandPass::new(settings.omega_rps, settings.q, settings.sample_s);
        let time_s = settings.direction_time_s;
        Self {
            settings,
            own: band,
            image: band,
            direction_gain: if time_s > 0.0 {
                1.0 - (-settings.sample_s / time_s).exp()
            } else {
                1.0
            },
            direction: None,
            last: None,
            sums: (0.0, 0.0),
            first_s: None,
            total: Default::default(),
            blocks: Vec::new(),
            current: Default::default(),
            current_start_s: None,
            reading: None,
        }
    }

    /// One frame taken at `t_s`, the excitation's amplitude then `amplitude` (any units: it
    /// weighs the frame) and its unit direction `direction_ned`: the frame's r (scaled, NED)
    /// and the follower's position then (ft, NED), or `None` when the frame measured nothing
    /// the instrument can use (the sums are held).
    pub fn add_frame(
        &mut self,
        t_s: f64,
        amplitude: f64,
        direction_ned: &Vec3,
        measured: Option<(&Vec3, &Vec3)>,
    ) {
        let direction_ned = self.low_passed(direction_ned);
        if let Some((r, p)) = measured {
            if let Some((last_r, last_p)) = self.last {
                self.sums.0 += direction_ned.dot(&(p - last_p));
                self.sums.1 += direction_ned.dot(&(r - last_r));
            }
            self.last = Some((*r, *p));
        } else if self.last.is_none() {
            return;
        }
        let (own, image) = (self.own.step(self.sums.0), self.image.step(self.sums.1));
        let first_s = *self.first_s.get_or_insert(t_s);
        if t_s < first_s + self.settings.settle_s {
            return;
        }
        let (s, c) = (self.settings.omega_rps * t_s).sin_cos();
        let phasor = Complex(amplitude * s, amplitude * c);
        let start_s = *self.current_start_s.get_or_insert(t_s);
        self.current.0.add_scaled(phasor, own);
        self.current.1.add_scaled(phasor, image);
        if t_s - start_s >= self.settings.block_s - 0.5 * self.settings.sample_s {
            self.close_block();
        }
    }

    /// E through a first-order low-pass of `direction_time_s`, normalised. E turns with the
    /// command's frame, whose heading the follower's own swing moves a little at the swing's
    /// frequency (through its estimate of the leader's velocity); along an E that wobbles in
    /// step with the swing the leader's motion along its track would enter the reading as an
    /// answer to the excitation (docs/equations.md, The instrument's direction).
    fn low_passed(&mut self, direction_ned: &Vec3) -> Vec3 {
        let gain = self.direction_gain;
        let smoothed = self
            .direction
            .map_or(*direction_ned, |d| d + gain * (direction_ned - d));
        self.direction = Some(smoothed);
        smoothed.try_normalize(1e-12).unwrap_or(*direction_ned)
    }

    fn close_block(&mut self) {
        let (own, image) = self.current;
        self.total.0.add_scaled(own, 1.0);
        self.total.1.add_scaled(image, 1.0);
        self.blocks.push(self.current);
        self.current = Default::default();
        self.current_start_s = None;
        self.reading = self.read();
    }

    /// The reading over the whole blocks so far (see [`Self::read`]).
    pub fn estimate(&self) -> Option<InstrumentSize> {
        self.reading
    }

    /// b̂ = −Re(C_F C_r*) / |C_r|² and its σ, √(Σ_j |C_F,j + b̂ C_r,j|² / 2) / |C_r| over the
    /// whole blocks; `None` before `min_blocks` of them or while the image has not answered
    /// the excitation.
    fn read(&self) -> Option<InstrumentSize> {
        if self.blocks.len() < self.settings.min_blocks.max(1) {
            return None;
        }
        let (own, image) = self.total;
        let image_sq = image.norm_sq();
        if image_sq <= 0.0 {
            return None;
        }
        let size_ft = -own.dot(image) / image_sq;
        let leader_sq: f64 = self
            .blocks
            .iter()
            .map(|(own_j, image_j)| {
                Complex(own_j.0 + size_ft * image_j.0, own_j.1 + size_ft * image_j.1).norm_sq()
            })
            .sum();
        let sigma_ft = (0.5 * leader_sq / image_sq).sqrt();
        (size_ft > 0.0).then_some(InstrumentSize { size_ft, sigma_ft })
    }
}

#[cfg(test)]
mod tests;
