//! Loss episodes: the runs of consecutive frames in which the target was not measured (out of
//! the image, too small, hidden), each with its start, its length and whether a frame measured
//! the target again. The same log keeps false locks: the runs of measured frames whose blob
//! was not the target (`FrameRecord::on_target`), ended by a frame that measured the target.

use serde::Serialize;

/// One run of lost frames.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LossEpisode {
    /// Time of the first lost frame, s.
    pub start_s: f64,
    /// Lost frames in the episode.
    pub frames: u64,
    /// From the first lost frame to the frame that measured the target again (or to the
    /// last frame taken, when none did), s.
    pub length_s: f64,
    /// Whether a frame measured the target again.
    pub found: bool,
}

/// The episodes of a run, fed frame by frame in the order they were taken.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LossLog {
    closed: Vec<LossEpisode>,
    open: Option<LossEpisode>,
}

impl LossLog {
    /// Records a frame taken at `t_s` that did (`measured`) or did not measure the target.
    pub fn record(&mut self, t_s: f64, measured: bool) {
        match (&mut self.open, measured) {
            (None, false) => {
                self.open = Some(LossEpisode {
                    start_s: t_s,
                    frames: 1,
                    length_s: 0.0,
                    found: false,
                })
            }
            (Some(open), false) => {
                open.frames += 1;
                open.length_s = t_s - open.start_s;
            }
            (Some(open), true) => {
                open.length_s = t_s - open.start_s;
                open.found = true;
                self.closed.push(*open);
                self.open = None;
            }
            (None, true) => {}
        }
    }

    /// The start of the episode still open (the target not found again yet), s.
    pub fn open_since_s(&self) -> Option<f64> {
        self.open.map(|e| e.start_s)
    }

    /// Every episode so far, the one still open (not found) last.
    pub fn episodes(&self) -> Vec<LossEpisode> {
        self.closed
            .iter()
            .chain(self.open.iter())
            .copied()
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn episodes_open_close_and_stay_open_at_the_end() {
        let mut log = LossLog::default();
        for (t, measured) in [
            (0.0, true),
            (0.1, false),
            (0.2, false),
            (0.3, true),
            (0.4, false),
        ] {
            log.record(t, measured);
        }
        let e = log.episodes();
        assert_eq!(e.len(), 2);
        assert_eq!((e[0].start_s, e[0].frames, e[0].found), (0.1, 2, true));
        assert!((e[0].length_s - 0.2).abs() < 1e-12);
        assert_eq!(
            (e[1].start_s, e[1].frames, e[1].found, e[1].length_s),
            (0.4, 1, false, 0.0)
        );
    }
}
