//! Procedural indoor world (in progress).
