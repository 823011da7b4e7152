//! Scenarios drawn on a map: random start/goal pairs joined by a path, with their
//! optimal octile length, bucketed and sorted as in MovingAI's files.

use super::{octile_distances, MovingAiMap, Scenario};
use rand::Rng;

/// Why no scenarios could be drawn.
#[derive(Debug, thiserror::Error)]
pub enum ScenarioGenError {
    /// No two distinct passable cells are joined by a path.
    #[error("the {width}×{height} map has no two connected passable cells")]
    NoConnectedPair {
        /// The map's width.
        width: usize,
        /// The map's height.
        height: usize,
    },
}

/// Starts tried per scenario before giving up on the map.
const MAX_TRIES: usize = 1000;

/// `count` scenarios on `map` (named `map_name` in the file), drawn with seed `seed`:
/// a uniformly random passable start, a uniformly random other cell reachable from it,
/// the optimal octile length, bucket `⌊length / 4⌋`; sorted by bucket (stable).
pub fn generate_scenarios(
    map: &MovingAiMap,
    map_name: &str,
    count: usize,
    seed: u64,
) -> Result<Vec<Scenario>, ScenarioGenError> {
    let mut rng = smug_core::rng::stage_rng(seed, "movingai-scenarios");
    let free: Vec<usize> = (0..map.passable.len())
        .filter(|&i| map.passable[i])
        .collect();
    let mut scenarios = Vec::with_capacity(count);
    while scenarios.len() < count {
        let scenario = (0..MAX_TRIES)
            .find_map(|_| draw(map, map_name, &free, &mut rng))
            .ok_or(ScenarioGenError::NoConnectedPair {
                width: map.width,
                height: map.height,
            })?;
        scenarios.push(scenario);
    }
    scenarios.sort_by_key(|s| s.bucket);
    Ok(scenarios)
}

/// One scenario from a random start, `None` when nothing else is reachable from it.
fn draw(map: &MovingAiMap, map_name: &str, free: &[usize], rng: &mut impl Rng) -> Option<Scenario> {
    if free.is_empty() {
        return None;
    }
    let start = free[rng.random_range(0..free.len())];
    let distance = octile_distances(map, cell(map, start));
    let reachable: Vec<usize> = free
        .iter()
        .copied()
        .filter(|&i| i != start && distance[i].is_finite())
        .collect();
    if reachable.is_empty() {
        return None;
    }
    let goal = reachable[rng.random_range(0..reachable.len())];
    Some(Scenario {
        bucket: (distance[goal] / 4.0) as u32,
        map: map_name.to_string(),
        width: map.width,
        height: map.height,
        start: cell(map, start),
        goal: cell(map, goal),
        optimal_length: distance[goal],
    })
}

fn cell(map: &MovingAiMap, index: usize) -> [usize; 2] {
    [index % map.width, index / map.width]
}
