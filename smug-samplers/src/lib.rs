//! SMUG samplers: uniform and informed SE(2) sampling.
#![warn(missing_docs)]
