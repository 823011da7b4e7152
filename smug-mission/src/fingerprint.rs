//! What a saved roadmap was built for, as a replan checks it: the
//! [`Fingerprint`] of a config on the world it built (before a mission state's
//! obstacles are added).

use smug_core::config::LoadedConfig;
use smug_core::digest::Digest;
use smug_core::stages::Fingerprint;
use smug_core::world::World;

/// The fingerprint of `loaded` on `world` (the world as built from the config, before
/// a mission state's obstacles are added): digests of the world's name and elevation
/// grid, of the `[robot]` section and of the resolved config table.
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
        config: Digest::hex_of(loaded.table.to_string().as_bytes()),
    }
}
