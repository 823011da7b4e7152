//! Every solution of a tiny team problem, for testing the other team sequencers.

use smug_core::{lex_less, TeamProblem, TeamSolution, Visit};

/// Most targets [`brute_force_team`] accepts (it enumerates every ordered assignment).
pub const BRUTE_FORCE_TEAM_MAX_TARGETS: usize = 7;

/// The optimum of `problem` by enumerating every solution: each target in turn is put
/// at every position of every allowed robot's route at every one of its nodes. `None`
/// when the problem has more than [`BRUTE_FORCE_TEAM_MAX_TARGETS`] targets.
pub fn brute_force_team(problem: &TeamProblem) -> Option<TeamSolution> {
    if problem.targets().len() > BRUTE_FORCE_TEAM_MAX_TARGETS {
        return None;
    }
    let mut routes = vec![Vec::new(); problem.robots().len()];
    let mut best: Option<TeamSolution> = None;
    place(problem, 0, &mut routes, &mut best);
    best
}

fn place(
    problem: &TeamProblem,
    target: usize,
    routes: &mut Vec<Vec<Visit>>,
    best: &mut Option<TeamSolution>,
) {
    if target == problem.targets().len() {
        consider(problem, routes, best);
        return;
    }
    for r in 0..routes.len() {
        if !problem.allows(target, r) {
            continue;
        }
        for &node in &problem.targets()[target].nodes {
            for at in 0..=routes[r].len() {
                routes[r].insert(at, Visit { target, node });
                place(problem, target + 1, routes, best);
                routes[r].remove(at);
            }
        }
    }
}

fn consider(problem: &TeamProblem, routes: &[Vec<Visit>], best: &mut Option<TeamSolution>) {
    if let Some(size) = problem.route_size() {
        if routes
            .iter()
            .any(|r| r.len() < size.min || r.len() > size.max)
        {
            return;
        }
    }
    let candidate = problem.solution(routes.to_vec());
    let better = best
        .as_ref()
        .is_none_or(|b| lex_less(problem.score(&candidate), problem.score(b)));
    if better {
        *best = Some(candidate);
    }
}
