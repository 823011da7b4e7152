//! How a plan fares under every objective: its length, its cost under each registered
//! objective (so plans made with different objectives can be compared), and the
//! traversability along it.

use smug_core::config::PluginSection;
use smug_core::grid::GridLayer;
use smug_core::objective::integrate_motion;
use smug_core::pipeline::BuildContext;
use smug_core::pose::Pose2;
use smug_core::registry::{ObjectiveStage, Stage};
use smug_core::world::World;
use std::collections::BTreeMap;

pub use smug_core::plan::{PlanMetrics, RISKY_TRAVERSABILITY};

/// The metrics of the path through `states` (joined by the space's motions of `ctx`),
/// made with `ctx`'s objective, registered as `objective`.
pub fn plan_metrics(
    ctx: &BuildContext,
    world: &World,
    objective: &str,
    states: &[Pose2],
) -> PlanMetrics {
    let space = ctx.space();
    let length_m = states
        .windows(2)
        .map(|w| space.motion_extent(&w[0], &w[1]).length)
        .sum();
    let mut costs = costs_under_other_objectives(ctx, objective, states);
    costs.insert(objective.to_string(), ctx.objective().path_cost(states));
    let mut metrics = PlanMetrics {
        objective: objective.to_string(),
        length_m,
        climb_m: climb(ctx, world, states),
        costs,
        ..PlanMetrics::default()
    };
    if let Some(layer) = &world.traversability {
        let (min, mean, risky) = traversability_along(ctx, layer, states, length_m);
        metrics.traversability_min = min;
        metrics.traversability_mean = mean;
        metrics.risky_length_m = Some(risky);
    }
    metrics
}

/// The lowest and the length-weighted mean traversability along the space's motions
/// through `states` (sampled every half cell), and the length below
/// [`RISKY_TRAVERSABILITY`]; unknown traversability counts as 0.
fn traversability_along(
    ctx: &BuildContext,
    layer: &GridLayer,
    states: &[Pose2],
    length_m: f64,
) -> (Option<f64>, Option<f64>, f64) {
    let step = layer.geometry.resolution * 0.5;
    let space = ctx.space();
    let (mut min, mut weighted, mut risky) = (f64::INFINITY, 0.0, 0.0);
    for w in states.windows(2) {
        integrate_motion(space.as_ref(), &w[0], &w[1], step, |piece| {
            let tau = layer.nearest(piece.middle.x, piece.middle.y).unwrap_or(0.0);
            let length = piece.length;
            min = min.min(tau);
            weighted += tau * length;
            if tau < RISKY_TRAVERSABILITY {
                risky += length;
            }
            0.0
        });
    }
    let mean = (length_m > 0.0).then(|| weighted / length_m);
    (min.is_finite().then_some(min), mean, risky)
}

/// Height climbed along the space's motions through `states`, sampled every half cell
/// of the elevation layer (unknown heights climb nothing).
fn climb(ctx: &BuildContext, world: &World, states: &[Pose2]) -> f64 {
    let step = world.elevation.geometry.resolution * 0.5;
    let space = ctx.space();
    let height = |p: &Pose2| world.height_at(p.x, p.y);
    states
        .windows(2)
        .map(|w| {
            integrate_motion(space.as_ref(), &w[0], &w[1], step, |piece| {
                match (height(&piece.from), height(&piece.to)) {
                    (Some(a), Some(b)) => (b - a).max(0.0),
                    _ => 0.0,
                }
            })
        })
        .sum()
}

/// The cost of `states` under every registered objective but `planning` that builds in
/// `ctx` with its default parameters.
fn costs_under_other_objectives(
    ctx: &BuildContext,
    planning: &str,
    states: &[Pose2],
) -> BTreeMap<String, f64> {
    let Ok(registry) = ObjectiveStage::registry() else {
        return BTreeMap::new();
    };
    registry
        .names()
        .into_iter()
        .filter(|&name| name != planning)
        .filter_map(|name| {
            let built = ctx.build::<ObjectiveStage>(&PluginSection::new("objective", name));
            built
                .ok()
                .map(|b| (name.to_string(), b.object.path_cost(states)))
        })
        .collect()
}
