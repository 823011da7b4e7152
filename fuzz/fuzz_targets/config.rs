//! The TOML config loader with `--set` overrides: the input's leading `--set key=value`
//! lines are overrides, the rest is the config (includes resolve against `configs/`).
#![no_main]

use libfuzzer_sys::fuzz_target;
use smug_core::LoadedConfig;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let mut overrides = Vec::new();
    let mut rest = text;
    while let Some(line) = rest.strip_prefix("--set ") {
        let (value, tail) = line.split_once('\n').unwrap_or((line, ""));
        overrides.push(value.to_string());
        rest = tail;
    }
    let base = Path::new(env!("CARGO_MANIFEST_DIR")).join("../configs");
    if let Ok(loaded) = LoadedConfig::from_text(rest, "fuzz.toml", &base, &overrides) {
        let _ = loaded.input_files();
    }
});
