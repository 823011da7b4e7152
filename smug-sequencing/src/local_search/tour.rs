//! An array tour: the cycle as an array of nodes plus each node's position, with a
//! journal of moves so that any sequence of moves can be rolled back exactly.

/// One move as the journal keeps it: enough to apply its inverse.
#[derive(Clone, Copy, Debug)]
enum Undo {
    /// `len` positions from `start` were reversed (its own inverse).
    Reverse { start: usize, len: usize },
    /// The blocks `[X][Y]` (`len_x`, `len_y` nodes from `start`) became `[Y][X]`.
    Swap {
        start: usize,
        len_x: usize,
        len_y: usize,
    },
}

/// A cyclic tour over nodes `0..n` (n ≥ 3 for the moves to make sense).
#[derive(Clone, Debug)]
pub(crate) struct ArrayTour {
    order: Vec<usize>,
    pos: Vec<usize>,
    /// Every move since the last commit, oldest first.
    journal: Vec<Undo>,
    scratch: Vec<usize>,
}

impl ArrayTour {
    /// The cycle visiting `order` (a permutation of `0..order.len()`).
    pub(crate) fn new(order: &[usize]) -> Self {
        let mut pos = vec![0; order.len()];
        for (p, &c) in order.iter().enumerate() {
            pos[c] = p;
        }
        Self {
            order: order.to_vec(),
            pos,
            journal: Vec::new(),
            scratch: Vec::new(),
        }
    }

    /// Number of nodes.
    pub(crate) fn len(&self) -> usize {
        self.order.len()
    }

    /// The nodes in array order.
    pub(crate) fn order(&self) -> &[usize] {
        &self.order
    }

    /// Position of `c` in the array.
    pub(crate) fn pos(&self, c: usize) -> usize {
        self.pos[c]
    }

    /// The node at position `p` (taken modulo n).
    #[inline]
    pub(crate) fn at(&self, p: usize) -> usize {
        self.order[p % self.order.len()]
    }

    /// The node after `c` in array order.
    #[inline]
    pub(crate) fn next(&self, c: usize) -> usize {
        let p = self.pos[c] + 1;
        if p == self.order.len() {
            self.order[0]
        } else {
            self.order[p]
        }
    }

    /// The node before `c` in array order.
    #[inline]
    pub(crate) fn prev(&self, c: usize) -> usize {
        let p = self.pos[c];
        if p == 0 {
            self.order[self.order.len() - 1]
        } else {
            self.order[p - 1]
        }
    }

    /// The node after (`forward`) or before `c`.
    #[inline]
    pub(crate) fn step(&self, c: usize, forward: bool) -> usize {
        if forward {
            self.next(c)
        } else {
            self.prev(c)
        }
    }

    /// Steps from `a` forward to `b` (0 when equal).
    #[inline]
    pub(crate) fn forward_distance(&self, a: usize, b: usize) -> usize {
        let n = self.order.len();
        (self.pos[b] + n - self.pos[a]) % n
    }

    /// A journal mark to roll back to.
    pub(crate) fn mark(&self) -> usize {
        self.journal.len()
    }

    /// Undoes every move made after `mark`, newest first.
    pub(crate) fn rollback(&mut self, mark: usize) {
        while self.journal.len() > mark {
            match self.journal.pop() {
                Some(Undo::Reverse { start, len }) => self.reverse_unlogged(start, len),
                Some(Undo::Swap {
                    start,
                    len_x,
                    len_y,
                }) => self.swap_unlogged(start, len_y, len_x),
                None => break,
            }
        }
    }

    /// Forgets the journal: the current tour can no longer be rolled back.
    pub(crate) fn commit(&mut self) {
        self.journal.clear();
    }

    /// Reverses the `len` nodes starting at position `start` (cyclically), journaled.
    fn reverse_positions(&mut self, start: usize, len: usize) {
        self.journal.push(Undo::Reverse { start, len });
        self.reverse_unlogged(start, len);
    }

