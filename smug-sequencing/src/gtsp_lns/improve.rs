//! Local improvement of a GTSP tour: 2-opt on its nodes (symmetric costs), moving one
//! cluster to its best place and node (GLNS's "move-opt"), the cluster sweep, and a
//! reorder of the chosen nodes by the TSP local search.

use super::insertion::Legs;
use super::tour::Problem;
use crate::local_search::{LocalSearch, LocalSearchParams};
use smug_core::rng::StageRng;
use smug_core::{CostMatrix, Sequencer, TourKind};

impl Problem<'_> {
    /// First-improvement 2-opt until no reversal gains; returns the gain. Only for
    /// symmetric costs (a reversal keeps every leg's cost).
    ///
    /// A reversal of the legs `(a, b)` and `(c, d)` gains only if `d(a, c) < d(a, b)` or
    /// `d(b, d) < d(c, d)` (else its delta is ≥ 0 up to rounding far below `eps`). With
    /// the cluster bounds and a tour of every cluster, only the positions of the
    /// clusters near `a` or `b` are tried, in the order of the plain scan, so the moves
    /// made are the same.
    pub(crate) fn two_opt(&self, order: &mut [usize]) -> f64 {
        let len = order.len();
        let eps = self.dist.eps();
        let last_leg = match self.end {
            None => len,
            Some(_) => len.saturating_sub(1),
        };
        let Legs {
            cost: mut legs,
            mut cluster,
            ..
        } = self.legs(order);
        let near = self.bounds.as_ref().filter(|_| len == self.len());
        let mut position = vec![0; if near.is_some() { len } else { 0 }];
        if near.is_some() {
            for (p, &c) in cluster.iter().enumerate() {
                position[c as usize] = p;
            }
        }
        let mut gain = 0.0;
        let mut improved = true;
        let mut candidates = Vec::new();
        while improved {
            improved = false;
            let mut longest = legs[..last_leg]
                .iter()
                .copied()
                .fold(f64::NEG_INFINITY, f64::max);
            // No pair of legs two apart starts at the last two positions.
            for i in 0..last_leg.saturating_sub(2) {
                let mut after = i + 1;
                loop {
                    let (ca, cb) = (cluster[i] as usize, cluster[i + 1] as usize);
                    let valid = |j: usize| j > after && j < last_leg && !(i == 0 && j + 1 == len);
                    candidates.clear();
                    match near {
                        Some(bounds) => {
                            for &cc in bounds.nearest_out_of(ca) {
                                if bounds.cheapest_out_of(ca)[cc as usize] >= legs[i] {
                                    break;
                                }
                                let j = position[cc as usize];
                                if valid(j) {
                                    candidates.push(j);
                                }
                            }
                            for &cd in bounds.nearest_out_of(cb) {
                                let lo = bounds.cheapest_out_of(cb)[cd as usize];
                                if lo >= longest {
                                    break;
                                }
                                let j = match position[cd as usize] {
                                    0 => len - 1,
                                    q => q - 1,
                                };
                                if valid(j) && lo < legs[j] {
                                    candidates.push(j);
                                }
                            }
                            candidates.sort_unstable();
                            candidates.dedup();
                        }
                        None => candidates.extend((after + 1..last_leg).filter(|&j| valid(j))),
                    }
                    let mut moved = None;
                    for &j in &candidates {
                        let (a, b) = (order[i], order[i + 1]);
                        let (c, d) = (order[j], order[(j + 1) % len]);
                        // legs[i] = d(a, b), legs[j] = d(c, d).
                        let delta = self.dist.d(a, c) + self.dist.d(b, d) - legs[i] - legs[j];
                        if delta < -eps {
                            order[i + 1..=j].reverse();
                            cluster[i + 1..=j].reverse();
                            for k in i..=j {
                                legs[k] = self.leg(order, k);
                                if near.is_some() {
                                    position[cluster[k] as usize] = k;
                                }
                            }
                            longest = legs[..last_leg]
                                .iter()
                                .copied()
                                .fold(f64::NEG_INFINITY, f64::max);
                            gain -= delta;
                            moved = Some(j);
                            break;
                        }
                    }
                    match moved {
                        Some(j) => {
                            improved = true;
                            after = j;
                        }
                        None => break,
                    }
                }
            }
        }
        gain
    }

    /// Takes each movable cluster out in turn and puts it back at its cheapest place
    /// with its cheapest node, until a pass changes nothing; returns the gain.
    pub(crate) fn move_opt(&self, order: &mut Vec<usize>, rng: &mut StageRng) -> f64 {
        if order.len() < 2 {
            return 0.0;
        }
        let eps = self.dist.eps();
        let mut gain = 0.0;
        let mut improved = true;
        let mut legs = self.legs(order);
        while improved {
            improved = false;
            let mut p = self.movable(order.len()).start;
            while p < self.movable(order.len()).end {
                let len = order.len();
                // d(a, v) and d(v, b) before the removal, d(a, b) after it.
                let before = (p + len - 1) % len;
                let (into_v, out_of_v) = (legs.cost[before], legs.cost[p]);
                let v = self.remove_at(order, &mut legs, p);
                let saved = into_v + out_of_v - legs.cost[(p + len - 2) % (len - 1)];
                let c = self.clusters.of(v);
                match self.insertion_below(order, &legs, c, saved - eps, rng) {
                    Some((q, w, added)) => {
                        self.insert_at(order, &mut legs, q, w);
                        gain += saved - added;
                        improved = true;
                    }
                    None => self.insert_at(order, &mut legs, p, v),
                }
                p += 1;
            }
        }
        gain
    }

    /// Re-picks every cluster's node for the current order; returns the gain.
    pub(crate) fn sweep_in_place(&self, order: &mut Vec<usize>) -> f64 {
        let before = self.cost(order);
        let (nodes, cost) = self.sweep(order);
        if cost < before - self.dist.eps() {
            *order = nodes;
            before - cost
        } else {
            0.0
        }
    }

    /// 2-opt (symmetric costs) and the sweep, alternated until neither gains. A sweep
    /// right after a sweep of the same cluster order (2-opt moved nothing) is skipped:
    /// its nodes are already that order's best, so it could not gain.
    pub(crate) fn polish(&self, order: &mut Vec<usize>) {
        let mut swept = false;
        loop {
            let mut gain = 0.0;
            if self.dist.is_symmetric() {
                let moved = self.two_opt(order);
                if moved > 0.0 {
                    swept = false;
                }
                gain += moved;
            }
            if !swept {
                gain += self.sweep_in_place(order);
                swept = true;
            }
            if gain <= 0.0 {
                return;
            }
        }
    }

    /// Reorders the chosen nodes with the TSP local search (`iterations` perturbation
    /// rounds, seeded from `rng`), then sweeps, as long as that gains (at most `rounds`
    /// times). Returns the gain.
    pub(crate) fn reorder(
        &self,
        order: &mut Vec<usize>,
        iterations: u64,
        rounds: usize,
        rng: &StageRng,
    ) -> f64 {
        let start = self.cost(order);
        for _ in 0..rounds {
            let before = self.cost(order);
            let Some(reordered) = self.tsp_order(order, iterations, rng) else {
                return start - self.cost(order);
            };
            let mut candidate = reordered;
            self.polish(&mut candidate);
            if self.cost(&candidate) < before - self.dist.eps() {
                *order = candidate;
            } else {
                break;
            }
        }
        start - self.cost(order)
    }

    /// The nodes of `order` in the order the TSP local search gives them.
    fn tsp_order(&self, order: &[usize], iterations: u64, rng: &StageRng) -> Option<Vec<usize>> {
        let len = order.len();
        let sub = CostMatrix::from_fn(len, |i, j| self.dist.d(order[i], order[j])).ok()?;
        let kind = match self.end {
            Some(_) if len > 1 => TourKind::OpenTo(len - 1),
            _ => TourKind::Closed,
        };
        let params = LocalSearchParams {
            time_limit_s: 0.0,
            max_iterations: iterations.max(1),
            ..LocalSearchParams::default()
        };
        let tour = LocalSearch::new(params, rng.clone())
            .ok()?
            .solve(&sub, kind)
            .ok()?;
        Some(tour.order.into_iter().map(|k| order[k]).collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::costs::Dist;
    use rand::SeedableRng;
    use smug_core::Clusters;

    fn square() -> (CostMatrix, Clusters) {
        // Unit square corners 0..4 (singleton clusters) plus far copies 4..8.
        let xy = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0_f64)];
        let at = |v: usize| {
            let (x, y) = xy[v % 4];
            (x + 10.0 * (v / 4) as f64, y)
        };
        let costs = CostMatrix::from_fn(8, |i, j| {
            let (a, b) = (at(i), at(j));
            (a.0 - b.0).hypot(a.1 - b.1)
        })
        .unwrap();
        let clusters = Clusters::new(8, (0..4).map(|c| vec![c, c + 4]).collect()).unwrap();
        (costs, clusters)
    }

    #[test]
    fn two_opt_uncrosses_and_move_opt_repicks() {
        let (costs, clusters) = square();
        let problem = Problem::new(Dist::new(&costs), &clusters, TourKind::Closed);
        let mut crossed = vec![0, 2, 1, 3];
        assert!(problem.two_opt(&mut crossed) > 0.0);
        assert_eq!(problem.cost(&crossed), 4.0);
        let mut rng = StageRng::seed_from_u64(1);
        let mut far = vec![1, 0, 6, 3];
        let before = problem.cost(&far);
        let gain = problem.move_opt(&mut far, &mut rng);
        assert!(gain > 0.0 && (problem.cost(&far) - (before - gain)).abs() < 1e-9);
        assert_eq!(problem.cost(&far), 4.0, "{far:?}");
        let mut mixed = vec![0, 6, 5, 7];
        problem.reorder(&mut mixed, 10, 3, &rng);
        assert_eq!(problem.cost(&mixed), 4.0);
        assert!(clusters.is_valid_tour(
            &smug_core::Tour {
                order: mixed,
                cost: 4.0
            },
            TourKind::Closed
        ));
    }
}
