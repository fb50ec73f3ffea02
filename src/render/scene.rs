//! A world for the camera: a sky whose colour follows elevation, a flat ground plane with a
//! seeded procedural texture of fields and roads, an optional seeded cloud sheet, and a sun
//! that lights the target (docs/equations.md, Scene).
//!
//! The world is fixed in NED: the renderer draws it, for every pixel, along the pixel's ray
//! turned into NED by the camera's true orientation and started from its true position
//! ([`CameraInWorld`]), in `shaders/target.wgsl` (`fs_scene`). The lattice noise of the clouds
//! is written twice, here and in the shader, with the same integer hash: the CPU copy finds
//! the density threshold that covers the stated fraction of the sheet, and says what lies
//! behind the target for the summary ([`WorldScene::backdrop`], for reporting only).

use crate::frames::{Mat3, Vec3};

/// Where the camera is in the world: what the renderer draws the world from (the truth).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CameraInWorld {
    /// Rotation taking camera axes (x along the optical axis, y right, z down in the image)
    /// to NED: (L_CB L_BE)ᵀ.
    pub ned_from_camera: Mat3,
    /// The camera's position, NED, ft.
    pub position_ned_ft: Vec3,
}

impl Default for CameraInWorld {
    fn default() -> Self {
        Self {
            ned_from_camera: Mat3::identity(),
            position_ned_ft: Vec3::zeros(),
        }
    }
}

/// The ground: a horizontal plane of square fields with roads along some field edges.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ground {
    /// The plane's NED down coordinate, ft (below the camera while it flies).
    pub down_ft: f64,
    /// Side of a square field, ft.
    pub field_ft: f64,
    /// A road runs along every this many field edges, each way.
    pub road_every_fields: u32,
    /// Width of a road, ft.
    pub road_width_ft: f64,
}

/// A thin sheet of cloud at one height, its cloudy parts where a lattice noise exceeds the
/// threshold that leaves `coverage` of the sheet cloudy.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Clouds {
    /// The sheet's NED down coordinate, ft.
    pub down_ft: f64,
    /// The noise's lattice spacing, ft (about the size of one cloud).
    pub cell_ft: f64,
    /// Fraction of the sheet that is cloud, 0-1.
    pub coverage: f64,
}

/// The sun: a direction fixed in NED.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sun {
    /// Unit vector towards the sun, NED.
    pub towards_ned: Vec3,
    /// Strength of the glare around the sun, 0 (none) to 1 (white at the sun): a veil added
    /// to sky, ground and target alike, falling off as exp(-(angle / 6°)²).
    pub glare: f64,
}

impl Sun {
    /// The sun at `azimuth_deg` from north (positive east) and `elevation_deg` above the
    /// horizon.
    pub fn at(azimuth_deg: f64, elevation_deg: f64, glare: f64) -> Self {
        let (az, el) = (azimuth_deg.to_radians(), elevation_deg.to_radians());
        Self {
            towards_ned: Vec3::new(el.cos() * az.cos(), el.cos() * az.sin(), -el.sin()),
            glare,
        }
    }
}

/// The world behind the target.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WorldScene {
    /// Sky colour straight up (RGB, 0-255).
    pub zenith_rgb: [u8; 3],
    /// Sky colour at the horizon, and of the haze (RGB, 0-255).
    pub horizon_rgb: [u8; 3],
    /// The ground (None: the haze colour below the horizon).
    pub ground: Option<Ground>,
    /// The cloud sheet (None: no clouds).
    pub clouds: Option<Clouds>,
    /// The sun.
    pub sun: Sun,
    /// Distance over which the haze hides ground and cloud, ft: a surface at distance d shows
    /// exp(-d / visibility) of its own colour.
    pub visibility_ft: f64,
    /// Seed of the ground's fields and the clouds' noise.
    pub seed: u32,
}

/// What lies along a ray from the camera.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Backdrop {
    /// Open sky.
    Sky,
    /// The ground.
    Ground,
    /// A cloudy part of the cloud sheet.
    Cloud,
}

