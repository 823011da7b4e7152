//! The memory limit: inputs whose dense matrices, grids or roadmaps would need more than
//! it are refused, naming what and how much, instead of exhausting the machine.
//!
//! The limit is a value (default 8 GB) carried by each pipeline's
//! [`RunContext`](crate::run_context::RunContext), set from its config's
//! `[limits] memory_gb`; code that allocates is handed the limit it must respect.

/// The default limit in bytes (8 GB).
pub const DEFAULT_MEMORY_BYTES: u64 = 8_000_000_000;

/// The largest allocation of one structure, in bytes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MemoryLimit {
    /// The limit in bytes.
    pub bytes: u64,
}

impl Default for MemoryLimit {
    fn default() -> Self {
        Self {
            bytes: DEFAULT_MEMORY_BYTES,
        }
    }
}

impl MemoryLimit {
    /// A limit of `bytes`.
    pub fn bytes(bytes: u64) -> Self {
        Self { bytes }
    }

    /// `Ok` when `count` items of `bytes_each` bytes fit this limit; else an error
    /// naming `what`, the count, the size it would need and the limit.
    pub fn check(&self, what: &str, count: u128, bytes_each: u128) -> Result<(), MemoryLimitError> {
        let needed = count.saturating_mul(bytes_each);
        let limit = u128::from(self.bytes);
        if needed <= limit {
            return Ok(());
        }
        Err(MemoryLimitError {
            what: what.to_string(),
            count,
            bytes_each,
            needed,
            limit,
        })
    }
}

/// The config's `[limits]` section.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct LimitsConfig {
    /// Largest allocation of one structure, in GB (10⁹ bytes).
    pub memory_gb: f64,
}

impl Default for LimitsConfig {
    fn default() -> Self {
        Self {
            memory_gb: DEFAULT_MEMORY_BYTES as f64 / 1e9,
        }
    }
}

impl LimitsConfig {
    /// The first key with a value outside its domain: `(key, message)`.
    pub fn invalid_field(&self) -> Option<(&'static str, String)> {
        let gb = self.memory_gb;
        (!(gb.is_finite() && gb > 0.0 && gb <= 1e9)).then(|| {
            (
                "memory_gb",
                format!("must be a number of GB in (0, 1e9], got {gb}"),
            )
        })
    }

    /// The memory limit this section sets.
    pub fn memory(&self) -> MemoryLimit {
        MemoryLimit::bytes((self.memory_gb * 1e9) as u64)
    }
}

/// An allocation above the memory limit: what, how many of what size, and the limit.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error(
    "{what} ({count} × {bytes_each} B) would need {}, above the memory limit of {} \
     (`limits.memory_gb`)",
    human(*needed),
    human(*limit)
)]
pub struct MemoryLimitError {
    /// What would be allocated, e.g. `a 100×100 grid`.
    pub what: String,
    /// How many items.
    pub count: u128,
    /// Bytes per item.
    pub bytes_each: u128,
    /// Bytes needed.
    pub needed: u128,
    /// The limit in bytes.
    pub limit: u128,
}

/// [`MemoryLimit::check`] against the default limit (8 GB), for structures built
/// outside a pipeline.
pub fn check_allocation(what: &str, count: u128, bytes_each: u128) -> Result<(), MemoryLimitError> {
    MemoryLimit::default().check(what, count, bytes_each)
}

/// Bytes in B, kB, MB, GB, TB … with three significant digits.
pub fn human(bytes: u128) -> String {
    let units = ["B", "kB", "MB", "GB", "TB", "PB", "EB", "ZB", "YB"];
    let mut value = bytes as f64;
    let mut unit = 0;
    while value >= 1000.0 && unit + 1 < units.len() {
        value /= 1000.0;
        unit += 1;
    }
    if unit == 0 {
        format!("{bytes} B")
    } else {
        format!("{value:.3} {}", units[unit])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn allocations_above_the_limit_are_refused_with_their_size() {
        assert!(check_allocation("a grid", 1000, 4).is_ok());
        let err = check_allocation("the lunar world's grid", 4_000_000_000, 4).unwrap_err();
        assert_eq!(
            err.to_string(),
            "the lunar world's grid (4000000000 × 4 B) would need 16.000 GB, above the \
             memory limit of 8.000 GB (`limits.memory_gb`)"
        );
        assert!(
            check_allocation("x", u128::MAX, u128::MAX).is_err(),
            "no overflow"
        );
        let small = MemoryLimit::bytes(1000);
        assert!(small.check("a grid", 250, 4).is_ok());
        assert!(small.check("a grid", 251, 4).is_err());
        assert_eq!(
            LimitsConfig { memory_gb: 0.2 }.memory(),
            MemoryLimit::bytes(200_000_000)
        );
        assert_eq!(human(999), "999 B");
        assert_eq!(human(1_500_000), "1.500 MB");
    }
}
