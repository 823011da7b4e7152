//! What a saved roadmap was built for, as a replan checks it: the
//! [`Fingerprint`] of a config on the world it built (before a mission state's
//! obstacles are added).

use smug_core::config::LoadedConfig;
use smug_core::digest::Digest;
use smug_core::stages::Fingerprint;
use smug_core::world::World;
use std::collections::BTreeMap;

/// The fingerprint of `loaded` on `world` (the world as built from the config, before
/// a mission state's obstacles are added): digests of the world's name and elevation
/// grid, of the `[robot]` section, and of the resolved config table with the contents
/// of the files its `[traversability]` section names (a model, a layer file: see
/// [`traversability_files`]), so a roadmap made with another model is refused.
pub fn fingerprint(loaded: &LoadedConfig, world: &World) -> Fingerprint {
    let grid = &world.elevation;
    let mut digest = Digest::default()
        .update(world.name.as_bytes())
        .update(format!("{:?}", grid.geometry).as_bytes());
    for v in &grid.data {
        digest = digest.update(&v.to_bits().to_le_bytes());
    }
    let robot = format!("{:?}", loaded.config.robot);
    Fingerprint {
        world: digest.hex(),
        robot: Digest::hex_of(robot.as_bytes()),
        config: Digest::default()
            .update(loaded.table.to_string().as_bytes())
            .update(format!("{:?}", traversability_files(loaded)).as_bytes())
            .hex(),
    }
}

/// The files the `[traversability]` section's parameters name (relative to the config
/// file, as its plugins resolve them), each with the FNV-1a digest of its contents:
/// what the layer came from beyond the config's text (an ONNX model, a layer file).
/// Plans record them (`traversability_files` in plan.json).
pub fn traversability_files(loaded: &LoadedConfig) -> BTreeMap<String, String> {
    let Some(params) = loaded
        .table
        .get("traversability")
        .and_then(|t| t.get("params"))
        .and_then(|p| p.as_table())
    else {
        return BTreeMap::new();
    };
    let base = loaded.sources.base_dir();
    params
        .values()
        .filter_map(|v| v.as_str())
        .filter_map(|name| {
            let bytes = std::fs::read(base.join(name)).ok()?;
            Some((name.to_owned(), Digest::hex_of(&bytes)))
        })
        .collect()
}
