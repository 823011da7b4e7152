//! `team-auto`: `team-exact` while the problem is small, `team-lns` above.

use super::exact::{TeamExact, TeamExactParams};
use super::lns::{TeamLns, TeamLnsParams};
use serde::{Deserialize, Serialize};
use smug_core::{TeamProblem, TeamSequencer, TeamSolution};

/// Parameters of [`TeamAuto`]: the threshold, then the LNS's own parameters.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TeamAutoParams {
    /// Most targets solved exactly.
    pub exact_targets: usize,
    /// Most DP steps solved exactly: `robots · (3^targets + 2^targets · PoIs²)`.
    pub exact_work: f64,
    /// The LNS above the threshold.
    pub lns: TeamLnsParams,
}

impl Default for TeamAutoParams {
    fn default() -> Self {
        Self {
            exact_targets: 10,
            exact_work: 5e7,
            lns: TeamLnsParams::default(),
        }
    }
}

/// Exact when small, LNS otherwise.
#[derive(Clone, Debug)]
pub struct TeamAuto {
    params: TeamAutoParams,
    exact: TeamExact,
    lns: TeamLns,
}

impl TeamAuto {
    /// The combined solver; `lns` is the configured LNS (seeded, with its deadline).
    pub fn new(params: TeamAutoParams, lns: TeamLns) -> smug_core::Result<Self> {
        let exact = TeamExact::new(TeamExactParams {
            max_targets: params.exact_targets,
        })?;
        Ok(Self { params, exact, lns })
    }

    /// Whether `problem` goes to the exact solver.
    pub fn exactly(&self, problem: &TeamProblem) -> bool {
        let k = problem.targets().len();
        let pois: usize = problem.targets().iter().map(|t| t.nodes.len()).sum();
        let work = problem.robots().len() as f64
            * (3f64.powi(k as i32) + 2f64.powi(k as i32) * (pois as f64).powi(2));
        self.exact.fits(k) && work <= self.params.exact_work
    }
}

impl TeamSequencer for TeamAuto {
    fn solve(&self, problem: &TeamProblem) -> smug_core::Result<TeamSolution> {
        if self.exactly(problem) {
            self.exact.solve(problem)
        } else {
            self.lns.solve(problem)
        }
    }

    fn solve_from(
        &self,
        problem: &TeamProblem,
        initial: &TeamSolution,
    ) -> smug_core::Result<TeamSolution> {
        if self.exactly(problem) {
            problem.validate(initial)?;
            self.exact.solve(problem)
        } else {
            self.lns.solve_from(problem, initial)
        }
    }
}

smug_core::register_plugin!(
    smug_core::registry::TeamSequencerStage,
    name = "team-auto",
    summary = "team-exact up to `exact_targets` targets (default 10) and `exact_work` DP steps, team-lns above",
    params = TeamAutoParams,
    build = |params, ctx| {
        let lns = TeamLns::new(params.lns.clone(), ctx.rng("team_sequencer"))?
            .with_deadline(ctx.deadline());
        Ok(Box::new(TeamAuto::new(params, lns)?))
    },
);
