//! Procedural lunar world (in progress).
