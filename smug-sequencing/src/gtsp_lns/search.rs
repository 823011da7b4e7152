//! The large-neighbourhood search loop: remove clusters, reinsert them, polish, accept
//! by simulated annealing; restart from the best tour after each epoch.

use super::params::GtspLnsParams;
use super::tour::Problem;
use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};
use rayon::prelude::*;
use smug_core::rng::StageRng;
use smug_core::termination::TerminationClock;

/// An iteration may always remove up to this many clusters (small instances need
/// large moves to leave a local optimum: measured on random 5–10-cluster instances).
const MIN_REMOVAL_RANGE: usize = 10;

/// How clusters are chosen for removal.
#[derive(Clone, Copy, Debug)]
enum Removal {
    /// Any clusters.
    Random,
    /// A run of consecutive positions.
    Segment,
    /// A seed and the nodes closest to it.
    Related,
    /// The ones whose legs cost most, with some randomness.
    Worst,
}

/// Instances of this many nodes or more build an iteration's neighbours side by side:
/// on smaller ones waking a second thread costs more than a neighbour (measured:
/// joint lunar 13×10, about 130 nodes, 37% slower side by side; lunar 48×6, about 290
/// nodes, 10% faster).
const SIDE_BY_SIDE_FROM: usize = 256;

const REMOVALS: [Removal; 4] = [
    Removal::Random,
    Removal::Segment,
    Removal::Related,
    Removal::Worst,
];

/// The search state.
pub(crate) struct Search<'p, 'a> {
    problem: &'p Problem<'a>,
    params: &'p GtspLnsParams,
    rng: StageRng,
    /// Best tour found and its cost.
    pub(crate) best: (Vec<usize>, f64),
}

impl<'p, 'a> Search<'p, 'a> {
    pub(crate) fn new(
        problem: &'p Problem<'a>,
        params: &'p GtspLnsParams,
        rng: StageRng,
        first: Vec<usize>,
    ) -> Self {
        let cost = problem.cost(&first);
        Self {
            problem,
            params,
            rng,
            best: (first, cost),
        }
    }

    /// Runs until the clock says done; returns the iterations done.
    pub(crate) fn run(&mut self, clock: &mut TerminationClock<'_>) -> u64 {
        if self.problem.most_removable(self.problem.len()) == 0 {
            return 0;
        }
        let epoch = self.epoch_length();
        let mut current = self.best.clone();
        let mut in_epoch = 0;
        while !clock.is_done() {
            clock.tick();
            let temperature = self.temperature(in_epoch, epoch);
            let candidate = self.best_neighbour(&current.0);
            let delta = candidate.1 - current.1;
            if delta <= 0.0 || self.rng.random::<f64>() < (-delta / temperature).exp() {
                current = candidate;
                if current.1 < self.best.1 - self.problem.dist.eps() {
                    self.best = current.clone();
                }
            }
            in_epoch += 1;
            if in_epoch >= epoch {
                in_epoch = 0;
                self.restart();
                current = self.best.clone();
            }
        }
        clock.iterations()
    }

    fn epoch_length(&self) -> u64 {
        if self.params.epoch_iterations > 0 {
            self.params.epoch_iterations
        } else {
            (10 * self.problem.len() as u64).max(200)
        }
    }

    /// The annealing temperature: a fraction of an average leg of the best tour,
    /// falling linearly to 0 over an epoch.
    fn temperature(&self, in_epoch: u64, epoch: u64) -> f64 {
        let average_leg = self.best.1 / self.problem.len() as f64;
        let left = 1.0 - in_epoch as f64 / epoch as f64;
        (self.params.temperature * average_leg * left).max(f64::MIN_POSITIVE)
    }

    /// A restart from the best tour: the TSP local search reorders its nodes.
    fn restart(&mut self) {
        let mut order = self.best.0.clone();
        let rng = StageRng::from_rng(&mut self.rng);
        self.problem
            .reorder(&mut order, self.params.reorder_iterations, 3, &rng);
        let cost = self.problem.cost(&order);
        if cost < self.best.1 - self.problem.dist.eps() {
            self.best = (order, cost);
        }
    }

