//! Shared by the fuzz targets: a per-process scratch directory for readers that take
//! paths, and splitting one input into parts.

use std::path::PathBuf;
use std::sync::OnceLock;

/// A scratch directory of this process, created once.
pub fn scratch() -> &'static PathBuf {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("smug-fuzz-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("scratch directory");
        dir
    })
}

/// Writes `bytes` to `name` in the scratch directory and returns its path.
pub fn scratch_file(name: &str, bytes: &[u8]) -> PathBuf {
    let path = scratch().join(name);
    std::fs::write(&path, bytes).expect("scratch file");
    path
}

/// Splits `data` at the first `\n---\n` into (head, tail); the tail is empty without one.
#[allow(dead_code)] // not every target splits its input
pub fn split_parts(data: &[u8]) -> (&[u8], &[u8]) {
    const SEP: &[u8] = b"\n---\n";
    match data.windows(SEP.len()).position(|w| w == SEP) {
        Some(i) => (&data[..i], &data[i + SEP.len()..]),
        None => (data, &[]),
    }
}
