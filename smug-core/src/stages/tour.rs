//! A visiting order and its kind (closed or open): what sequencers return and what
//! clusters check.

use serde::{Deserialize, Serialize};

/// Whether the tour returns to node 0 or ends at a given node.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum TourKind {
    /// 0 → … → 0.
    Closed,
    /// 0 → … → `end` (an open path; `end` ≠ 0 is visited last).
    OpenTo(usize),
}

/// A visiting order and its cost.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Tour {
    /// Every node exactly once, starting with 0 (and ending with the end node of an
    /// open path); a closed tour's return to 0 is implied.
    pub order: Vec<usize>,
    /// Total cost, including the return leg of a closed tour.
    pub cost: f64,
}

impl Tour {
    /// True when `order` is a permutation of `0..n` starting at 0 (and ending at the
    /// end node of an open path).
    pub fn is_valid_for(&self, n: usize, kind: TourKind) -> bool {
        let mut seen = vec![false; n];
        let is_permutation = self.order.len() == n
            && self
                .order
                .iter()
                .all(|&v| v < n && !std::mem::replace(&mut seen[v], true));
        let ends_right = match kind {
            TourKind::Closed => true,
            TourKind::OpenTo(end) => self.order.last() == Some(&end) || n <= 1,
        };
        is_permutation && self.order.first() == Some(&0) && ends_right
    }
}
