//! The improvement moves and the don't-look-bit queue that drives them.
//!
//! Symmetric matrices: an LK-style chain of 2-opt flips (depth-limited, breadth 5/3/1,
//! which covers 2-opt and sequential 3-opt) and Or-opt (segments of 1–3 nodes moved
//! elsewhere, in either orientation). Asymmetric matrices: no move reverses a segment —
//! Or-3opt segment exchange (`A B C → A C B`) and Or-opt without reversal.
//! Every move only looks at candidate legs from the neighbour lists; a node whose
//! surroundings did not change is not looked at again ("don't-look bits").

use super::neighbours::Neighbours;
use super::tour::ArrayTour;
use crate::costs::Dist;
use std::collections::VecDeque;

/// Deepest LK chain, in flips.
const LK_MAX_DEPTH: usize = 12;
/// Alternatives tried at the first LK levels (then 1).
const LK_BREADTH: [usize; 2] = [5, 3];
/// Longest segment Or-opt moves.
const OR_OPT_MAX_SEGMENT: usize = 3;

/// A tour being improved, with everything the moves need.
pub(crate) struct Search<'a> {
    pub(crate) dist: &'a Dist,
    pub(crate) neighbours: &'a Neighbours,
    pub(crate) tour: ArrayTour,
    /// A leg no move may remove (end → start of an open path).
    fixed: Option<(usize, usize)>,
    queue: VecDeque<usize>,
    queued: Vec<bool>,
    /// Nodes whose legs changed in the current move.
    touched: Vec<usize>,
    /// Legs added by the current LK chain (they may not be removed again).
    added: Vec<(usize, usize)>,
}

impl<'a> Search<'a> {
    /// A search over `order` (a cycle) keeping the leg `fixed` in place.
    pub(crate) fn new(
        dist: &'a Dist,
        neighbours: &'a Neighbours,
        order: &[usize],
        fixed: Option<(usize, usize)>,
    ) -> Self {
        let n = order.len();
        Self {
            dist,
            neighbours,
            tour: ArrayTour::new(order),
            fixed,
            queue: VecDeque::with_capacity(n),
            queued: vec![false; n],
            touched: Vec::new(),
            added: Vec::new(),
        }
    }

    /// Cost of the current cycle.
    pub(crate) fn cost(&self) -> f64 {
        (0..self.tour.len())
            .map(|p| self.dist.d(self.tour.at(p), self.tour.at(p + 1)))
            .sum()
    }

    /// Replaces the tour by the cycle `order` (forgetting the journal).
    pub(crate) fn reset(&mut self, order: &[usize]) {
        self.tour = ArrayTour::new(order);
    }

    /// Marks `c` to be looked at.
    pub(crate) fn activate(&mut self, c: usize) {
        if !std::mem::replace(&mut self.queued[c], true) {
            self.queue.push_back(c);
        }
    }

    /// Marks every node, in tour order.
    pub(crate) fn activate_all(&mut self) {
        for p in 0..self.tour.len() {
            self.activate(self.tour.at(p));
        }
    }

    /// True when the leg between `a` and `b` (either direction) must stay.
    #[inline]
    pub(crate) fn is_fixed(&self, a: usize, b: usize) -> bool {
        self.fixed
            .is_some_and(|(u, v)| (a == u && b == v) || (a == v && b == u))
    }

    /// Improves until no active node has an improving move; returns the total gain.
    pub(crate) fn optimise(&mut self) -> f64 {
        let mut total = 0.0;
        while let Some(c) = self.queue.pop_front() {
            self.queued[c] = false;
            self.touched.clear();
            if let Some(gain) = self.improve_around(c) {
                total += gain;
                let touched = std::mem::take(&mut self.touched);
                for &t in &touched {
                    self.activate(t);
                }
                self.activate(c);
                self.touched = touched;
            }
        }
        total
    }

