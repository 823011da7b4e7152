//! SMUG validity: traversability estimators, state and motion validity checkers.
#![warn(missing_docs)]
