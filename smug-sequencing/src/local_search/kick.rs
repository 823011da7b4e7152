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

/// The positions of a kick's cuts (`blocks` blocks of 1..=`max_block` nodes) from a
/// random position of a tour of `n` nodes.
fn random_cut_positions(
    n: usize,
    blocks: usize,
    max_block: usize,
    rng: &mut impl Rng,
) -> [usize; 4] {
    let mut positions = [0usize; 4];
    let mut p = rng.random_range(0..n);
    for position in positions.iter_mut().take(blocks + 1) {
        *position = p;
        p += rng.random_range(1..=max_block);
    }
    positions
}

impl Search<'_> {
    /// Applies a random double bridge whose blocks have 1..=`max_block` nodes and starts
    /// at a random position (with `around`, placed so that one of its nodes lies in a
    /// moved block); activates the nodes around the changed legs. Returns the cost
    /// change, or `None` when the tour is too short or only fixed legs were hit.
    pub(crate) fn kick(
        &mut self,
        kind: Kick,
        rng: &mut impl Rng,
        max_block: usize,
        around: Option<&[usize]>,
    ) -> Option<f64> {
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
            let positions = match around {
                Some(nodes) if !nodes.is_empty() => {
                    self.cut_positions_around(nodes, blocks, max_block, rng)
                }
                _ => random_cut_positions(n, blocks, max_block, rng),
            };
            let mut cuts = [0usize; 4];
            for (cut, &p) in cuts.iter_mut().zip(&positions[..=blocks]) {
                *cut = self.tour.at(p);
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

    /// The positions of a kick's cuts (`blocks` blocks of 1..=`max_block` nodes) such
    /// that a node drawn from `nodes` lies in one of its blocks.
    fn cut_positions_around(
        &self,
        nodes: &[usize],
        blocks: usize,
        max_block: usize,
        rng: &mut impl Rng,
    ) -> [usize; 4] {
        let n = self.tour.len();
        let node = nodes[rng.random_range(0..nodes.len())];
        let mut lengths = [0usize; 3];
        for length in lengths.iter_mut().take(blocks) {
            *length = rng.random_range(1..=max_block);
        }
        let span: usize = lengths.iter().sum();
        let mut positions = [0usize; 4];
        positions[0] = (self.tour.pos(node) + n - rng.random_range(0..span)) % n;
        for b in 0..blocks {
            positions[b + 1] = positions[b] + lengths[b];
        }
        positions
    }

    /// Cost of the legs entering the nodes `cuts`.
    fn boundary_cost(&self, cuts: &[usize]) -> f64 {
        cuts.iter()
            .map(|&c| self.dist.d(self.tour.prev(c), c))
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::costs::Dist;
    use crate::local_search::neighbours::Neighbours;
    use rand::SeedableRng;
    use smug_core::rng::StageRng;
    use smug_core::CostMatrix;

    /// A segment swap placed around a node moves that node: it lies in one of the two
    /// swapped blocks, whatever blocks are drawn (the first and last nodes included).
    #[test]
    fn a_segment_swap_around_a_node_moves_it() {
        let n = 120;
        let costs = CostMatrix::from_fn(n, |i, j| (i as f64 - j as f64).abs()).unwrap();
        let dist = Dist::new(&costs);
        let neighbours = Neighbours::new(&dist, 8);
        let order: Vec<usize> = (0..n).collect();
        let mut rng = StageRng::seed_from_u64(1);
        for node in [0, 1, 57, n - 1] {
            for _ in 0..200 {
                let mut search = Search::new(&dist, &neighbours, &order, None);
                let before = search.tour.pos(node);
                search
                    .kick(Kick::SegmentSwap, &mut rng, 50, Some(&[node]))
                    .unwrap();
                assert_ne!(search.tour.pos(node), before, "node {node}");
            }
        }
    }
}
