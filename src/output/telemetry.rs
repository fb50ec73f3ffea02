//! `telemetry.csv`: one row per logged tick, written as the run goes so that a run that stops
//! early keeps what it logged.

use super::columns::COLUMNS;
use crate::sim::Snapshot;
use std::fs::File;
use std::io::{Seek, SeekFrom, Write};
use std::path::Path;

/// One telemetry row: column names and values, in column order.
pub type Row = Vec<(&'static str, f64)>;

/// The named values of one telemetry row, in column order: the columns of [`COLUMNS`] that
/// the run has.
pub fn row_of(s: &Snapshot) -> Row {
    let mut row = Vec::with_capacity(96);
    for column in COLUMNS.iter().filter(|c| c.runs.has(s)) {
        column.push_values(s, &mut row);
    }
    row
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