    fn improve_around(&mut self, c: usize) -> Option<f64> {
        if self.dist.is_symmetric() {
            self.lk_from(c).or_else(|| self.or_opt_from(c))
        } else {
            self.or3_from(c)
                .or_else(|| self.or3_into(c))
                .or_else(|| self.or_opt_from(c))
        }
    }

    fn touch(&mut self, nodes: &[usize]) {
        self.touched.extend_from_slice(nodes);
    }

    // ----- LK-style chains of 2-opt flips (symmetric) -----

    fn lk_from(&mut self, t1: usize) -> Option<f64> {
        for forward in [true, false] {
            let t2 = self.tour.step(t1, forward);
            if self.is_fixed(t1, t2) {
                continue;
            }
            self.added.clear();
            if let Some(gain) = self.lk_step(t1, t2, 0, 0.0) {
                return Some(gain);
            }
        }
        None
    }

    /// One level of the chain. The tour is valid and `delta` better than at the start;
    /// the leg `{t1, last}` is the one the chain would remove next.
    fn lk_step(&mut self, t1: usize, last: usize, depth: usize, delta: f64) -> Option<f64> {
        let eps = self.dist.eps();
        let open_gain = delta + self.dist.d(t1, last);
        let forward = self.tour.next(t1) == last;
        let after_last = self.tour.step(last, forward);
        let breadth = LK_BREADTH.get(depth).copied().unwrap_or(1);
        let mut best: [(f64, usize, usize); 5] = [(f64::NEG_INFINITY, 0, 0); 5];
        let mut found = 0;
        for &t3 in self.neighbours.out_of(last) {
            let g1 = open_gain - self.dist.d(last, t3);
            if g1 <= eps {
                break;
            }
            if t3 == after_last || t3 == t1 {
                continue;
            }
            let t4 = self.tour.step(t3, !forward);
            if self.is_fixed(t3, t4) || self.was_added(t3, t4) {
                continue;
            }
            let g2 = g1 + self.dist.d(t4, t3);
            insert_top(&mut best[..breadth], &mut found, (g2, t3, t4));
        }
        for &(g2, t3, t4) in &best[..found.min(breadth)] {
            let mark = self.tour.mark();
            self.tour.two_opt(t1, last, t4, t3);
            let closed = g2 - self.dist.d(t4, t1);
            if closed > eps {
                self.touch(&[t1, last, t3, t4]);
                return Some(closed);
            }
            if depth + 1 < LK_MAX_DEPTH {
                self.added.push((last, t3));
                if let Some(gain) = self.lk_step(t1, t4, depth + 1, closed) {
                    self.touch(&[last, t3, t4]);
                    return Some(gain);
                }
                self.added.pop();
            }
            self.tour.rollback(mark);
        }
        None
    }

    fn was_added(&self, a: usize, b: usize) -> bool {
        self.added
            .iter()
            .any(|&(u, v)| (a == u && b == v) || (a == v && b == u))
    }

    // ----- Or-opt: move a segment of 1–3 nodes -----

    fn or_opt_from(&mut self, t: usize) -> Option<f64> {
        let max_len = OR_OPT_MAX_SEGMENT.min(self.tour.len().saturating_sub(4));
        for len in 1..=max_len {
            for t_is_first in [true, false] {
                if len == 1 && !t_is_first {
                    continue;
                }
                let (first, last) = if t_is_first {
                    (t, self.walk(t, len - 1, true))
                } else {
                    (self.walk(t, len - 1, false), t)
                };
                if let Some(gain) = self.move_segment(first, last, len) {
                    return Some(gain);
                }
            }
        }
        None
    }

    fn walk(&self, mut c: usize, steps: usize, forward: bool) -> usize {
        for _ in 0..steps {
            c = self.tour.step(c, forward);
        }
        c
    }

