//! SMUG point-to-point planners (LazyPRM*).
#![warn(missing_docs)]
