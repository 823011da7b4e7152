//! The warm roadmap of LazyPRM*: the answers it gave (saved with its roadmap) and,
//! after a load, those it may give again without planning.

use super::LazyPrmStar;
use crate::roadmap::file::{IncompatibleRoadmap, RoadmapSnapshot, SavedAnswer};
use crate::roadmap::Validity;
use smug_core::{
    Bounds2, BuildContext, ChangedDisc, Error, Path, PlannerOutcome, Pose2, PoseBits, Result,
    StateSpace,
};
use std::collections::{BTreeMap, HashMap, VecDeque};
use std::time::Instant;

/// The planner's name in saved snapshots.
pub(super) const PLANNER_NAME: &str = "lazy-prm-star";

/// What a load reused and invalidated (reported in the planner's counters).
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct LoadCounts {
    pub vertices: u64,
    pub edges: u64,
    pub vertices_rechecked: u64,
    pub vertices_dropped: u64,
    pub edges_reset: u64,
    pub answers_reused: u64,
    pub answers_dropped: u64,
    pub answers_served: u64,
}

/// Answers given and answers loaded.
#[derive(Debug, Default)]
pub(super) struct Warm {
    /// Exact answers given, by endpoints, in the order given (a pair asked again, e.g.
    /// to refine a leg, has one per query; saved with the roadmap).
    given: BTreeMap<(PoseBits, PoseBits), Vec<SavedAnswer>>,
    /// Loaded answers no change touches: served as they are, in the order they were
    /// given; the last one of a pair again once the others are served.
    reusable: HashMap<(PoseBits, PoseBits), VecDeque<Path>>,
    /// Set once a roadmap was loaded.
    pub loaded: Option<LoadCounts>,
}

impl Warm {
    /// A loaded answer for `start → goal`, if one is still valid.
    pub fn reuse(&mut self, start: &Pose2, goal: &Pose2) -> Option<PlannerOutcome> {
        let answers = self.reusable.get_mut(&((*start).into(), (*goal).into()))?;
        let path = if answers.len() > 1 {
            answers.pop_front()?
        } else {
            answers.front()?.clone()
        };
        if let Some(counts) = self.loaded.as_mut() {
            counts.answers_served += 1;
        }
        Some(PlannerOutcome::Exact(path))
    }

    /// Remembers an exact answer (to save it).
    pub fn record(&mut self, start: &Pose2, goal: &Pose2, outcome: &PlannerOutcome) {
        if let PlannerOutcome::Exact(path) = outcome {
            let key = ((*start).into(), (*goal).into());
            self.given.entry(key).or_default().push(SavedAnswer {
                start: key.0,
                goal: key.1,
                states: path.states.iter().map(|&s| s.into()).collect(),
                cost: path.cost.to_bits(),
                goal_distance: None,
            });
        }
    }
}

/// True when the motion `a → b` may pass through one of `changed`.
fn touches(space: &dyn StateSpace, changed: &[ChangedDisc], a: &Pose2, b: &Pose2) -> bool {
    let length = space.motion_extent(a, b).length;
    changed.iter().any(|d| d.may_touch(a, b, length))
}

fn incompatible(reason: impl Into<String>) -> Error {
    Error::stage(
        "planner",
        IncompatibleRoadmap {
            reason: reason.into(),
        },
    )
}

impl LazyPrmStar {
    /// The roadmap and the answers given, planner-independent.
    pub(super) fn snapshot(&self) -> RoadmapSnapshot {
        let (vertices, edges) = self.roadmap.export();
        RoadmapSnapshot {
            planner: PLANNER_NAME.into(),
            directed: self.roadmap.is_directed(),
            vertices,
            edges,
            answers: self.warm.given.values().flatten().cloned().collect(),
        }
    }

    /// Loads `snapshot` into this fresh planner; the world changed in `changed`.
    pub(super) fn load(
        &mut self,
        snapshot: RoadmapSnapshot,
        changed: &[ChangedDisc],
    ) -> Result<()> {
        if snapshot.planner != PLANNER_NAME {
            return Err(incompatible(format!(
                "saved by planner `{}`, this is `{PLANNER_NAME}`",
                snapshot.planner
            )));
        }
        if snapshot.directed != self.roadmap.is_directed() {
            return Err(incompatible(
                "directed and undirected roadmaps differ (another motion model)",
            ));
        }
        if self.counts.queries > 0 || self.roadmap.vertex_count() > 0 {
            return Err(incompatible("the planner already has a roadmap"));
        }
        self.roadmap
            .restore(&snapshot.vertices, &snapshot.edges)
            .map_err(|e| incompatible(e.to_string()))?;
        let mut counts = LoadCounts {
            vertices: snapshot.vertices.len() as u64,
            edges: snapshot.edges.len() as u64,
            ..LoadCounts::default()
        };
        self.invalidate(changed, &mut counts);
        self.keep_untouched_answers(snapshot.answers, changed, &mut counts);
        self.grown = true;
        self.fresh_from = self.roadmap.vertex_count() as u32;
        self.warm.loaded = Some(counts);
        Ok(())
    }

