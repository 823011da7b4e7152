//! Local improvement of a GTSP tour: 2-opt on its nodes (symmetric costs), moving one
//! cluster to its best place and node (GLNS's "move-opt"), the cluster sweep, and a
//! reorder of the chosen nodes by the TSP local search.

use super::tour::Problem;
use crate::local_search::{LocalSearch, LocalSearchParams};
use smug_core::rng::StageRng;
use smug_core::{CostMatrix, Sequencer, TourKind};

impl Problem<'_> {
    /// First-improvement 2-opt until no reversal gains; returns the gain. Only for
    /// symmetric costs (a reversal keeps every leg's cost).
    pub(crate) fn two_opt(&self, order: &mut [usize]) -> f64 {
        let len = order.len();
        let eps = self.dist.eps();
        let last_leg = match self.end {
            None => len,
            Some(_) => len.saturating_sub(1),
        };
        let mut gain = 0.0;
        let mut improved = true;
        let mut legs = self.legs(order);
        let mut cluster: Vec<usize> = order.iter().map(|&v| self.clusters.of(v)).collect();
        while improved {
            improved = false;
            for i in 0..last_leg {
                for j in i + 2..last_leg {
                    if i == 0 && j + 1 == len {
                        continue; // the same two legs of a closed tour
                    }
                    // A move gains only if d(a, c) < d(a, b) or d(b, d) < d(c, d) (else
                    // its delta is ≥ 0 up to rounding far below eps): the clusters'
                    // cheapest legs rule most pairs out without reading the matrix.
                    if let Some(bounds) = &self.bounds {
                        let (ca, cb) = (cluster[i], cluster[i + 1]);
                        if bounds.cheapest_out_of(ca)[cluster[j]] >= legs[i]
                            && bounds.cheapest_out_of(cb)[cluster[(j + 1) % len]] >= legs[j]
                        {
                            continue;
                        }
                    }
                    let (a, b) = (order[i], order[i + 1]);
                    let (c, d) = (order[j], order[(j + 1) % len]);
                    // legs[i] = d(a, b), legs[j] = d(c, d).
                    let delta = self.dist.d(a, c) + self.dist.d(b, d) - legs[i] - legs[j];
                    if delta < -eps {
                        order[i + 1..=j].reverse();
                        cluster[i + 1..=j].reverse();
                        for (k, leg) in legs.iter_mut().enumerate().take(j + 1).skip(i) {
                            *leg = self.leg(order, k);
                        }
                        gain -= delta;
                        improved = true;
                    }
                }
            }
        }
        gain
    }

    /// Takes each movable cluster out in turn and puts it back at its cheapest place
    /// with its cheapest node, until a pass changes nothing; returns the gain.
    pub(crate) fn move_opt(&self, order: &mut Vec<usize>, rng: &mut StageRng) -> f64 {
        let eps = self.dist.eps();
        let mut gain = 0.0;
        let mut improved = true;
        let mut legs = self.legs(order);
        while improved {
            improved = false;
            let mut p = self.movable(order.len()).start;
            while p < self.movable(order.len()).end {
                let len = order.len();
                let (a, v, b) = (order[(p + len - 1) % len], order[p], order[(p + 1) % len]);
                let saved = self.dist.d(a, v) + self.dist.d(v, b) - self.dist.d(a, b);
                self.remove_at(order, &mut legs, p);
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

    /// 2-opt (symmetric costs) and the sweep, alternated until neither gains.
    pub(crate) fn polish(&self, order: &mut Vec<usize>) {
        loop {
            let mut gain = 0.0;
            if self.dist.is_symmetric() {
                gain += self.two_opt(order);
            }
            gain += self.sweep_in_place(order);
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