/// Salts of the lattice noise's streams (the same in `shaders/target.wgsl`).
const CLOUD_SALT: u32 = 1;
/// The second octave of the clouds.
const CLOUD_DETAIL_SALT: u32 = 2;

/// The PCG hash (one round of O'Neill's PCG-RXS-M-XS on 32 bits), as the shader's `pcg`.
pub fn pcg(v: u32) -> u32 {
    let state = v.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
    let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(277_803_737);
    (word >> 22) ^ word
}

/// A value in [0, 1) for lattice point (i, j) of stream `salt` of `seed` (the shader's
/// `lattice`).
pub fn lattice(i: i32, j: i32, salt: u32, seed: u32) -> f32 {
    let h = pcg(i as u32 ^ pcg(j as u32 ^ pcg(seed ^ salt)));
    (h >> 8) as f32 / 16_777_216.0
}

/// Smooth value noise at `p` (lattice units): the lattice values blended with 3f² - 2f³
/// (the shader's `value_noise`).
fn value_noise(p: [f32; 2], salt: u32, seed: u32) -> f32 {
    let cell = [p[0].floor(), p[1].floor()];
    let f = [p[0] - cell[0], p[1] - cell[1]];
    let s = f.map(|f| f * f * (3.0 - 2.0 * f));
    let (i, j) = (cell[0] as i32, cell[1] as i32);
    let at = |di: i32, dj: i32| lattice(i.wrapping_add(di), j.wrapping_add(dj), salt, seed);
    let mix = |a: f32, b: f32, t: f32| a + (b - a) * t;
    mix(
        mix(at(0, 0), at(1, 0), s[0]),
        mix(at(0, 1), at(1, 1), s[0]),
        s[1],
    )
}

/// The clouds' density at `p` (lattice units): two octaves of value noise (the shader's
/// `cloud_density`).
pub fn cloud_density(p: [f32; 2], seed: u32) -> f32 {
    let detail = [p[0] * 2.3 + 17.0, p[1] * 2.3 + 31.0];
    0.65 * value_noise(p, CLOUD_SALT, seed) + 0.35 * value_noise(detail, CLOUD_DETAIL_SALT, seed)
}

/// The density above which `coverage` of the sheet is cloud: the (1 - coverage) quantile of
/// the density over 64 x 64 lattice cells sampled 8 times a cell each way (-1 for a sheet
/// all cloud, 2 for one without: the density lies in [0, 1)).
pub fn cloud_threshold(coverage: f64, seed: u32) -> f32 {
    const SIDE: usize = 512;
    let mut densities: Vec<f32> = (0..SIDE * SIDE)
        .map(|k| {
            let (x, y) = ((k % SIDE) as f32 + 0.5, (k / SIDE) as f32 + 0.5);
            cloud_density([x / 8.0, y / 8.0], seed)
        })
        .collect();
    densities.sort_by(f32::total_cmp);
    let clear = ((1.0 - coverage.clamp(0.0, 1.0)) * densities.len() as f64) as usize;
    match densities.get(clear) {
        Some(&d) if clear > 0 => d,
        Some(_) => -1.0,
        None => 2.0,
    }
}

/// Distance along the unit ray `dir_ned` from `from_ned_ft` to the horizontal plane at
/// `down_ft`, ft (None when the ray runs away from it or along it).
fn plane_distance_ft(from_ned_ft: &Vec3, dir_ned: &Vec3, down_ft: f64) -> Option<f64> {
    let t = (down_ft - from_ned_ft.z) / dir_ned.z;
    (t.is_finite() && t > 0.0).then_some(t)
}

impl WorldScene {
    /// A test scene: black sky, fields and roads 300 ft below, no cloud, the sun 30° up.
    #[cfg(test)]
    pub(crate) fn ground_300_ft_below() -> Self {
        Self {
            zenith_rgb: [0; 3],
            horizon_rgb: [0; 3],
            ground: Some(Ground {
                down_ft: 300.0,
                field_ft: 400.0,
                road_every_fields: 4,
                road_width_ft: 30.0,
            }),
            clouds: None,
            sun: Sun::at(0.0, 30.0, 0.0),
            visibility_ft: 1e4,
            seed: 1,
        }
    }

