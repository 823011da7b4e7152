//! SMUG's version.

/// SMUG's version (the workspace's), as sweep rows and run ids record it.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");
