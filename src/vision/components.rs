//! Connected components (8-connectivity) of the mask by one raster pass with union-find over
//! the listed mask pixels, then a relabelling pass that gathers per-blob statistics. Work is
//! proportional to the number of mask pixels; the label image is reset sparsely.

/// Inclusive pixel bounding box.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PixelBox {
    /// Leftmost column.
    pub min_u: u32,
    /// Topmost row.
    pub min_v: u32,
    /// Rightmost column.
    pub max_u: u32,
    /// Bottom row.
    pub max_v: u32,
}

/// Statistics of one connected blob of mask pixels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BlobSummary {
    /// Number of mask pixels.
    pub pixel_count: usize,
    /// Mean of the pixel centres, column, px.
    pub mean_u_px: f64,
    /// Mean of the pixel centres, row, px.
    pub mean_v_px: f64,
    /// Bounding box of the mask pixels.
    pub bbox: PixelBox,
}

/// Labels connected mask pixels; owns its label image and union-find forest between frames.
#[derive(Debug, Default, Clone)]
pub(crate) struct ComponentLabeller {
    /// Per pixel: 0 outside the mask, else blob index + 1 (after [`ComponentLabeller::label`]).
    pub labels: Vec<u32>,
    /// Mask pixels labelled last time, to reset `labels` sparsely.
    labelled: Vec<u32>,
    parents: Vec<u32>,
    root_to_blob: Vec<u32>,
    sums: Vec<(f64, f64)>,
    /// Blobs of the last frame, in order of their first pixel in raster order.
    pub blobs: Vec<BlobSummary>,
}

fn find(parents: &mut [u32], mut x: u32) -> u32 {
    while parents[x as usize] != x {
        let grand = parents[parents[x as usize] as usize];
        parents[x as usize] = grand;
        x = grand;
    }
    x
}

fn union(parents: &mut [u32], a: u32, b: u32) -> u32 {
    let ra = find(parents, a);
    let rb = find(parents, b);
    // Smaller index as root keeps roots in raster order of first appearance.
    let (lo, hi) = if ra < rb { (ra, rb) } else { (rb, ra) };
    parents[hi as usize] = lo;
    lo
}

impl ComponentLabeller {
    /// Labels the mask pixels `mask` (indices in raster order) of a `width` x `height` image
    /// with 8-connectivity; afterwards `labels[i]` is the blob index + 1 of pixel `i` (0
    /// outside the mask) and `blobs` holds one summary per blob.
    pub fn label(&mut self, mask: &[u32], width: usize, height: usize) {
        self.label_linked(mask, width, height, 1);
    }

    /// As [`Self::label`], but two mask pixels are in one blob when a chain of mask pixels
    /// joins them with steps of at most `link_radius_px` in u and in v (1: 8-connectivity;
    /// 2 bridges one-pixel gaps, e.g. a wing seen edge-on that rasterises as a broken line).
    pub fn label_linked(
        &mut self,
        mask: &[u32],
        width: usize,
        height: usize,
        link_radius_px: usize,
    ) {
        let n = width * height;
        self.reset(mask, n);
        self.provisional_labels(mask, width, link_radius_px.max(1));
        self.final_blobs(mask, width);
        debug_assert!(height == 0 || self.labels.len() == n);
    }

    /// Clears the last frame's labels (sparsely when the image size is unchanged), the
    /// forest and the blobs, and remembers `mask` as the pixels to clear next time.
    fn reset(&mut self, mask: &[u32], pixel_count: usize) {
        if self.labels.len() != pixel_count {
            self.labels.clear();
            self.labels.resize(pixel_count, 0);
        } else {
            for &i in &self.labelled {
                self.labels[i as usize] = 0;
            }
        }
        self.labelled.clear();
        self.labelled.extend_from_slice(mask);
        self.parents.clear();
        self.blobs.clear();
    }

    /// Pass 1: provisional labels (1-based), unions with the already visited neighbours
    /// within `radius` (W, NW, N, NE for a radius of 1).
    fn provisional_labels(&mut self, mask: &[u32], width: usize, radius: usize) {
        let w = width;
        for &i in mask {
            let i = i as usize;
            let (u, v) = (i % w, i / w);
            let mut label = 0u32;
            let mut neighbour = |j: usize, labels: &[u32], parents: &mut Vec<u32>| {
                let l = labels[j];
                if l != 0 {
                    label = if label == 0 {
                        find(parents, l - 1) + 1
                    } else {
                        union(parents, label - 1, l - 1) + 1
                    };
                }
            };
            // Already visited neighbours: the `radius` rows above (u ± radius) and the
            // `radius` pixels to the left on this row.
            for dv in 1..=radius.min(v) {
                let row = i - dv * w - u;
                for nu in u.saturating_sub(radius)..=(u + radius).min(w - 1) {
                    neighbour(row + nu, &self.labels, &mut self.parents);
                }
            }
            for nu in u.saturating_sub(radius)..u {
                neighbour(i - u + nu, &self.labels, &mut self.parents);
            }
            if label == 0 {
                self.parents.push(self.parents.len() as u32);
                label = self.parents.len() as u32;
            }
            self.labels[i] = label;
        }
    }