    /// What lies along the ray `dir_ned` (NED, any length) from a camera at `from_ned_ft`:
    /// the nearer of the ground and a cloudy part of the sheet, else sky. `threshold` is
    /// [`cloud_threshold`] of the clouds' coverage.
    pub fn backdrop(&self, from_ned_ft: &Vec3, dir_ned: &Vec3, threshold: f32) -> Backdrop {
        let dir = dir_ned.normalize();
        let ground_t = self
            .ground
            .and_then(|g| plane_distance_ft(from_ned_ft, &dir, g.down_ft));
        let cloud_hit = self.clouds.and_then(|c| {
            let t = plane_distance_ft(from_ned_ft, &dir, c.down_ft)?;
            let p = from_ned_ft + t * dir;
            let q = [(p.x / c.cell_ft) as f32, (p.y / c.cell_ft) as f32];
            (cloud_density(q, self.seed) > threshold).then_some(t)
        });
        match (ground_t, cloud_hit) {
            (Some(g), Some(c)) if c < g => Backdrop::Cloud,
            (Some(_), _) => Backdrop::Ground,
            (None, Some(_)) => Backdrop::Cloud,
            (None, None) => Backdrop::Sky,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The hash spreads neighbouring lattice points over [0, 1): mean near 1/2.
    #[test]
    fn lattice_values_are_uniform() {
        let n = 200;
        let sum: f64 = (0..n * n)
            .map(|k| f64::from(lattice(k % n - 100, k / n - 100, 0, 7)))
            .sum();
        let mean = sum / f64::from(n * n);
        assert!((mean - 0.5).abs() < 0.01, "{mean}");
        assert_ne!(lattice(3, 4, 0, 1), lattice(3, 4, 0, 2));
    }

    /// The threshold leaves the stated fraction cloudy, on a part of the sheet it was not
    /// computed on.
    #[test]
    fn threshold_covers_the_stated_fraction() {
        for coverage in [0.1, 0.3, 0.6] {
            let threshold = cloud_threshold(coverage, 3);
            let n = 300;
            let cloudy = (0..n * n)
                .filter(|k| {
                    let p = [
                        1000.3 + (k % n) as f32 * 0.17,
                        -500.1 + (k / n) as f32 * 0.17,
                    ];
                    cloud_density(p, 3) > threshold
                })
                .count();
            let fraction = cloudy as f64 / f64::from(n * n);
            assert!((fraction - coverage).abs() < 0.06, "{coverage}: {fraction}");
        }
        assert_eq!(cloud_threshold(0.0, 3), 2.0);
        assert_eq!(cloud_threshold(1.0, 3), -1.0);
    }

    /// Level rays see sky above and ground below; a cloudy sheet overhead hides the sky.
    #[test]
    fn backdrop_follows_the_ray() {
        let mut scene = WorldScene::ground_300_ft_below();
        let origin = Vec3::zeros();
        assert_eq!(
            scene.backdrop(&origin, &Vec3::new(1.0, 0.0, 0.1), 0.0),
            Backdrop::Ground
        );
        assert_eq!(
            scene.backdrop(&origin, &Vec3::new(1.0, 0.0, -0.1), 0.0),
            Backdrop::Sky
        );
        scene.clouds = Some(Clouds {
            down_ft: -600.0,
            cell_ft: 500.0,
            coverage: 1.0,
        });
        let everywhere = cloud_threshold(1.0, 1);
        assert_eq!(
            scene.backdrop(&origin, &Vec3::new(0.0, 0.0, -1.0), everywhere),
            Backdrop::Cloud
        );
        assert_eq!(
            scene.backdrop(&origin, &Vec3::new(0.0, 0.0, 1.0), everywhere),
            Backdrop::Ground
        );
    }

    /// The sun's direction: north at 0° azimuth, up for positive elevation.
    #[test]
    fn sun_points_where_stated() {
        let sun = Sun::at(90.0, 30.0, 0.0);
        assert!((sun.towards_ned - Vec3::new(0.0, 0.866_025_4, -0.5)).norm() < 1e-6);
    }
}