    /// Checks again the vertices in `changed` (kept if valid, dropped if not) and marks
    /// the valid edges whose motion may pass there unchecked.
    fn invalidate(&mut self, changed: &[ChangedDisc], counts: &mut LoadCounts) {
        if changed.is_empty() {
            return;
        }
        for v in 0..self.roadmap.vertex_count() as u32 {
            let pose = *self.roadmap.pose(v);
            if self.roadmap.vertex_validity(v) == Validity::Invalid
                || !changed.iter().any(|d| d.contains(&pose))
            {
                continue;
            }
            counts.vertices_rechecked += 1;
            if self.check_state(&pose) {
                self.roadmap.mark_vertex_valid(v);
            } else {
                self.roadmap.remove_vertex(v);
                counts.vertices_dropped += 1;
            }
        }
        for e in 0..self.roadmap.edge_count() as u32 {
            let edge = *self.roadmap.edge(e);
            if edge.validity != Validity::Valid {
                continue;
            }
            let (a, b) = (*self.roadmap.pose(edge.a), *self.roadmap.pose(edge.b));
            if touches(self.space.as_ref(), changed, &a, &b) {
                self.roadmap.mark_edge_unknown(e);
                counts.edges_reset += 1;
            }
        }
        self.roadmap.refresh_components();
    }

    /// Draws `n` samples (spread over the discs) into the squares around `changed`
    /// (within the bounds), so that the roadmap keeps its density where the vertices
    /// the obstacles took were: the ways around them are in the roadmap.
    fn resample(&mut self, changed: &[ChangedDisc], n: u64) {
        let finite: Vec<&ChangedDisc> = changed.iter().filter(|d| d.radius.is_finite()).collect();
        if finite.is_empty() || n == 0 {
            return;
        }
        let per_disc = n.div_ceil(finite.len() as u64);
        for disc in finite {
            let [x, y] = disc.center;
            let square = Bounds2 {
                min: [
                    (x - disc.radius).max(self.bounds.min[0]),
                    (y - disc.radius).max(self.bounds.min[1]),
                ],
                max: [
                    (x + disc.radius).min(self.bounds.max[0]),
                    (y + disc.radius).min(self.bounds.max[1]),
                ],
            };
            if square.min[0] > square.max[0] || square.min[1] > square.max[1] {
                continue;
            }
            for _ in 0..per_disc {
                let started = Instant::now();
                let sample = self.sampler.sample(&square, None);
                self.counts.samples += 1;
                self.counts.breakdown.sampling_s += started.elapsed().as_secs_f64();
                if let Some(sample) = sample {
                    self.insert_sample(sample);
                }
            }
        }
    }

    /// Keeps (to serve again, in their order, and to save) the exact `answers` no
    /// change touches; counts the kept and the dropped.
    fn keep_untouched_answers(
        &mut self,
        answers: impl IntoIterator<Item = SavedAnswer>,
        changed: &[ChangedDisc],
        counts: &mut LoadCounts,
    ) {
        for answer in answers {
            let states: Vec<Pose2> = answer.states.iter().map(|&s| s.into()).collect();
            if answer.goal_distance.is_some() || !self.untouched(&states, changed) {
                counts.answers_dropped += 1;
                continue;
            }
            counts.answers_reused += 1;
            let path = Path {
                states,
                cost: f64::from_bits(answer.cost),
            };
            let key = (answer.start, answer.goal);
            self.warm.given.entry(key).or_default().push(answer);
            self.warm.reusable.entry(key).or_default().push_back(path);
        }
    }

    /// True when no state of `states` lies in `changed` and no motion between them may
    /// pass there (an empty path counts as touched).
    fn untouched(&self, states: &[Pose2], changed: &[ChangedDisc]) -> bool {
        !states.is_empty()
            && !states
                .windows(2)
                .any(|w| touches(self.space.as_ref(), changed, &w[0], &w[1]))
            && !states.iter().any(|s| changed.iter().any(|d| d.contains(s)))
    }

    /// Carries on with the stages of `ctx` (rebuilt for a world with obstacles added in
    /// `changed`): checks again what reaches into `changed`, and keeps every answer given
    /// so far that no change touches for serving again (the sampler is kept: its
    /// stream goes on).
    pub(super) fn carry_on(&mut self, ctx: &BuildContext, changed: &[ChangedDisc]) -> Result<()> {
        self.states = ctx.state_validity()?;
        self.motions = ctx.motion_validator()?;
        self.objective = ctx.objective();
        let mut counts = self.warm.loaded.unwrap_or_default();
        let dropped_before = counts.vertices_dropped;
        self.invalidate(changed, &mut counts);
        self.resample(changed, 2 * (counts.vertices_dropped - dropped_before));
        let given = std::mem::take(&mut self.warm.given);
        self.warm.reusable.clear();
        self.keep_untouched_answers(given.into_values().flatten(), changed, &mut counts);
        self.fresh_from = self.roadmap.vertex_count() as u32;
        self.warm.loaded = Some(counts);
        Ok(())
    }

    /// The load's counters, if a roadmap was loaded.
    pub(super) fn load_counters(&self) -> Vec<(String, u64)> {
        let Some(c) = self.warm.loaded else {
            return Vec::new();
        };
        [
            ("warm_vertices", c.vertices),
            ("warm_edges", c.edges),
            ("warm_vertices_rechecked", c.vertices_rechecked),
            ("warm_vertices_dropped", c.vertices_dropped),
            ("warm_edges_reset", c.edges_reset),
            ("warm_answers_reused", c.answers_reused),
            ("warm_answers_dropped", c.answers_dropped),
            ("warm_answers_served", c.answers_served),
        ]
        .into_iter()
        .map(|(k, v)| (k.to_string(), v))
        .collect()
    }
}
