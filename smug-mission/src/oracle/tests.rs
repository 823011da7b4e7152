//! Tests of the path oracle with a straight-line planner.

use super::*;
use smug_core::objective::PathLength;
use smug_core::stages::{ChangedDisc, MotionValidator, NoPathReason, PlannerStats, Proof};

/// Connects everything with the straight line, except into pose index 2's position.
struct StraightLine {
    objective: PathLength,
    calls: u64,
}

impl PointToPointPlanner for StraightLine {
    fn plan(&mut self, start: &Pose2, goal: &Pose2) -> Result<PlannerOutcome> {
        self.calls += 1;
        if goal.x == 9.0 || start.x == 9.0 {
            return Ok(PlannerOutcome::NoPath(NoPathReason::Proved(
                Proof::Disconnected,
            )));
        }
        Ok(PlannerOutcome::Exact(Path::new(
            vec![*start, *goal],
            &self.objective,
        )))
    }

    fn stats(&self) -> PlannerStats {
        PlannerStats {
            queries: self.calls,
            ..Default::default()
        }
    }
}

fn oracle() -> PathOracle {
    let objective = PathLength::default();
    let mut oracle = PathOracle::new(
        Arc::new(objective.clone()),
        Box::new(StraightLine {
            objective,
            calls: 0,
        }),
    );
    oracle.add_pose(Pose2::new(0.0, 0.0, 0.0));
    oracle.add_pose(Pose2::new(3.0, 4.0, 1.0));
    oracle.add_pose(Pose2::new(9.0, 0.0, 0.0));
    oracle
}

/// Answers each query with the straight line times a factor that shrinks by a
/// tenth with every query of the pair, down to 1 (a roadmap that densifies).
struct Densifying {
    objective: PathLength,
    asked: HashMap<(u64, u64), u32>,
}

impl PointToPointPlanner for Densifying {
    fn plan(&mut self, start: &Pose2, goal: &Pose2) -> Result<PlannerOutcome> {
        let key = (start.x.to_bits(), goal.x.to_bits());
        let times = self.asked.entry(key).or_default();
        *times += 1;
        let mut path = Path::new(vec![*start, *goal], &self.objective);
        path.cost *= (1.3 - 0.1 * f64::from(*times)).max(1.0);
        Ok(PlannerOutcome::Exact(path))
    }

    fn stats(&self) -> PlannerStats {
        PlannerStats::default()
    }
}

#[test]
fn refine_keeps_the_cheaper_path_both_ways_and_plans_unplanned_pairs() {
    let objective = PathLength::default();
    let planner = Densifying {
        objective: objective.clone(),
        asked: HashMap::new(),
    };
    let mut o = PathOracle::new(Arc::new(objective), Box::new(planner));
    o.add_pose(Pose2::new(0.0, 0.0, 0.0));
    o.add_pose(Pose2::new(3.0, 4.0, 0.0));
    // Unplanned: planned now (factor 1.2), not reported as an improvement.
    assert!(!o.refine(0, 1).unwrap());
    assert!((o.planned_cost(0, 1).unwrap() - 6.0).abs() < 1e-12);
    // Planned again at 1.1 and 1.0: cheaper each time, the reverse pair follows.
    assert!(o.refine(0, 1).unwrap());
    assert!(o.refine(0, 1).unwrap());
    assert!((o.planned_cost(1, 0).unwrap() - 5.0).abs() < 1e-12);
    assert_eq!(o.path(1, 0).unwrap().path().unwrap().states[0], *o.pose(1));
    // No cheaper path: the cached one stays.
    assert!(!o.refine(0, 1).unwrap());
    assert!((o.planned_cost(0, 1).unwrap() - 5.0).abs() < 1e-12);
    assert_eq!(o.stats().paths_planned, 4);
}

#[test]
fn plans_once_and_reuses_reversed_paths() {
    let mut o = oracle();
    assert!(!o.is_planned(0, 1));
    let lb = o.lower_bound(0, 1);
    assert_eq!(o.cost(0, 1).unwrap(), lb);
    assert!(o.is_planned(1, 0));
    let back = o.path(1, 0).unwrap();
    assert_eq!(back.path().unwrap().states[0], *o.pose(1));
    assert_eq!(o.stats().paths_planned, 1);
    assert_eq!(o.stats().cache_hits, 1);
    assert_eq!(o.planner().stats().queries, 1);
}

