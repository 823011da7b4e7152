//! A sweep's rows as JSON lines: appended one whole line per run as runs finish, and
//! read back for the run ids already done (resume).

use super::row::SweepRow;
use super::spec::SweepError;
use std::collections::HashSet;
use std::io::{Read, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

/// The runs a rows file already holds.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct DoneRuns {
    /// The run ids of its rows.
    pub ids: HashSet<String>,
    /// Lines that are not a row (e.g. the last line of a sweep killed while writing
    /// it): their runs run again.
    pub unreadable_lines: usize,
}

/// The runs `path` holds; none when it does not exist.
pub fn done_runs(path: &Path) -> Result<DoneRuns, SweepError> {
    let text = match std::fs::read_to_string(path) {
        Ok(text) => text,
        Err(err) if err.kind() == std::io::ErrorKind::NotFound => return Ok(DoneRuns::default()),
        Err(source) => return Err(rows_error(path, "cannot read", source)),
    };
    let mut done = DoneRuns::default();
    for line in text.lines().filter(|line| !line.trim().is_empty()) {
        match serde_json::from_str::<SweepRow>(line) {
            Ok(row) => {
                done.ids.insert(row.run_id);
            }
            Err(_) => done.unreadable_lines += 1,
        }
    }
    Ok(done)
}

/// Appends rows to a rows file, one whole line each, flushed as written.
pub struct RowWriter {
    file: std::fs::File,
    path: PathBuf,
}

impl RowWriter {
    /// Opens `path` to append to (creates it); a last line cut short is ended first,
    /// so the next row starts a line of its own.
    pub fn append_to(path: &Path) -> Result<Self, SweepError> {
        let mut file = std::fs::OpenOptions::new()
            .create(true)
            .read(true)
            .append(true)
            .open(path)
            .map_err(|source| rows_error(path, "cannot open", source))?;
        if ends_without_newline(&mut file)
            .map_err(|source| rows_error(path, "cannot read", source))?
        {
            file.write_all(b"\n")
                .map_err(|source| rows_error(path, "cannot write", source))?;
        }
        Ok(Self {
            file,
            path: path.to_path_buf(),
        })
    }

    /// Appends `row` as one line.
    pub fn write(&mut self, row: &SweepRow) -> Result<(), SweepError> {
        let line = row.to_json_line() + "\n";
        self.file
            .write_all(line.as_bytes())
            .and_then(|()| self.file.flush())
            .map_err(|source| rows_error(&self.path, "cannot write", source))
    }
}

/// Whether a non-empty file's last byte is not a newline.
fn ends_without_newline(file: &mut std::fs::File) -> std::io::Result<bool> {
    if file.metadata()?.len() == 0 {
        return Ok(false);
    }
    file.seek(SeekFrom::End(-1))?;
    let mut last = [0u8];
    file.read_exact(&mut last)?;
    Ok(last[0] != b'\n')
}

fn rows_error(path: &Path, what: &'static str, source: std::io::Error) -> SweepError {
    SweepError::Rows {
        path: path.to_path_buf(),
        what,
        source,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sweep::{RunSpec, RunStatus};

    fn row(id: &str) -> SweepRow {
        let spec = RunSpec {
            config: "x.toml".into(),
            overrides: vec!["a.b=1".into()],
            seed: 3,
            run_id: id.into(),
        };
        SweepRow::failed(&spec, RunStatus::Error, "why".into(), 0.5)
    }

    #[test]
    fn rows_read_back_and_a_line_cut_short_is_ended_then_counted() {
        let dir = std::env::temp_dir().join(format!("smug-jsonl-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("runs.jsonl");
        std::fs::write(
            &path,
            format!("{}\n{{\"run_id\": \"cut", row("a").to_json_line()),
        )
        .unwrap();
        let mut writer = RowWriter::append_to(&path).unwrap();
        writer.write(&row("b")).unwrap();
        let done = done_runs(&path).unwrap();
        assert_eq!(done.ids, HashSet::from(["a".to_string(), "b".to_string()]));
        assert_eq!(done.unreadable_lines, 1);
        let back: SweepRow = serde_json::from_str(
            std::fs::read_to_string(&path)
                .unwrap()
                .lines()
                .last()
                .unwrap(),
        )
        .unwrap();
        assert_eq!(back, row("b"));
        assert_eq!(
            done_runs(&dir.join("none.jsonl")).unwrap(),
            DoneRuns::default()
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
