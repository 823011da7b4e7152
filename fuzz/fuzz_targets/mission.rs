//! The mission file reader, as TOML and as JSON.
#![no_main]

mod common;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    for name in ["m.toml", "m.json"] {
        let path = common::scratch_file(name, data);
        let _ = smug_worlds::mission_file::load_mission(&path);
    }
});