    /// Pass 2: final blob indices (in raster order of each blob's first pixel) and the
    /// blobs' counts, bounding boxes and mean pixel centres.
    fn final_blobs(&mut self, mask: &[u32], width: usize) {
        let w = width;
        self.root_to_blob.clear();
        self.root_to_blob.resize(self.parents.len(), u32::MAX);
        self.sums.clear();
        for &i in mask {
            let i = i as usize;
            let (u, v) = ((i % w) as u32, (i / w) as u32);
            let root = find(&mut self.parents, self.labels[i] - 1) as usize;
            if self.root_to_blob[root] == u32::MAX {
                self.root_to_blob[root] = self.blobs.len() as u32;
                self.blobs.push(BlobSummary {
                    pixel_count: 0,
                    mean_u_px: 0.0,
                    mean_v_px: 0.0,
                    bbox: PixelBox {
                        min_u: u,
                        min_v: v,
                        max_u: u,
                        max_v: v,
                    },
                });
                self.sums.push((0.0, 0.0));
            }
            let b = self.root_to_blob[root] as usize;
            self.labels[i] = b as u32 + 1;
            let blob = &mut self.blobs[b];
            blob.pixel_count += 1;
            blob.bbox.min_u = blob.bbox.min_u.min(u);
            blob.bbox.max_u = blob.bbox.max_u.max(u);
            blob.bbox.max_v = v;
            self.sums[b].0 += f64::from(u) + 0.5;
            self.sums[b].1 += f64::from(v) + 0.5;
        }
        for (blob, (su, sv)) in self.blobs.iter_mut().zip(self.sums.iter()) {
            let n = blob.pixel_count as f64;
            blob.mean_u_px = su / n;
            blob.mean_v_px = sv / n;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn label_ascii(rows: &[&str]) -> (ComponentLabeller, usize) {
        let w = rows[0].len();
        let mask: Vec<u32> = rows
            .iter()
            .enumerate()
            .flat_map(|(v, r)| {
                r.bytes()
                    .enumerate()
                    .filter(|(_, b)| *b == b'#')
                    .map(move |(u, _)| (v * w + u) as u32)
            })
            .collect();
        let mut l = ComponentLabeller::default();
        l.label(&mask, w, rows.len());
        (l, w)
    }

    /// 8-connectivity joins diagonal neighbours; a U shape whose arms meet only at the bottom
    /// (the case needing a union after both arms got labels) is one blob; counts and boxes are
    /// exact.
    #[test]
    fn eight_connectivity_and_merging() {
        let (l, w) = label_ascii(&[
            "#.#....#", //
            "#.#...#.", //
            "###.....", //
            "........", //
            "....##..", //
        ]);
        assert_eq!(l.blobs.len(), 3);
        assert_eq!(l.blobs[0].pixel_count, 7);
        assert_eq!(
            l.blobs[0].bbox,
            PixelBox {
                min_u: 0,
                min_v: 0,
                max_u: 2,
                max_v: 2
            }
        );
        assert_eq!(l.blobs[1].pixel_count, 2); // the diagonal pair
        assert_eq!(l.blobs[2].pixel_count, 2);
        assert_eq!(l.labels[0], l.labels[2]);
        assert_eq!(l.labels[7], l.labels[w + 6]);
        assert!((l.blobs[2].mean_u_px - 5.0).abs() < 1e-12);
        assert!((l.blobs[2].mean_v_px - 4.5).abs() < 1e-12);
    }

    /// Relabelling a second, different mask leaves no stale labels from the first.
    #[test]
    fn labels_reset_between_frames() {
        let mut l = ComponentLabeller::default();
        l.label(&[0, 1, 5], 4, 2);
        l.label(&[7], 4, 2);
        assert_eq!(l.labels, vec![0, 0, 0, 0, 0, 0, 0, 1]);
        l.label(&[], 0, 0);
        assert!(l.blobs.is_empty());
    }

    /// A one-pixel gap splits a line with 8-connectivity and is bridged with a link radius
    /// of 2; a two-pixel gap needs 3.
    #[test]
    fn link_radius_bridges_gaps() {
        let mut l = ComponentLabeller::default();
        // Row 0 of a 10-wide image: pixels 0, 1, 3 (gap at 2) and 7 (gap at 4-6).
        let mask = [0u32, 1, 3, 7];
        l.label_linked(&mask, 10, 1, 1);
        assert_eq!(l.blobs.len(), 3);
        l.label_linked(&mask, 10, 1, 2);
        assert_eq!(l.blobs.len(), 2);
        l.label_linked(&mask, 10, 1, 4);
        assert_eq!(l.blobs.len(), 1);
        // Diagonal gap across rows: (0,0) and (2,2) in a 4x4 image.
        l.label_linked(&[0, 10], 4, 4, 2);
        assert_eq!(l.blobs.len(), 1);
        l.label_linked(&[0, 10], 4, 4, 1);
        assert_eq!(l.blobs.len(), 2);
    }
}
