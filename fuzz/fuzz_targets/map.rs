//! The map YAML + occupancy image loader: the input is `yaml \n---\n image bytes`; the
//! image is written as `a.pgm` and `a.png` (the YAML names which one it reads).
#![no_main]

mod common;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let (yaml, image) = common::split_parts(data);
    common::scratch_file("a.pgm", image);
    common::scratch_file("a.png", image);
    let path = common::scratch_file("map.yaml", yaml);
    let _ = smug_worlds::map_file::load_map(&path, 2.0);
});
