//! Helpers shared by the workspace tests that plan the shipped configs.

use smug_core::LoadedConfig;
use std::path::Path;

/// The shipped config `configs/NAME` loaded with the `KEY=VALUE` overrides `set`.
pub fn shipped_config(name: &str, set: &[&str]) -> LoadedConfig {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../configs")
        .join(name);
    let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
    LoadedConfig::from_file(&path, &set).unwrap()
}