#[test]
fn unreachable_pairs_cost_infinity_and_self_pairs_are_free() {
    let mut o = oracle();
    assert_eq!(o.cost(0, 2).unwrap(), f64::INFINITY);
    assert_eq!(o.planned_cost(2, 0), Some(f64::INFINITY));
    assert_eq!(o.cost(1, 1).unwrap(), 0.0);
    assert_eq!(o.stats().paths_planned, 1);
    assert_eq!(o.cost_or_bound(0, 1), o.lower_bound(0, 1));
}

#[test]
fn plan_from_plans_each_missing_pair_once_and_serves_it_after() {
    let mut o = oracle();
    o.cost(0, 1).unwrap();
    o.plan_from(0, &[1, 2, 2, 0]).unwrap();
    assert_eq!(o.stats().paths_planned, 2);
    assert_eq!(o.cost(2, 0).unwrap(), f64::INFINITY);
    assert_eq!(o.cost(0, 1).unwrap(), o.lower_bound(0, 1));
    assert_eq!(o.stats().paths_planned, 2);
}

/// Every motion valid except those ending right of x = 5.
struct LeftOfFive;

impl MotionValidator for LeftOfFive {
    fn is_valid_motion(&self, a: &Pose2, b: &Pose2) -> bool {
        a.x <= 5.0 && b.x <= 5.0
    }

    fn check_motion(&self, _: &Pose2, _: &Pose2) -> smug_core::stages::MotionCheck {
        unreachable!("not used")
    }
}

#[test]
fn known_answers_are_served_without_planning_and_rechecked_near_changes() {
    let mut first = oracle();
    first.cost(0, 1).unwrap();
    first.cost(0, 2).unwrap();
    let mut known = first.take_known_answers();
    // 0 → 1 both ways; 0 → 2 has no path: not kept.
    assert_eq!(known.len(), 2);
    let mut again = oracle().with_known(known.clone());
    let (a, b) = (*again.pose(0), *again.pose(1));
    // Registered at other indices: found by the poses.
    let j = again.add_pose(b);
    let i = again.add_pose(a);
    assert!(again.is_planned(i, j));
    assert_eq!(
        again.planned_cost(i, j),
        Some(first.planned_cost(0, 1).unwrap())
    );
    assert_eq!(again.cost(j, i).unwrap(), first.planned_cost(1, 0).unwrap());
    assert_eq!(again.stats().paths_planned, 0);
    assert_eq!(again.stats().known_hits, 1);
    // A change far away keeps them; one on the way checks them again.
    let space = smug_core::space::Se2Space::default();
    let far = ChangedDisc {
        center: [-20.0, -20.0],
        radius: 1.0,
    };
    assert_eq!(known.recheck_touched(&space, &[far], &LeftOfFive), (0, 0));
    let near = ChangedDisc {
        center: [1.5, 2.0],
        radius: 0.5,
    };
    assert_eq!(known.recheck_touched(&space, &[near], &LeftOfFive), (2, 0));
    let mut moved = KnownAnswers::default();
    let far_right = Pose2::new(6.0, 4.0, 0.0);
    let path = Path::new(vec![a, far_right], &PathLength::default());
    let planned = Arc::new(PlannedPath {
        cost: path.cost,
        outcome: PlannerOutcome::Exact(path),
    });
    moved.insert(&a, &far_right, planned);
    assert_eq!(moved.recheck_touched(&space, &[near], &LeftOfFive), (1, 1));
    assert!(moved.is_empty());
}

#[test]
fn asymmetric_oracle_plans_both_directions() {
    let mut o = oracle().with_symmetry(false);
    o.cost(0, 1).unwrap();
    assert!(!o.is_planned(1, 0));
    o.cost(1, 0).unwrap();
    assert_eq!(o.stats().paths_planned, 2);
}