    /// Moves the forward segment `first ..= last` (`len` nodes) to the best improving
    /// place between two adjacent nodes elsewhere, if there is one.
    fn move_segment(&mut self, first: usize, last: usize, len: usize) -> Option<f64> {
        let segment = Segment {
            first,
            last,
            len,
            before: self.tour.prev(first),
            after: self.tour.next(last),
        };
        if self.is_fixed(segment.before, first) || self.is_fixed(last, segment.after) {
            return None;
        }
        let d = |a: usize, b: usize| self.dist.d(a, b);
        let removal_gain =
            d(segment.before, first) + d(last, segment.after) - d(segment.before, segment.after);
        if removal_gain <= self.dist.eps() {
            return None;
        }
        let insertion = self.best_insertion(&segment, removal_gain)?;
        self.insert_segment(&segment, &insertion);
        Some(insertion.gain)
    }

    /// The best improving place for `segment`, near the candidates of its ends: every
    /// leg next to a node with a cheap leg into `first` or out of `last`.
    fn best_insertion(&self, segment: &Segment, removal_gain: f64) -> Option<Insertion> {
        let eps = self.dist.eps();
        let d = |a: usize, b: usize| self.dist.d(a, b);
        let worth_it = |new_leg: f64| removal_gain - new_leg > eps;
        let into_first = self.neighbours.into(segment.first).iter();
        let out_of_last = self.neighbours.out_of(segment.last).iter();
        let candidates = into_first
            .map(|&c| (c, d(c, segment.first)))
            .take_while(|&(_, leg)| worth_it(leg))
            .chain(
                out_of_last
                    .map(|&c| (c, d(segment.last, c)))
                    .take_while(|&(_, leg)| worth_it(leg)),
            );
        let orientations: &[bool] = if self.dist.is_symmetric() {
            &[false, true]
        } else {
            &[false]
        };
        let mut best: Option<Insertion> = None;
        for (c, _) in candidates {
            for (a, b) in [(self.tour.prev(c), c), (c, self.tour.next(c))] {
                if segment.contains(&self.tour, a)
                    || segment.contains(&self.tour, b)
                    || self.is_fixed(a, b)
                {
                    continue;
                }
                for &reversed in orientations {
                    let (head, tail) = if reversed {
                        (segment.last, segment.first)
                    } else {
                        (segment.first, segment.last)
                    };
                    let gain = removal_gain + d(a, b) - d(a, head) - d(tail, b);
                    if gain > eps && best.as_ref().is_none_or(|best| gain > best.gain) {
                        best = Some(Insertion {
                            gain,
                            a,
                            b,
                            reversed,
                        });
                    }
                }
            }
        }
        best
    }

    /// Puts `segment` between `insertion.a` and `insertion.b` (`b = next(a)`).
    fn insert_segment(&mut self, segment: &Segment, insertion: &Insertion) {
        let Segment {
            first,
            last,
            before,
            after,
            ..
        } = *segment;
        let Insertion { a, b, reversed, .. } = *insertion;
        // Blocks S = [first..last], X = [after..a], Y = [b..before]: S X Y → S Y X, i.e.
        // … before → after … a → first … last → b ….
        self.tour.exchange(first, after, b);
        if reversed {
            self.tour.two_opt(a, first, last, b);
        }
        self.touch(&[before, after, first, last, a, b]);
    }

    // ----- Or-3opt segment exchange (asymmetric-safe) -----