    /// [`reverse_positions`](Self::reverse_positions) without the journal.
    fn reverse_unlogged(&mut self, start: usize, len: usize) {
        let n = self.order.len();
        let (mut i, mut j) = (start, (start + len + n - 1) % n);
        for _ in 0..len / 2 {
            let (a, b) = (self.order[i], self.order[j]);
            self.order[i] = b;
            self.pos[b] = i;
            self.order[j] = a;
            self.pos[a] = j;
            i = if i + 1 == n { 0 } else { i + 1 };
            j = if j == 0 { n - 1 } else { j - 1 };
        }
    }

    /// 2-opt move: replaces tour edges `{a, b}` and `{c, d}` by `{a, c}` and `{b, d}`.
    ///
    /// Needs `b = next(a), d = next(c)` or `b = prev(a), d = prev(c)`. Reverses whichever
    /// side of the cycle is shorter, so the array orientation may flip.
    pub(crate) fn two_opt(&mut self, a: usize, b: usize, c: usize, d: usize) {
        let (first, last) = if self.next(a) == b { (b, c) } else { (a, d) };
        let n = self.order.len();
        let len = self.forward_distance(first, last) + 1;
        if 2 * len <= n {
            self.reverse_positions(self.pos[first], len);
        } else {
            self.reverse_positions((self.pos[last] + 1) % n, n - len);
        }
    }

    /// Or-3opt segment exchange without reversal: with the cycle cut into the blocks
    /// `A = [a .. b)`, `B = [b .. c)` and `C = [c .. a)` (forward), makes it `A C B`.
    /// Moves only the two shortest blocks.
    pub(crate) fn exchange(&mut self, a: usize, b: usize, c: usize) {
        let len_a = self.forward_distance(a, b);
        let len_b = self.forward_distance(b, c);
        let len_c = self.order.len() - len_a - len_b;
        // A C B is the same cycle as B A C and C B A: swap the cheapest adjacent pair.
        let (first, len_first, len_second) =
            if len_a + len_b <= len_b + len_c && len_a + len_b <= len_c + len_a {
                (a, len_a, len_b)
            } else if len_b + len_c <= len_c + len_a {
                (b, len_b, len_c)
            } else {
                (c, len_c, len_a)
            };
        self.swap_adjacent_blocks(self.pos[first], len_first, len_second);
    }

    /// Makes `[X][Y]` (X of `len_x` nodes at position `start`, Y after it) into `[Y][X]`,
    /// journaled.
    fn swap_adjacent_blocks(&mut self, start: usize, len_x: usize, len_y: usize) {
        self.journal.push(Undo::Swap {
            start,
            len_x,
            len_y,
        });
        self.swap_unlogged(start, len_x, len_y);
    }

    /// [`swap_adjacent_blocks`](Self::swap_adjacent_blocks) without the journal.
    fn swap_unlogged(&mut self, start: usize, len_x: usize, len_y: usize) {
        let n = self.order.len();
        let mut scratch = std::mem::take(&mut self.scratch);
        scratch.clear();
        scratch.extend((0..len_x + len_y).map(|k| self.order[(start + k) % n]));
        let rotated = scratch[len_x..].iter().chain(&scratch[..len_x]);
        for (k, &c) in rotated.enumerate() {
            let p = (start + k) % n;
            self.order[p] = c;
            self.pos[c] = p;
        }
        self.scratch = scratch;
    }

