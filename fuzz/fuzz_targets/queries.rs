//! The point-to-point query CSV reader.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        if let Ok(queries) = smug_core::queries::parse_queries(text, "fuzz.csv") {
            for (s, g) in queries {
                assert!(s.x.is_finite() && g.yaw.is_finite());
            }
        }
    }
});
