//! The sequential mode's first step: the visiting order of the targets from path
//! costs between one representative pose per target (full or lazy cost matrix).

use crate::layout::Layout;
use crate::lazy::{lazy_solve, LazyRules, Warm};
use crate::matrix::{full_matrix, plan_matrix_rows};
use crate::oracle::PathOracle;
use crate::unreachable::unreachable_targets;
use smug_core::error::{Error, Result};
use smug_core::mission::Mission;
use smug_core::mission::{PlanOptions, Representative, SequencingCosts};
use smug_core::pipeline::Pipeline;
use smug_core::stages::{Clusters, Sequencer, Tour, TourKind};

/// The target's stand-in for sequencing, among the PoIs `layout` keeps for it (those
/// not dropped as dead ends), in the mission's order.
fn representative(
    oracle: &PathOracle,
    mission: &Mission,
    layout: &Layout,
    target: usize,
    rule: Representative,
) -> usize {
    let pois = &layout.pois[target];
    if rule == Representative::FirstPoi {
        return pois[0];
    }
    let centre = &mission.targets[target].position;
    let d = |i: usize| {
        let p = oracle.pose(i);
        (p.x - centre.x).hypot(p.y - centre.y)
    };
    let best = (0..pois.len())
        .min_by(|&a, &b| d(pois[a]).total_cmp(&d(pois[b])).then(a.cmp(&b)))
        .unwrap_or(0);
    pois[best]
}

/// The stand-ins of `targets` (indices into the mission) for sequencing, in their order.
fn representatives(
    oracle: &PathOracle,
    mission: &Mission,
    layout: &Layout,
    targets: &[usize],
    rule: Representative,
) -> Vec<usize> {
    targets
        .iter()
        .map(|&t| representative(oracle, mission, layout, t, rule))
        .collect()
}

/// The sequencing matrix's nodes: the start, the stand-ins of `targets` in their
/// order, and the end pose of an open tour.
fn matrix_nodes(
    oracle: &PathOracle,
    mission: &Mission,
    layout: &Layout,
    targets: &[usize],
    rule: Representative,
) -> Vec<usize> {
    let mut nodes = vec![layout.start];
    nodes.extend(representatives(oracle, mission, layout, targets, rule));
    if mission.end.is_some() {
        nodes.push(layout.end);
    }
    nodes
}

/// Whether the start's row is planned in the same batch as the full matrix's other
/// rows ([`plan_matrix_rows`]) instead of on its own: when the planner searches rows
/// side by side (the lattice), the oracle is symmetric and the tour is closed (the
/// start's row of [`matrix_nodes`] is then exactly the legs asked here). The searches
/// are the same, so are the plans; the start's search no longer runs alone on one core
/// (lunar rover, 2 cores: wall median 5.15 → 4.50 s, measured). A start cut off from
/// some targets is then found after the whole matrix, not its row.
fn plans_matrix_with_start_row(oracle: &PathOracle, mission: &Mission) -> bool {
    oracle.plans_rows_side_by_side() && oracle.is_symmetric() && mission.end.is_none()
}

/// The targets the start cannot reach, found from the full cost matrix's first row
/// before its other rows are planned: a robot whose start is cut off from some targets
/// (a car in a room it cannot leave) then fails in the time of one failed leg per
/// pocket, not after every row has spent its budgets. A planner answering one leg at
/// a time gets the row's legs in the matrix's own order, so a mission whose start
/// reaches every stand-in is planned exactly as before; a one-to-many planner plans
/// the start's row on its own, then the other rows together (the same plans on every
/// shipped config, measured), or, searching rows side by side on a closed tour, all
/// rows in one batch ([`plans_matrix_with_start_row`]; a cut-off start is then found
/// after the whole matrix). Where a stand-in is missed, the target's other PoIs are
/// asked too: a target is unreachable only when none is reached. Only for `"full"`
/// costs (lazy costs plan the start's legs the tour uses, first).
pub(super) fn unreached_from_start_row(
    oracle: &mut PathOracle,
    mission: &Mission,
    layout: &Layout,
    targets: &[usize],
    options: PlanOptions,
) -> Result<Vec<usize>> {
    if fills_lazily(oracle, options.sequencing_costs) {
        return Ok(Vec::new());
    }
    if plans_matrix_with_start_row(oracle, mission) {
        let nodes = matrix_nodes(oracle, mission, layout, targets, options.representative);
        plan_matrix_rows(oracle, &nodes)?;
    }
    start_row_misses(
        oracle,
        mission,
        layout,
        targets,
        options.representative,
        true,
    )
}

