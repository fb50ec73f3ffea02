//! Test images: shapes rasterised with area coverage from regular supersampling, composited
//! over a uniform or gradient background, plus optional per-channel Gaussian noise.

use rand::SeedableRng;
use rand_distr::{Distribution, Normal};

/// Background colour as a function of pixel position.
#[derive(Debug, Clone)]
pub(crate) enum Background {
    /// One colour everywhere.
    Uniform([f64; 3]),
    /// Linear in v from `top` (v = 0) to `bottom` (v = height), like a sky.
    Vertical { top: [f64; 3], bottom: [f64; 3] },
    /// `at_origin + per_u * u + per_v * v` per channel.
    Linear {
        at_origin: [f64; 3],
        per_u: [f64; 3],
        per_v: [f64; 3],
    },
}

impl Background {
    /// Colour at (u, v) in an image `height` px high.
    fn colour(&self, u: f64, v: f64, height: f64) -> [f64; 3] {
        match self {
            Background::Uniform(c) => *c,
            Background::Vertical { top, bottom } => {
                let t = v / height;
                [0, 1, 2].map(|c| top[c] + (bottom[c] - top[c]) * t)
            }
            Background::Linear {
                at_origin,
                per_u,
                per_v,
            } => [0, 1, 2].map(|c| at_origin[c] + per_u[c] * u + per_v[c] * v),
        }
    }
}

/// A filled shape in pixel coordinates.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Shape {
    /// Disc of `radius` px around (u, v).
    Disc { u: f64, v: f64, radius: f64 },
    /// Rectangle `length` x `breadth` px centred at (u, v), its length axis at `angle_rad`
    /// from the u axis.
    Rectangle {
        u: f64,
        v: f64,
        length: f64,
        breadth: f64,
        angle_rad: f64,
    },
    /// Triangle with corners `a`, `b`, `c` (u, v).
    Triangle {
        a: (f64, f64),
        b: (f64, f64),
        c: (f64, f64),
    },
}

/// Twice the signed area of (o, p, q).
fn cross(o: (f64, f64), p: (f64, f64), q: (f64, f64)) -> f64 {
    (p.0 - o.0) * (q.1 - o.1) - (p.1 - o.1) * (q.0 - o.0)
}

impl Shape {
    /// Whether the point (u, v) is inside the shape.
    pub fn contains(&self, pu: f64, pv: f64) -> bool {
        match *self {
            Shape::Disc { u, v, radius } => (pu - u).powi(2) + (pv - v).powi(2) <= radius * radius,
            Shape::Rectangle {
                u,
                v,
                length,
                breadth,
                angle_rad,
            } => {
                let (s, c) = angle_rad.sin_cos();
                let (du, dv) = (pu - u, pv - v);
                let along = du * c + dv * s;
                let across = -du * s + dv * c;
                along.abs() <= 0.5 * length && across.abs() <= 0.5 * breadth
            }
            Shape::Triangle { a, b, c } => {
                let p = (pu, pv);
                let (d1, d2, d3) = (cross(a, b, p), cross(b, c, p), cross(c, a, p));
                (d1 >= 0.0 && d2 >= 0.0 && d3 >= 0.0) || (d1 <= 0.0 && d2 <= 0.0 && d3 <= 0.0)
            }
        }
    }

    /// Conservative bounding box (min u, min v, max u, max v).
    fn bounds(&self) -> (f64, f64, f64, f64) {
        if let Shape::Triangle { a, b, c } = *self {
            return (
                a.0.min(b.0).min(c.0),
                a.1.min(b.1).min(c.1),
                a.0.max(b.0).max(c.0),
                a.1.max(b.1).max(c.1),
            );
        }
        let (u, v, r) = match *self {
            Shape::Disc { u, v, radius } => (u, v, radius),
            Shape::Rectangle {
                u,
                v,
                length,
                breadth,
                ..
            } => (u, v, 0.5 * length.hypot(breadth)),
            Shape::Triangle { .. } => (0.0, 0.0, 0.0),
        };
        (u - r, v - r, u + r, v + r)
    }

    /// The shape's exact maximal length (maximum Feret diameter), px.
    pub fn max_length_px(&self) -> f64 {
        match *self {
            Shape::Disc { radius, .. } => 2.0 * radius,
            Shape::Rectangle {
                length, breadth, ..
            } => length.hypot(breadth),
            Shape::Triangle { a, b, c } => {
                let d = |p: (f64, f64), q: (f64, f64)| (p.0 - q.0).hypot(p.1 - q.1);
                d(a, b).max(d(b, c)).max(d(c, a))
            }
        }
    }

