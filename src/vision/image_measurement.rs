//! The three numbers the image pipeline delivers per frame (3.1)-(3.7), in the seed's image
//! coordinates: what the sensing transform turns into r.

/// What the image pipeline (or a model of it) says about the target in one frame, in pixels
/// relative to the principal point (3.1).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ImageMeasurement {
    /// Centroid, horizontal, positive right, px.
    pub y_i_px: f64,
    /// Centroid, vertical, positive up, px.
    pub z_i_px: f64,
    /// Maximal length of the silhouette, px.
    pub b_i_px: f64,
}

impl ImageMeasurement {
    /// aI = sqrt(l² + yI² + zI²) / bI (3.7): the range in units of the target's size.
    pub fn scaled_range(&self, focal_px: f64) -> f64 {
        (focal_px * focal_px + self.y_i_px * self.y_i_px + self.z_i_px * self.z_i_px).sqrt()
            / self.b_i_px
    }

    /// The target size this measurement implies at a known range: ‖R‖ / aI, ft. (3.7) takes
    /// the size as the target's maximal dimension b; a real silhouette's depends on the view
    /// (seed 8.2), and this is what the camera saw.
    pub fn apparent_size_ft(&self, focal_px: f64, range_ft: f64) -> f64 {
        range_ft / self.scaled_range(focal_px)
    }
}
