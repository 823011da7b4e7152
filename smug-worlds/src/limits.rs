//! Size limits shared by the map readers.

/// The largest image or raster a map may have, in pixels (a unit mistake, not a map,
/// beyond).
pub const MAX_PIXELS: u64 = 100_000_000;
