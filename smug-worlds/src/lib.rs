//! SMUG worlds: procedural lunar and indoor worlds, map import and export.
#![warn(missing_docs)]
