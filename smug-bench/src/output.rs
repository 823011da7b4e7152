//! The output convention of every `smug bench` command: the Markdown report on stdout
//! and in `--out`, the raw numbers as JSON in `--json` (default: beside `--out`).

use serde::Serialize;
use std::path::{Path, PathBuf};

/// What every report-writing bench takes: overrides, and where its report and raw
/// numbers go.
#[derive(clap::Args, Clone, Debug, Default)]
pub struct ReportArgs {
    /// Override a config key (every run of every planner and mode, after their own
    /// overrides).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// Write the Markdown report here (else stdout only).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Write the raw numbers as JSON here (default: beside `--out`, as `.json`).
    #[arg(long)]
    pub json: Option<PathBuf>,
}

impl ReportArgs {
    /// Prints `report` and writes it and the raw numbers `raw` where asked
    /// ([`write_report`] with `--out` and `--json`).
    pub fn write(&self, report: &str, raw: &impl Serialize) -> crate::Result<()> {
        write_report(report, raw, self.out.as_deref(), self.json.as_deref())
    }
}

/// Where the raw JSON goes: `--json`, else `--out` with the extension `.json`.
pub fn json_path(out: Option<&Path>, json: Option<&Path>) -> Option<PathBuf> {
    json.map(Path::to_path_buf)
        .or_else(|| out.map(|p| p.with_extension("json")))
}

/// Prints the report and writes it and the raw numbers where asked.
pub fn write_report(
    report: &str,
    raw: &impl Serialize,
    out: Option<&Path>,
    json: Option<&Path>,
) -> crate::Result<()> {
    print!("{report}");
    if let Some(path) = out {
        write_file(path, report)?;
    }
    if let Some(path) = json_path(out, json) {
        write_file(&path, &serde_json::to_string_pretty(raw)?)?;
    }
    Ok(())
}

fn write_file(path: &Path, text: &str) -> crate::Result<()> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)
            .map_err(|e| crate::error::invalid!("{}: cannot create: {e}", dir.display()))?;
    }
    smug_core::output::write_atomic(path, text.as_bytes())
        .map_err(|e| crate::error::invalid!("{}: cannot write: {e}", path.display()))
}