/// Once the order is chosen, when some leg planned so far has no path: the targets the
/// start cannot reach, from its legs to every target's stand-in (and to the other PoIs
/// of a target whose stand-in it misses). Found here, before the PoI selection plans
/// the legs between the targets' PoIs (each spending a budget where a target lies in a
/// pocket the others cannot reach), a mission with lazy costs whose robot cannot leave
/// the room it starts in fails after a few spent budgets. Missions whose legs all have
/// a path ask nothing more.
pub(super) fn unreached_after_failed_legs(
    oracle: &mut PathOracle,
    mission: &Mission,
    layout: &Layout,
    targets: &[usize],
    options: PlanOptions,
) -> Result<Vec<usize>> {
    if !oracle.has_legs_without_path() {
        return Ok(Vec::new());
    }
    start_row_misses(
        oracle,
        mission,
        layout,
        targets,
        options.representative,
        false,
    )
}

/// The targets of which the start reaches no PoI: its legs to each target's stand-in
/// (one call for a one-to-many planner; `as_the_matrix`: each leg followed by its
/// reverse for a directed model, as the full matrix asks them), then, for the
/// stand-ins missed, to the target's other PoIs.
fn start_row_misses(
    oracle: &mut PathOracle,
    mission: &Mission,
    layout: &Layout,
    targets: &[usize],
    rule: Representative,
    as_the_matrix: bool,
) -> Result<Vec<usize>> {
    let mut missed = Vec::new();
    let stand_ins = representatives(oracle, mission, layout, targets, rule);
    if oracle.answers_many() {
        oracle.plan_from(layout.start, &stand_ins)?;
    }
    for (&t, &p) in targets.iter().zip(&stand_ins) {
        let reached = oracle.cost(layout.start, p)?.is_finite();
        if as_the_matrix && !oracle.is_symmetric() && !oracle.answers_many() {
            oracle.cost(p, layout.start)?;
        }
        if !reached {
            missed.push(t);
        }
    }
    unreachable_targets(oracle, layout, &missed)
}

/// The visiting order of `targets` (indices into the mission). A lazy matrix
/// (`"lazy"` costs) with `refine_legs` refines the early legs that decide the order
/// ([`lazy_solve`]'s `settle`).
#[allow(clippy::too_many_arguments)]
pub(super) fn sequence(
    pipeline: &Pipeline,
    oracle: &mut PathOracle,
    mission: &Mission,
    layout: &Layout,
    targets: &[usize],
    rule: Representative,
    costs: SequencingCosts,
    refine_legs: bool,
) -> Result<Vec<usize>> {
    let sequencer = pipeline.sequencer.as_ref().ok_or(Error::MissingStage {
        stage: "plan".into(),
        needed: "sequencer",
    })?;
    let open = mission.end.is_some();
    let nodes = matrix_nodes(oracle, mission, layout, targets, rule);
    let n = nodes.len();
    let kind = if open {
        TourKind::OpenTo(n - 1)
    } else {
        TourKind::Closed
    };
    let tour = if fills_lazily(oracle, costs) {
        let settle = costs == SequencingCosts::Lazy && refine_legs;
        lazy_tour(sequencer.as_ref(), oracle, &nodes, kind, settle)?
    } else {
        sequencer.solve(&full_matrix(oracle, &nodes)?, kind)?
    };
    Ok(tour
        .order
        .iter()
        .filter(|&&v| v != 0 && !(open && v == n - 1))
        .map(|&v| targets[v - 1])
        .collect())
}