    /// The cheapest of `neighbours_per_iteration` neighbours of the current tour
    /// (the first on ties), built side by side on the caller's rayon pool when the
    /// instance has [`SIDE_BY_SIDE_FROM`] nodes or more. Each draws from a generator
    /// split off the search's in order, so the answer depends neither on the number of
    /// threads nor on the size rule; one neighbour draws from the search's own generator.
    fn best_neighbour(&mut self, current: &[usize]) -> (Vec<usize>, f64) {
        let moves = Moves {
            problem: self.problem,
            params: self.params,
            best_cost: self.best.1,
        };
        let count = self.params.neighbours_per_iteration.max(1);
        if count == 1 {
            return moves.neighbour(current, &mut self.rng);
        }
        let mut rngs: Vec<StageRng> = (0..count)
            .map(|_| StageRng::from_rng(&mut self.rng))
            .collect();
        let build = |rng: &mut StageRng| moves.neighbour(current, rng);
        let neighbours: Vec<(Vec<usize>, f64)> =
            if self.problem.clusters.node_count() >= SIDE_BY_SIDE_FROM {
                rngs.par_iter_mut().map(build).collect()
            } else {
                rngs.iter_mut().map(build).collect()
            };
        neighbours
            .into_iter()
            .reduce(|best, next| if next.1 < best.1 { next } else { best })
            .expect("at least one neighbour")
    }
}

/// What building a neighbour reads: the instance, the parameters and the best cost
/// so far (it scales the noise and gates move-opt).
#[derive(Clone, Copy)]
struct Moves<'p, 'a> {
    problem: &'p Problem<'a>,
    params: &'p GtspLnsParams,
    best_cost: f64,
}

impl Moves<'_, '_> {
    /// The current tour with some clusters removed, reinserted and polished.
    fn neighbour(&self, current: &[usize], rng: &mut StageRng) -> (Vec<usize>, f64) {
        let mut order = current.to_vec();
        let fraction = (self.params.max_removal_fraction * self.problem.len() as f64).ceil();
        let most = (fraction as usize)
            .max(MIN_REMOVAL_RANGE)
            .clamp(1, self.problem.most_removable(order.len()));
        let k = rng.random_range(1..=most);
        let removal = REMOVALS[rng.random_range(0..REMOVALS.len())];
        let mut removed = self.remove(&mut order, k, removal, rng);
        removed.shuffle(rng);
        let average_leg = self.best_cost / self.problem.len() as f64;
        let noise = self.params.noise * average_leg * rng.random::<f64>();
        self.problem.insert_all(&mut order, &removed, noise, rng);
        self.problem.polish(&mut order);
        let cost = self.problem.cost(&order);
        if cost < self.best_cost * (1.0 + self.params.move_opt_within) {
            self.problem.move_opt(&mut order, rng);
            self.problem.polish(&mut order);
        }
        let cost = self.problem.cost(&order);
        (order, cost)
    }

    /// Takes `k` clusters out of `order`; returns them.
    fn remove(
        &self,
        order: &mut Vec<usize>,
        k: usize,
        removal: Removal,
        rng: &mut StageRng,
    ) -> Vec<usize> {
        let range = self.problem.movable(order.len());
        let mut positions: Vec<usize> = match removal {
            Removal::Random => {
                let mut all: Vec<usize> = range.collect();
                all.shuffle(rng);
                all.truncate(k);
                all
            }
            Removal::Segment => {
                let first = rng.random_range(range.start..=range.end - k);
                (first..first + k).collect()
            }
            Removal::Related => {
                let seed = order[rng.random_range(range.clone())];
                let d = &self.problem.dist;
                let mut all: Vec<usize> = range.collect();
                all.sort_by(|&p, &q| {
                    let (a, b) = (order[p], order[q]);
                    (d.d(seed, a) + d.d(a, seed)).total_cmp(&(d.d(seed, b) + d.d(b, seed)))
                });
                all.truncate(k);
                all
            }
            Removal::Worst => {
                let mut all: Vec<(usize, f64)> = range
                    .map(|p| {
                        let before = (p + order.len() - 1) % order.len();
                        let detour = self.problem.leg(order, before) + self.problem.leg(order, p);
                        (p, detour * (0.5 + rng.random::<f64>()))
                    })
                    .collect();
                all.sort_by(|a, b| b.1.total_cmp(&a.1));
                all.into_iter().take(k).map(|(p, _)| p).collect()
            }
        };
        positions.sort_unstable_by(|a, b| b.cmp(a));
        positions
            .into_iter()
            .map(|p| self.problem.clusters.of(order.remove(p)))
            .collect()
    }
}
