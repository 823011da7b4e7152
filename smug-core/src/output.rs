//! Writing outputs safely: each file is written whole or not at all, and never over
//! one of the run's own inputs.

use std::io::Write;
use std::path::{Path, PathBuf};

/// Writes `bytes` to `path` atomically: into a temporary file beside it, flushed to
/// disk, then renamed over `path`. A run killed or failing midway leaves the previous
/// file intact (or none), never a truncated one.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let dir = path
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let name = path
        .file_name()
        .ok_or_else(|| std::io::Error::new(std::io::ErrorKind::InvalidInput, "not a file name"))?;
    let temporary = dir.join(format!(
        ".{}.{}.tmp",
        name.to_string_lossy(),
        std::process::id()
    ));
    let written = (|| {
        let mut file = std::fs::File::create(&temporary)?;
        file.write_all(bytes)?;
        file.sync_all()?;
        std::fs::rename(&temporary, path)
    })();
    if written.is_err() {
        let _ = std::fs::remove_file(&temporary);
    }
    written
}

/// The first of `outputs` that is one of `inputs` (the same file, however named), if
/// any: writing it would destroy what the run read.
pub fn output_over_input<'a>(outputs: &'a [PathBuf], inputs: &[PathBuf]) -> Option<&'a Path> {
    let inputs: Vec<PathBuf> = inputs
        .iter()
        .filter_map(|p| p.canonicalize().ok())
        .collect();
    outputs
        .iter()
        .find(|out| out.canonicalize().is_ok_and(|c| inputs.contains(&c)))
        .map(PathBuf::as_path)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("smug-output-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn a_write_replaces_the_file_whole_and_leaves_no_temporary() {
        let dir = scratch("replace");
        let path = dir.join("plan.json");
        write_atomic(&path, b"old").unwrap();
        write_atomic(&path, b"new").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"new");
        let names: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names, vec![std::ffi::OsString::from("plan.json")]);
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[test]
    fn a_failed_write_leaves_the_previous_file_intact() {
        let dir = scratch("failed");
        let path = dir.join("plan.json");
        write_atomic(&path, b"previous").unwrap();
        // The temporary file's place is taken by a directory: the write fails.
        let blocker = dir.join(format!(".plan.json.{}.tmp", std::process::id()));
        std::fs::create_dir_all(&blocker).unwrap();
        assert!(write_atomic(&path, b"new").is_err());
        assert_eq!(std::fs::read(&path).unwrap(), b"previous");
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[test]
    fn an_output_that_is_an_input_is_found_under_another_name() {
        let dir = scratch("input");
        let config = dir.join("mission.toml");
        std::fs::write(&config, "x = 1").unwrap();
        let outputs = [dir.join("plan.json"), dir.join("sub/../mission.toml")];
        std::fs::create_dir_all(dir.join("sub")).unwrap();
        let found = output_over_input(&outputs, std::slice::from_ref(&config));
        assert_eq!(found, Some(outputs[1].as_path()));
        assert_eq!(output_over_input(&outputs[..1], &[config]), None);
        std::fs::remove_dir_all(dir).unwrap();
    }
}
