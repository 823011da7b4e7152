//! SMUG PoI selection: DP, iterative DP, iterative rubber band.
#![warn(missing_docs)]
