//! SMUG sequencing: TSP solvers (Held-Karp, local search) and a TSPLIB reader.
#![warn(missing_docs)]
