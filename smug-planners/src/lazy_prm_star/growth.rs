//! Growing the roadmap: samples, endpoint expansions, query endpoints, and the corner
//! vertices of a disc on a grid.

use super::*;

/// `k = ⌈e(1 + 1/d) ln n⌉` with `d = 3`, at least 1.
pub(super) fn connection_k(n: usize) -> usize {
    let k = (std::f64::consts::E * (1.0 + 1.0 / 3.0) * (n.max(1) as f64).ln()).ceil();
    (k as usize).max(1)
}

impl LazyPrmStar {
    /// Draws `n` samples into the roadmap now.
    pub fn grow(&mut self, n: u64) {
        for _ in 0..n {
            if let Some(sample) = self.draw_sample(None) {
                self.insert_sample(sample);
            }
        }
    }

    /// Draws one sample from the sampler (in `informed` when given), counted and timed.
    pub(super) fn draw_sample(&mut self, informed: Option<&InformedSet>) -> Option<Pose2> {
        let started = Instant::now();
        let sample = self.sampler.sample(&self.bounds, informed);
        self.counts.samples += 1;
        self.counts.breakdown.sampling_s += started.elapsed().as_secs_f64();
        sample
    }

    /// Draws an expansion sample and adds it (checked first unless vertices are lazy) to
    /// the roadmap and to its end's tree; true if added.
    pub(super) fn insert_expansion_sample(&mut self) -> bool {
        let started = Instant::now();
        let drawn = self.expansion.sample(self.space.as_ref(), &self.bounds);
        self.counts.samples += 1;
        self.counts.breakdown.sampling_s += started.elapsed().as_secs_f64();
        let Some((end, sample, (from, to))) = drawn else {
            return false;
        };
        let added = self.insert_sample(sample);
        if added {
            let started = Instant::now();
            let joined = self.motions.is_valid_motion(&from, &to);
            self.counts.edge_checks += 1;
            self.counts.breakdown.edge_checking_s += started.elapsed().as_secs_f64();
            if joined {
                self.expansion.grow(end, sample);
            }
        }
        added
    }

    /// Adds a sample as a vertex like [`insert_sample`](Self::insert_sample), but an
    /// invalid one becomes a bridge attempt (see [`LazyPrmStarParams::bridge_sigma`]):
    /// a valid pose halfway between it and an invalid partner is added instead.
    pub(super) fn insert_or_bridge(&mut self, sample: Pose2) -> bool {
        if self.params.lazy_vertices || !self.bridge.is_on() {
            return self.insert_sample(sample);
        }
        if self.check_state(&sample) {
            self.add_vertex(sample, Validity::Valid);
            return true;
        }
        let started = Instant::now();
        let partner = self.bridge.partner(&sample);
        self.counts.breakdown.sampling_s += started.elapsed().as_secs_f64();
        // Outside the bounds counts as blocked: a passage beside the map's edge.
        if self.bounds.contains(partner.x, partner.y) && self.check_state(&partner) {
            return false;
        }
        let middle = Bridge::midpoint(self.space.as_ref(), &sample, &partner);
        if !self.bounds.contains(middle.x, middle.y) || !self.check_state(&middle) {
            return false;
        }
        self.add_vertex(middle, Validity::Valid);
        true
    }

    /// Checks a state, counted and timed as vertex checking.
    pub(super) fn check_state(&mut self, state: &Pose2) -> bool {
        timed_state_check(self.states.as_ref(), &mut self.counts, state)
    }

    /// Adds a sample as a vertex (checked first unless vertices are lazy); true if added.
    pub(super) fn insert_sample(&mut self, sample: Pose2) -> bool {
        let validity = if self.params.lazy_vertices {
            Validity::Unknown
        } else if self.check_state(&sample) {
            Validity::Valid
        } else {
            return false;
        };
        self.add_vertex(sample, validity);
        true
    }

    /// Adds a vertex joined to its k nearest (timed as sampling); its id.
    pub(super) fn add_vertex(&mut self, pose: Pose2, validity: Validity) -> u32 {
        let started = Instant::now();
        let k = connection_k(self.roadmap.live_vertex_count() + 1);
        let v = self.roadmap.add_vertex(
            pose,
            validity,
            k,
            (self.space.as_ref(), self.w_t),
            self.objective.as_ref(),
        );
        self.counts.breakdown.sampling_s += started.elapsed().as_secs_f64();
        v
    }

    /// The vertex of a query endpoint (added if new), checked; `None` when invalid.
    pub(super) fn terminal(&mut self, pose: &Pose2) -> Option<u32> {
        if let Some(v) = self.roadmap.find(pose) {
            let mut checks = Checks {
                states: self.states.as_ref(),
                motions: self.motions.as_ref(),
                counts: &mut self.counts,
            };
            return checks.vertex(&mut self.roadmap, v).then_some(v);
        }
        if !self.check_state(pose) {
            return None;
        }
        Some(self.add_vertex(*pose, Validity::Valid))
    }

    /// Grows the initial roadmap before the first query: corner vertices, then
    /// `initial_samples`.
    pub(super) fn ensure_grown(&mut self) {
        if !self.grown {
            self.grown = true;
            self.add_corner_vertices();
            self.grow(self.params.initial_samples);
        }
    }

    /// For a disc on a grid and straight motions, a valid vertex at each of the grid's
    /// corner and corridor waypoints inside the bounds (see
    /// [`LazyPrmStarParams::corner_vertices`]).
    pub(super) fn add_corner_vertices(&mut self) {
        if !self.params.corner_vertices || !self.space.is_holonomic() {
            return;
        }
        let Some(disc) = self.states.disc_on_grid() else {
            return;
        };
        let mut waypoints = crate::grid_disc::corner_waypoints(&disc);
        waypoints.extend(crate::grid_disc::corridor_waypoints(&disc));
        waypoints.retain(|&[x, y]| self.bounds.contains(x, y));
        for [x, y] in evenly_spaced(waypoints, self.params.max_corner_vertices) {
            self.insert_sample(Pose2::new(x, y, 0.0));
        }
    }
}

/// At most `limit` of `items`, evenly spaced through them (all when they fit): a map
/// with more corners than their budget (`max_corner_vertices`) keeps a roadmap the
/// size the budget allows (its memory check holds), its corners thinned evenly.
fn evenly_spaced<T: Copy>(items: Vec<T>, limit: u64) -> Vec<T> {
    let n = items.len() as u64;
    if n <= limit {
        return items;
    }
    (0..limit)
        .map(|k| items[(k as u128 * n as u128 / limit as u128) as usize])
        .collect()
}

#[cfg(test)]
mod tests {
    use super::evenly_spaced;

    #[test]
    fn thinning_keeps_everything_that_fits_and_spreads_the_rest() {
        let items: Vec<u32> = (0..10).collect();
        assert_eq!(evenly_spaced(items.clone(), 10), items);
        assert_eq!(evenly_spaced(items.clone(), 5), vec![0, 2, 4, 6, 8]);
        assert_eq!(evenly_spaced(items.clone(), 3), vec![0, 3, 6]);
        assert!(evenly_spaced(items, 0).is_empty());
    }
}
