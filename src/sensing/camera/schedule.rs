//! The camera's frame schedule: which ticks take a frame, how frames are numbered, and the
//! latency queue that delivers each frame's record `latency_frames` frames after it was taken
//! and holds it between frames.

use super::FrameRecord;
use crate::sensing::geometry::CaptureGeometry;
use std::collections::VecDeque;

/// A frame taken: when, and the geometry it was taken in.
#[derive(Debug, Clone, Copy)]
pub(super) struct Exposure {
    /// Frame number (0-based).
    pub index: u64,
    /// Time the frame was taken, s.
    pub t_s: f64,
    /// Where follower and target were.
    pub geometry: CaptureGeometry,
}

/// The frame clock and the latency queue.
#[derive(Debug)]
pub(super) struct FrameSchedule {
    period_ticks: u64,
    latency_frames: u64,
    /// Frames taken.
    frames: u64,
    /// Records not yet delivered, oldest first.
    pending: VecDeque<FrameRecord>,
    /// The record the guidance holds.
    held: Option<FrameRecord>,
    /// The frame read back but not measured yet (latency of a frame or more).
    unmeasured: Option<Exposure>,
}

impl FrameSchedule {
    /// A frame every `period_ticks` ticks, delivered `latency_frames` frames later.
    pub fn new(period_ticks: u64, latency_frames: u64) -> Self {
        Self {
            period_ticks,
            latency_frames,
            frames: 0,
            pending: VecDeque::new(),
            held: None,
            unmeasured: None,
        }
    }

    /// Whether a frame is taken at this tick.
    pub fn is_frame_tick(&self, tick: u64) -> bool {
        tick.is_multiple_of(self.period_ticks)
    }

    /// The number the next frame will get.
    pub fn next_index(&self) -> u64 {
        self.frames
    }

    /// Numbers the next frame, taken at `t_s` in `geometry`.
    pub fn expose(&mut self, t_s: f64, geometry: &CaptureGeometry) -> Exposure {
        let exposure = Exposure {
            index: self.frames,
            t_s,
            geometry: *geometry,
        };
        self.frames += 1;
        exposure
    }

    /// Whether a frame's measurement waits for the next frame (a latency of a frame or more),
    /// so that measuring one overlaps drawing the next.
    pub fn overlaps(&self) -> bool {
        self.latency_frames > 0
    }

    /// The frame left to measure, replaced by `next`.
    pub fn replace_unmeasured(&mut self, next: Option<Exposure>) -> Option<Exposure> {
        std::mem::replace(&mut self.unmeasured, next)
    }

    /// Queues a measured frame's record for delivery.
    pub fn queue(&mut self, record: FrameRecord) {
        self.pending.push_back(record);
    }

    /// The record held once frame `index` has been taken: the latest one at least
    /// `latency_frames` frames old.
    pub fn deliver(&mut self, index: u64) -> Option<FrameRecord> {
        while self
            .pending
            .front()
            .is_some_and(|r| r.index + self.latency_frames <= index)
        {
            self.held = self.pending.pop_front();
        }
        self.held
    }

    /// The record the guidance holds now.
    pub fn held(&self) -> Option<FrameRecord> {
        self.held
    }

    /// Frames taken.
    pub fn frames(&self) -> u64 {
        self.frames
    }
}
