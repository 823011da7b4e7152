//! Perturbations for the iterated local search: double-bridge moves on short blocks.

use super::search::Search;
use rand::Rng;

/// Which double bridge to apply.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Kick {
    /// `A B C → A C B` on two short adjacent blocks: three legs change. LK chains cannot
    /// undo it (it needs no reversal), and it is cheap.
    SegmentSwap,
    /// `X Y Z R → Z Y X R` on three short blocks: four legs change, so no single Or-3opt
    /// move undoes it (the kick for asymmetric instances, whose local search *is* Or-3opt).
    TripleReversal,
}

impl Search<'_> {
    /// Applies a random double bridge whose blocks have 1..=`max_block` nodes and starts
    /// at a random position; activates the nodes around the changed legs. Returns the
    /// cost change, or `None` when the tour is too short or only fixed legs were hit.
    pub(crate) fn kick(&mut self, kind: Kick, rng: &mut impl Rng, max_block: usize) -> Option<f64> {
        let n = self.tour.len();
        let blocks = match kind {
            Kick::SegmentSwap => 2,
            Kick::TripleReversal => 3,
        };
        let max_block = max_block.min((n - 1) / (blocks + 1)).max(1);
        if n < 2 * (blocks + 1) {
            return None;
        }
        for _attempt in 0..8 {
            let mut p = rng.random_range(0..n);
            let mut cuts = [0usize; 4];
            for cut in cuts.iter_mut().take(blocks + 1) {
                *cut = self.tour.at(p);
                p += rng.random_range(1..=max_block);
            }
            let cuts = &cuts[..=blocks];
            if cuts.iter().any(|&c| self.is_fixed(self.tour.prev(c), c)) {
                continue;
            }
            let before = self.boundary_cost(cuts);
            for &c in cuts {
                self.activate(self.tour.prev(c));
                self.activate(c);
            }
            match kind {
                Kick::SegmentSwap => self.tour.exchange(cuts[0], cuts[1], cuts[2]),
                Kick::TripleReversal => {
                    self.tour.exchange(cuts[0], cuts[1], cuts[2]);
                    self.tour.exchange(cuts[1], cuts[2], cuts[3]);
                }
            }
            return Some(self.boundary_cost(cuts) - before);
        }
        None
    }

    /// Cost of the legs entering the nodes `cuts`.
    fn boundary_cost(&self, cuts: &[usize]) -> f64 {
        cuts.iter()
            .map(|&c| self.dist.d(self.tour.prev(c), c))
            .sum()
    }
}