    /// Tries `x1 → y2`, `x2 → y3`, `x3 → y1` in place of the legs `xi → yi`, with the
    /// nodes in tour order `x1 y1 … x2 y2 … x3 y3 …` (the blocks `[y1..x2]` and
    /// `[y2..x3]` swap places).
    fn or3_from(&mut self, x1: usize) -> Option<f64> {
        let eps = self.dist.eps();
        let y1 = self.tour.next(x1);
        if self.is_fixed(x1, y1) {
            return None;
        }
        let d = |a: usize, b: usize| self.dist.d(a, b);
        let n = self.tour.len();
        let rank = |c: usize| match self.tour.forward_distance(x1, c) {
            0 => n,
            r => r,
        };
        for &y2 in self.neighbours.out_of(x1) {
            let g1 = d(x1, y1) - d(x1, y2);
            if g1 <= eps {
                break;
            }
            if y2 == y1 {
                continue;
            }
            let x2 = self.tour.prev(y2);
            if self.is_fixed(x2, y2) {
                continue;
            }
            let g1 = g1 + d(x2, y2);
            let rank_y2 = rank(y2);
            for &y3 in self.neighbours.out_of(x2) {
                let g2 = g1 - d(x2, y3);
                if g2 <= eps {
                    break;
                }
                if rank(y3) <= rank_y2 {
                    continue;
                }
                let x3 = self.tour.prev(y3);
                if self.is_fixed(x3, y3) {
                    continue;
                }
                let gain = g2 + d(x3, y3) - d(x3, y1);
                if gain > eps {
                    self.tour.exchange(y1, y2, y3);
                    self.touch(&[x1, y1, x2, y2, x3, y3]);
                    return Some(gain);
                }
            }
        }
        None
    }

    /// The mirror image of [`Search::or3_from`]: the same exchange, found from the head
    /// `y1` of a leg through the cheapest legs *into* nodes (`x3 → y1`, then `x2 → y3`).
    fn or3_into(&mut self, y1: usize) -> Option<f64> {
        let eps = self.dist.eps();
        let x1 = self.tour.prev(y1);
        if self.is_fixed(x1, y1) {
            return None;
        }
        let d = |a: usize, b: usize| self.dist.d(a, b);
        let rank = |c: usize| self.tour.forward_distance(x1, c);
        for &x3 in self.neighbours.into(y1) {
            let g1 = d(x1, y1) - d(x3, y1);
            if g1 <= eps {
                break;
            }
            if x3 == x1 {
                continue;
            }
            let y3 = self.tour.next(x3);
            if self.is_fixed(x3, y3) {
                continue;
            }
            let g1 = g1 + d(x3, y3);
            let rank_x3 = rank(x3);
            for &x2 in self.neighbours.into(y3) {
                let g2 = g1 - d(x2, y3);
                if g2 <= eps {
                    break;
                }
                let rank_x2 = rank(x2);
                if rank_x2 == 0 || rank_x2 >= rank_x3 {
                    continue;
                }
                let y2 = self.tour.next(x2);
                if self.is_fixed(x2, y2) {
                    continue;
                }
                let gain = g2 + d(x2, y2) - d(x1, y2);
                if gain > eps {
                    self.tour.exchange(y1, y2, y3);
                    self.touch(&[x1, y1, x2, y2, x3, y3]);
                    return Some(gain);
                }
            }
        }
        None
    }
}

/// Keeps the `top.len()` best candidates by gain, best first.
fn insert_top(top: &mut [(f64, usize, usize)], found: &mut usize, cand: (f64, usize, usize)) {
    let len = (*found).min(top.len());
    let mut k = len;
    while k > 0 && top[k - 1].0 < cand.0 {
        k -= 1;
    }
    if k >= top.len() {
        return;
    }
    let end = (len + 1).min(top.len());
    for i in (k + 1..end).rev() {
        top[i] = top[i - 1];
    }
    top[k] = cand;
    *found = end;
}

/// A forward run of nodes `first ..= last` and the nodes just outside it.
#[derive(Clone, Copy, Debug)]
struct Segment {
    first: usize,
    last: usize,
    len: usize,
    before: usize,
    after: usize,
}

impl Segment {
    fn contains(&self, tour: &ArrayTour, c: usize) -> bool {
        tour.forward_distance(self.first, c) < self.len
    }
}

/// Where an Or-opt move puts a segment: between the adjacent nodes `a → b`, reversed
/// (`a → last … first → b`) or not, and what it saves.
#[derive(Clone, Copy, Debug)]
struct Insertion {
    gain: f64,
    a: usize,
    b: usize,
    reversed: bool,
}