/// Whether the matrix is filled lazily ([`lazy_tour`]): with lazy costs, and with
/// `"full"` costs on an oracle that serves answers kept from earlier missions (a
/// [`MissionSession`](crate::MissionSession)'s replan). There the paths between the
/// targets are known already, and the pairs it does not know (from the robot's new
/// pose, or whose kept path a new obstacle blocked) are planned only where the tour
/// uses them, on lower bounds elsewhere: with an exact solver the order is optimal for
/// the full matrix of planned costs as well (a tour optimal on costs that are planned
/// or lower bounds, whose own legs are all planned, is optimal on the planned costs),
/// from a few paths instead of one per target.
fn fills_lazily(oracle: &PathOracle, costs: SequencingCosts) -> bool {
    costs != SequencingCosts::Full || oracle.has_known_answers()
}

/// The tour over `nodes` on planned costs where known and lower bounds elsewhere,
/// re-solved after planning its unplanned legs until it uses planned legs only (or a
/// planned leg has no path: then the selection finds out which target is unreachable);
/// with `settle`, until refining the early legs cannot change the order either. Each
/// round starts from the previous round's tour ([`Sequencer::solve_from`]); a round that
/// ends on planned legs only is checked by one solve from scratch ([`lazy_solve`]).
fn lazy_tour(
    sequencer: &dyn Sequencer,
    oracle: &mut PathOracle,
    nodes: &[usize],
    kind: TourKind,
    settle: bool,
) -> Result<Tour> {
    oracle.tighten_bounds(nodes)?;
    lazy_solve(
        oracle,
        nodes,
        &Clusters::singletons(nodes.len()),
        kind,
        LazyRules {
            warm: true,
            settle,
            order_only: true,
        },
        |matrix, warm| match warm {
            Some(Warm {
                tour,
                changed: Some(changed),
            }) => sequencer.solve_from_changed(matrix, kind, tour, changed),
            Some(Warm {
                tour,
                changed: None,
            }) => sequencer.solve_from(matrix, kind, tour),
            None => sequencer.solve(matrix, kind),
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use smug_core::mission::Target;
    use smug_core::pose::{Point3, Pose2};

    /// A target's stand-in is one of the PoIs the layout keeps: with the PoI nearest
    /// its centre dropped (a dead end), the nearest of the others, never the dropped
    /// one or a PoI of the wrong position in the list.
    #[test]
    fn a_stand_in_is_the_nearest_kept_poi() {
        let pois = [(4.0, 0.0), (1.0, 0.0), (0.0, 2.0), (3.0, 3.0)];
        let poses: Vec<Pose2> = std::iter::once(Pose2::new(9.0, 9.0, 0.0))
            .chain(pois.iter().map(|&(x, y)| Pose2::new(x, y, 0.0)))
            .collect();
        let (oracle, at) = oracle(&poses, vec![0.0; poses.len()]);
        let mission = Mission {
            start: poses[0],
            end: None,
            targets: vec![Target {
                id: "t".into(),
                position: Point3 {
                    x: 0.0,
                    y: 0.0,
                    z: 0.0,
                },
                pois: poses[1..].to_vec(),
            }],
        };
        let mut layout = Layout {
            start: at[0],
            end: at[0],
            pois: vec![at[1..].to_vec()],
        };
        let nearest = Representative::NearestPoi;
        assert_eq!(
            representative(&oracle, &mission, &layout, 0, nearest),
            at[2]
        );
        // (4, 0) dropped: (1, 0) is still the nearest, now second in the list.
        layout.pois[0] = vec![at[2], at[3], at[4]];
        assert_eq!(
            representative(&oracle, &mission, &layout, 0, nearest),
            at[2]
        );
        // The nearest (1, 0) dropped: (0, 2) is the nearest left.
        layout.pois[0] = vec![at[1], at[3], at[4]];
        assert_eq!(
            representative(&oracle, &mission, &layout, 0, nearest),
            at[3]
        );
        layout.pois[0] = vec![at[4]];
        assert_eq!(
            representative(&oracle, &mission, &layout, 0, nearest),
            at[4]
        );
        let first = Representative::FirstPoi;
        layout.pois[0] = vec![at[3], at[4]];
        assert_eq!(representative(&oracle, &mission, &layout, 0, first), at[3]);
    }
    use crate::test_support::{oracle, oracle_with_dead_leg, Exhaustive};
    use proptest::prelude::*;

    /// A directed model whose cheapest order by bounds ends on a leg without a path
    /// (a PoI a car can enter but not leave towards the end): the lazy tour goes round
    /// it, in another order, on planned legs only.
    #[test]
    fn a_directed_leg_without_a_path_is_routed_round() {
        let poses =
            [(0.0, 0.0), (1.0, 0.0), (2.0, 0.0), (1.0, 1.0)].map(|(x, y)| Pose2::new(x, y, 0.0));
        // Closed tours: 0 → 1 → 2 → 3 → 0 and its reverse are the cheapest; 3 → 0
        // has no path, so 0 → 3 → 2 → 1 → 0 (or another tour without it) must be taken.
        let (mut directed, nodes) = oracle_with_dead_leg(&poses, vec![1.0; 16], Some((3, 0)));
        let tour = lazy_tour(&Exhaustive, &mut directed, &nodes, TourKind::Closed, false).unwrap();
        let matrix = full_matrix(&mut directed, &nodes).unwrap();
        let cost = matrix.tour_cost(&tour.order, TourKind::Closed);
        assert!(cost.is_finite(), "tour {:?} uses the dead leg", tour.order);
        let (mut plain, nodes) = oracle(&poses, vec![1.0; 16]);
        let best = Exhaustive
            .solve(&full_matrix(&mut plain, &nodes).unwrap(), TourKind::Closed)
            .unwrap();
        assert!(cost >= best.cost - 1e-9);
    }

    /// Each `plan_rows` call's rows: (the start's x, how many goals).
    type Calls = std::sync::Arc<std::sync::Mutex<Vec<Vec<(f64, usize)>>>>;

    /// Plans straight paths and records each `plan_rows` call's rows.
    struct RowRecorder {
        objective: smug_core::objective::PathLength,
        calls: Calls,
    }

    impl smug_core::stages::PointToPointPlanner for RowRecorder {
        fn plan(&mut self, s: &Pose2, g: &Pose2) -> Result<smug_core::stages::PlannerOutcome> {
            Ok(self.plan_rows(&[(*s, vec![*g])])?.remove(0).remove(0))
        }

        fn plan_rows(
            &mut self,
            rows: &[(Pose2, Vec<Pose2>)],
        ) -> Result<Vec<Vec<smug_core::stages::PlannerOutcome>>> {
            let asked = rows.iter().map(|(s, g)| (s.x, g.len())).collect();
            self.calls.lock().unwrap().push(asked);
            let straight = |s: &Pose2, g: &Pose2| {
                let path = smug_core::path::Path::new(vec![*s, *g], &self.objective);
                smug_core::stages::PlannerOutcome::Exact(path)
            };
            Ok(rows
                .iter()
                .map(|(s, goals)| goals.iter().map(|g| straight(s, g)).collect())
                .collect())
        }

        fn answers_many(&self) -> bool {
            true
        }

        fn plans_rows_side_by_side(&self) -> bool {
            true
        }

        fn stats(&self) -> smug_core::stages::PlannerStats {
            smug_core::stages::PlannerStats::default()
        }
    }

    /// The `plan_rows` calls made for the start's row of a mission of three
    /// one-PoI targets, closed or open, with full costs.
    fn start_row_calls(open: bool) -> Vec<Vec<(f64, usize)>> {
        let objective = smug_core::objective::PathLength::default();
        let calls = Calls::default();
        let planner = RowRecorder {
            objective: objective.clone(),
            calls: calls.clone(),
        };
        let mut oracle = PathOracle::new(std::sync::Arc::new(objective), Box::new(planner));
        let target = |i: usize| smug_core::mission::Target {
            id: format!("t{i}"),
            position: smug_core::pose::Point3 {
                x: i as f64,
                y: 1.0,
                z: 0.0,
            },
            pois: vec![Pose2::new(i as f64, 2.0, 0.0)],
        };
        let mission = Mission {
            start: Pose2::new(0.0, 0.0, 0.0),
            end: open.then(|| Pose2::new(9.0, 0.0, 0.0)),
            targets: (1..4).map(target).collect(),
        };
        let layout = crate::layout::register_poses(&mut oracle, &mission);
        let options = PlanOptions {
            sequencing_costs: SequencingCosts::Full,
            ..PlanOptions::default()
        };
        let unreached =
            unreached_from_start_row(&mut oracle, &mission, &layout, &[0, 1, 2], options);
        assert!(unreached.unwrap().is_empty());
        let calls = calls.lock().unwrap().clone();
        calls
    }

    /// A closed tour on a planner searching rows side by side: the start's row is
    /// asked in the same call as the matrix's other rows (start, then each stand-in's
    /// rest of the row); an open tour still asks the start's row alone.
    #[test]
    fn the_start_row_is_planned_with_the_matrix_rows_on_a_closed_tour() {
        let closed = start_row_calls(false);
        assert_eq!(closed, vec![vec![(0.0, 3), (1.0, 2), (2.0, 1)]]);
        let open = start_row_calls(true);
        assert_eq!(open, vec![vec![(0.0, 3)]]);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(128))]
        /// With an exact solver and admissible lower bounds, the lazy tour costs what
        /// the full matrix's tour costs, from no more planned paths.
        #[test]
        fn lazy_sequencing_is_exact_with_an_exact_solver(
            points in prop::collection::vec((0.0..20.0f64, 0.0..20.0f64, -3.0..3.0f64), 3..7),
            detours in prop::collection::vec(1.0..2.0f64, 49),
            open in any::<bool>(),
        ) {
            let poses: Vec<Pose2> = points.iter().map(|&(x, y, yaw)| Pose2::new(x, y, yaw)).collect();
            let n = poses.len();
            let kind = if open { TourKind::OpenTo(n - 1) } else { TourKind::Closed };
            let (mut full_oracle, nodes) = oracle(&poses, detours.clone());
            let full = Exhaustive.solve(&full_matrix(&mut full_oracle, &nodes).unwrap(), kind).unwrap();
            let (mut lazy_oracle, nodes) = oracle(&poses, detours);
            let lazy = lazy_tour(&Exhaustive, &mut lazy_oracle, &nodes, kind, false).unwrap();
            let true_cost = full_matrix(&mut full_oracle, &nodes).unwrap().tour_cost(&lazy.order, kind);
            prop_assert!((true_cost - full.cost).abs() < 1e-9, "lazy {true_cost} vs full {}", full.cost);
            prop_assert!((lazy.cost - true_cost).abs() < 1e-9, "the lazy tour's legs are all planned");
            prop_assert!(lazy_oracle.stats().paths_planned <= full_oracle.stats().paths_planned);
        }

        /// A session's replan: an oracle that knows every pair of the targets from an
        /// earlier mission fills the full matrix lazily, and with an exact solver its
        /// tour costs what the full matrix's tour costs, from no more paths than the
        /// new start's row (a cold oracle plans the full matrix).
        #[test]
        fn a_warm_full_matrix_is_filled_lazily_at_the_full_matrix_cost(
            points in prop::collection::vec((0.0..20.0f64, 0.0..20.0f64, -3.0..3.0f64), 4..8),
            detours in prop::collection::vec(1.0..2.0f64, 64),
            open in any::<bool>(),
        ) {
            let poses: Vec<Pose2> = points.iter().map(|&(x, y, yaw)| Pose2::new(x, y, yaw)).collect();
            let n = poses.len();
            let kind = if open { TourKind::OpenTo(n - 1) } else { TourKind::Closed };
            let (mut full_oracle, nodes) = oracle(&poses, detours.clone());
            prop_assert!(!fills_lazily(&full_oracle, SequencingCosts::Full));
            let full = Exhaustive.solve(&full_matrix(&mut full_oracle, &nodes).unwrap(), kind).unwrap();
            // The earlier mission planned every pair but those of the new start (node 0).
            let (mut earlier, _) = oracle(&poses, detours.clone());
            full_matrix(&mut earlier, &nodes[1..]).unwrap();
            let (warm, nodes) = oracle(&poses, detours);
            let mut warm = warm.with_known(earlier.take_known_answers());
            prop_assert!(fills_lazily(&warm, SequencingCosts::Full));
            let tour = lazy_tour(&Exhaustive, &mut warm, &nodes, kind, false).unwrap();
            let true_cost = full_matrix(&mut full_oracle, &nodes).unwrap().tour_cost(&tour.order, kind);
            prop_assert!((true_cost - full.cost).abs() < 1e-9, "warm {true_cost} vs full {}", full.cost);
            let row = n as u64 - 1;
            prop_assert!(warm.stats().paths_planned <= row, "at most the start's row");
        }
    }
}