    /// The cycle read from `start` in the direction that leaves `last` for the end.
    pub(crate) fn path_from(&self, start: usize, last: Option<usize>) -> Vec<usize> {
        let forward = last.is_none_or(|end| self.prev(start) == end);
        let mut out = Vec::with_capacity(self.len());
        let mut c = start;
        for _ in 0..self.len() {
            out.push(c);
            c = self.step(c, forward);
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cycle_edges(t: &ArrayTour) -> Vec<(usize, usize)> {
        let mut edges: Vec<_> = t
            .order()
            .iter()
            .map(|&c| {
                let d = t.next(c);
                (c.min(d), c.max(d))
            })
            .collect();
        edges.sort_unstable();
        edges
    }

    #[test]
    fn two_opt_swaps_two_edges_and_rolls_back() {
        let mut t = ArrayTour::new(&[0, 1, 2, 3, 4, 5, 6, 7]);
        let before = t.order().to_vec();
        let mark = t.mark();
        t.two_opt(1, 2, 5, 6);
        let edges = cycle_edges(&t);
        assert!(edges.contains(&(1, 5)) && edges.contains(&(2, 6)));
        assert!(!edges.contains(&(1, 2)) && !edges.contains(&(5, 6)));
        // The long side: reverses the complement.
        t.two_opt(0, 1, 6, 7);
        assert!(cycle_edges(&t).contains(&(0, 6)));
        t.rollback(mark);
        assert_eq!(t.order(), &before[..]);
    }

    #[test]
    fn exchange_moves_blocks_without_reversal() {
        let mut t = ArrayTour::new(&[0, 1, 2, 3, 4, 5, 6, 7, 8, 9]);
        t.exchange(1, 3, 4); // A = [1 2], B = [3], C = [4 .. 0] → A C B
        assert_eq!(t.path_from(1, None), vec![1, 2, 4, 5, 6, 7, 8, 9, 0, 3]);
        let mut t = ArrayTour::new(&[0, 1, 2, 3, 4, 5, 6, 7, 8, 9]);
        t.exchange(2, 8, 0); // A = [2..7], B = [8 9], C = [0 1]
        assert_eq!(t.path_from(2, None), vec![2, 3, 4, 5, 6, 7, 0, 1, 8, 9]);
        for c in 0..10 {
            assert_eq!(t.at(t.pos(c)), c);
        }
    }

    #[test]
    fn random_moves_roll_back_to_the_exact_original_tour() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(34);
        for n in [3, 4, 5, 8, 13, 50] {
            for _case in 0..40 {
                let mut order: Vec<usize> = (0..n).collect();
                for i in (1..n).rev() {
                    order.swap(i, rng.random_range(0..=i));
                }
                let mut t = ArrayTour::new(&order);
                // Some committed moves first: the marks count from the commit.
                if n >= 5 {
                    t.two_opt(
                        order[0],
                        t.next(order[0]),
                        order[n / 2],
                        t.next(order[n / 2]),
                    );
                    t.commit();
                }
                let original = t.order().to_vec();
                let mut marks = Vec::new();
                let mut states = Vec::new();
                for _move in 0..rng.random_range(1..20) {
                    marks.push(t.mark());
                    states.push(t.order().to_vec());
                    let (a, c) = (rng.random_range(0..n), rng.random_range(0..n));
                    let (a, c) = (t.at(a), t.at(c));
                    if rng.random_bool(0.5) {
                        let (b, d) = (t.next(a), t.next(c));
                        if a != c && b != c && d != a {
                            t.two_opt(a, b, c, d);
                        }
                    } else {
                        let b = t.at(t.pos(a) + rng.random_range(1..n));
                        let c = t.at(t.pos(b) + rng.random_range(0..n - t.forward_distance(a, b)));
                        if c != a && c != b {
                            t.exchange(a, b, c);
                        }
                    }
                    assert!((0..n).all(|c| t.at(t.pos(c)) == c));
                }
                // Back to each intermediate state, then to the committed tour.
                let k = rng.random_range(0..marks.len());
                t.rollback(marks[k]);
                assert_eq!(t.order(), &states[k][..], "n = {n}");
                t.rollback(0);
                assert_eq!(t.order(), &original[..], "n = {n}");
                assert!((0..n).all(|c| t.at(t.pos(c)) == c));
            }
        }
    }

    #[test]
    fn path_from_honours_the_end() {
        let t = ArrayTour::new(&[3, 0, 1, 2]);
        assert_eq!(t.path_from(0, Some(3)), vec![0, 1, 2, 3]);
        assert_eq!(t.path_from(0, Some(1)), vec![0, 3, 2, 1]);
    }
}