/// A straight-line planner that answers many goals at once and records each search's
/// start and goals.
struct ManyAtOnce {
    objective: PathLength,
    searches: Arc<std::sync::Mutex<Vec<(f64, usize)>>>,
}

impl PointToPointPlanner for ManyAtOnce {
    fn plan(&mut self, start: &Pose2, goal: &Pose2) -> Result<PlannerOutcome> {
        Ok(self.plan_many(start, std::slice::from_ref(goal))?.remove(0))
    }

    fn plan_many(&mut self, start: &Pose2, goals: &[Pose2]) -> Result<Vec<PlannerOutcome>> {
        self.searches.lock().unwrap().push((start.x, goals.len()));
        Ok(goals
            .iter()
            .map(|g| PlannerOutcome::Exact(Path::new(vec![*start, *g], &self.objective)))
            .collect())
    }

    fn answers_many(&self) -> bool {
        true
    }

    fn plans_rows_side_by_side(&self) -> bool {
        true
    }

    fn stats(&self) -> PlannerStats {
        PlannerStats::default()
    }
}

#[test]
fn pairs_that_share_a_pose_are_one_search_from_it() {
    let objective = PathLength::default();
    let searches = Arc::new(std::sync::Mutex::new(Vec::new()));
    let planner = ManyAtOnce {
        objective: objective.clone(),
        searches: searches.clone(),
    };
    let mut o = PathOracle::new(Arc::new(objective), Box::new(planner));
    for x in 0..5 {
        o.add_pose(Pose2::new(x as f64, 1.0, 0.0));
    }
    // Pose 4 is in every pair, on either side: one search from it (the model is
    // symmetric), then every pair is served both ways without planning again.
    o.plan_pairs(&[(0, 4), (4, 1), (2, 4), (3, 4)]).unwrap();
    assert_eq!(*searches.lock().unwrap(), vec![(4.0, 4)]);
    for j in 0..4 {
        assert_eq!(o.cost(j, 4).unwrap(), o.cost(4, j).unwrap());
    }
    assert_eq!(o.stats().paths_planned, 4);
    assert_eq!(searches.lock().unwrap().len(), 1);
}

/// The straight line, with its own bounds: the straight distance plus the start's x.
struct Bounding {
    inner: StraightLine,
}

impl PointToPointPlanner for Bounding {
    fn plan(&mut self, start: &Pose2, goal: &Pose2) -> Result<PlannerOutcome> {
        self.inner.plan(start, goal)
    }

    fn cost_bounds(&mut self, starts: &[Pose2], goals: &[Pose2]) -> Result<Option<Vec<Vec<f64>>>> {
        let row = |s: &Pose2| goals.iter().map(|g| s.xy_distance(g) + s.x).collect();
        Ok(Some(starts.iter().map(row).collect()))
    }

    fn stats(&self) -> PlannerStats {
        self.inner.stats()
    }
}

#[test]
fn tightened_bounds_are_the_planners_the_larger_of_both_ways_when_symmetric() {
    let objective = PathLength::default();
    let planner = Bounding {
        inner: StraightLine {
            objective: objective.clone(),
            calls: 0,
        },
    };
    let mut o = PathOracle::new(Arc::new(objective), Box::new(planner));
    for pose in [(0.0, 0.0), (3.0, 4.0), (9.0, 0.0)] {
        o.add_pose(Pose2::new(pose.0, pose.1, 0.0));
    }
    let straight = o.lower_bound(0, 1);
    assert!(
        (straight - 5.0).abs() < 1e-9,
        "the objective's bound before"
    );
    o.tighten_bounds(&[0, 1]).unwrap();
    // 0 → 1: 5 + 0; 1 → 0: 5 + 3; a symmetric oracle takes the larger both ways.
    assert_eq!(o.lower_bound(0, 1), 8.0);
    assert_eq!(o.lower_bound(1, 0), 8.0);
    assert_eq!(
        o.lower_bound(0, 2),
        o.objective.cost_bound(o.pose(0), o.pose(2))
    );
    assert_eq!(o.planner().stats().queries, 0, "bounds plan nothing");
}