    /// The shape's exact area centroid (u, v), px.
    pub fn centroid_px(&self) -> (f64, f64) {
        match *self {
            Shape::Disc { u, v, .. } | Shape::Rectangle { u, v, .. } => (u, v),
            Shape::Triangle { a, b, c } => ((a.0 + b.0 + c.0) / 3.0, (a.1 + b.1 + c.1) / 3.0),
        }
    }
}

/// A synthetic frame: background, shapes painted in order, noise.
#[derive(Debug, Clone)]
pub(crate) struct SyntheticScene {
    pub width_px: u32,
    pub height_px: u32,
    pub background: Background,
    pub shapes: Vec<(Shape, [f64; 3])>,
    /// Per-channel Gaussian noise, grey levels.
    pub noise_sigma: f64,
    pub seed: u64,
    /// Samples per pixel side (coverage resolution 1 / n²).
    pub supersample: u32,
}

impl SyntheticScene {
    pub fn new(width_px: u32, height_px: u32, background: Background) -> Self {
        Self {
            width_px,
            height_px,
            background,
            shapes: Vec::new(),
            noise_sigma: 0.0,
            seed: 1,
            supersample: 16,
        }
    }

    pub fn add_disc(&mut self, u: f64, v: f64, radius: f64, rgb: [f64; 3]) -> Shape {
        let s = Shape::Disc { u, v, radius };
        self.shapes.push((s, rgb));
        s
    }

    pub fn add_rectangle(
        &mut self,
        (u, v): (f64, f64),
        (length, breadth): (f64, f64),
        angle_rad: f64,
        rgb: [f64; 3],
    ) -> Shape {
        let s = Shape::Rectangle {
            u,
            v,
            length,
            breadth,
            angle_rad,
        };
        self.shapes.push((s, rgb));
        s
    }

    pub fn add_triangle(
        &mut self,
        a: (f64, f64),
        b: (f64, f64),
        c: (f64, f64),
        rgb: [f64; 3],
    ) -> Shape {
        let s = Shape::Triangle { a, b, c };
        self.shapes.push((s, rgb));
        s
    }

    /// Background colour at (u, v).
    pub fn background_at(&self, u: f64, v: f64) -> [f64; 3] {
        self.background.colour(u, v, f64::from(self.height_px))
    }

    /// The frame as tightly packed RGBA8, alpha 255.
    pub fn render(&self) -> Vec<u8> {
        let (w, h) = (self.width_px as usize, self.height_px as usize);
        let mut colour: Vec<[f64; 3]> = (0..w * h)
            .map(|i| self.background_at((i % w) as f64 + 0.5, (i / w) as f64 + 0.5))
            .collect();
        let n = self.supersample.max(1);
        let step = 1.0 / f64::from(n);
        for (shape, rgb) in &self.shapes {
            let (u0, v0, u1, v1) = shape.bounds();
            let iu0 = u0.floor().max(0.0) as usize;
            let iv0 = v0.floor().max(0.0) as usize;
            let iu1 = (u1.ceil().max(0.0) as usize).min(w);
            let iv1 = (v1.ceil().max(0.0) as usize).min(h);
            for j in iv0..iv1 {
                for i in iu0..iu1 {
                    let mut inside = 0u32;
                    for sj in 0..n {
                        for si in 0..n {
                            let pu = i as f64 + (f64::from(si) + 0.5) * step;
                            let pv = j as f64 + (f64::from(sj) + 0.5) * step;
                            inside += u32::from(shape.contains(pu, pv));
                        }
                    }
                    let alpha = f64::from(inside) / f64::from(n * n);
                    let px = &mut colour[j * w + i];
                    for c in 0..3 {
                        px[c] = alpha * rgb[c] + (1.0 - alpha) * px[c];
                    }
                }
            }
        }
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(self.seed);
        let noise = Normal::new(0.0, self.noise_sigma.max(0.0)).ok();
        let mut out = Vec::with_capacity(w * h * 4);
        for px in colour {
            for value in px {
                let n = noise.map_or(0.0, |d| d.sample(&mut rng));
                out.push((value + n).round().clamp(0.0, 255.0) as u8);
            }
            out.push(255);
        }
        out
    }
}
