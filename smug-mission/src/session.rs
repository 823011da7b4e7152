//! A long-lived mission session: what a robot runs onboard. It keeps the assembled
//! pipeline (world with its layers, traversability estimator, validity checker, motion
//! validator, the planner with its roadmap, and the paths planned so far) in memory
//! after the first plan, and replans for each new [`MissionState`] **in place**: the
//! state's new obstacles are applied to the world's layers only where they can reach,
//! the checkers are rebuilt on the updated layers, the planner checks again only what
//! the obstacles touch, and paths no obstacle touches are served again without
//! planning. With `sequencing_costs = "full"`, the pairs of targets whose paths are
//! not kept (from the robot's new pose, or blocked by a new obstacle) are planned only
//! where the tour uses them (the matrix filled lazily, with lower bounds elsewhere).
//!
//! **Obstacles accumulate.** A state lists every obstacle seen so far: the session
//! applied the first `n` of them already (the states it replanned for before), so a
//! new state must begin with those same `n` obstacles, in the same order, and the
//! obstacles after them are the new ones. A state that drops or changes an applied
//! obstacle is refused (`obstacles[k]` named); a world without it needs a new session.

use crate::oracle::KnownAnswers;
use crate::replan::replan_mission_keeping;
use crate::run::plan_mission_keeping;
use smug_core::config::{LoadedConfig, RobotConfig};
use smug_core::error::{Error, Result};
use smug_core::mission::{add_obstacles, mask_layer, DiscObstacle};
use smug_core::mission::{Mission, PlanOptions};
use smug_core::mission::{MissionState, StateError};
use smug_core::pipeline::{DroppedPoi, Pipeline, WorldChange};
use smug_core::plan::Plan;
use smug_core::registry::{PlannerStage, TraversabilityStage};
use smug_core::stages::{CellRect, ChangedDisc, TraversabilityEstimator};
use smug_core::world::World;
use std::sync::Arc;
use std::time::Instant;

/// A pipeline kept in memory across replans (see the module documentation).
pub struct MissionSession {
    pipeline: Pipeline,
    options: PlanOptions,
    /// The config's traversability estimator, for local updates of the layer.
    estimator: Option<Box<dyn TraversabilityEstimator>>,
    /// The obstacles applied so far, in order.
    obstacles: Vec<DiscObstacle>,
    /// Paths planned by earlier plans and replans (re-checked near new obstacles).
    answers: KnownAnswers,
    /// The mission as assembled (PoIs not valid for the robot left out) and the PoIs
    /// left out, for [`plan`](Self::plan).
    assembled: (Option<Mission>, Vec<DroppedPoi>),
}

/// What one world update changed (see [`MissionSession::apply_obstacles`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct WorldUpdate {
    /// The obstacles applied by this update.
    pub applied: usize,
    /// The regions where vertices, edges and paths were looked at again.
    pub changed: Vec<ChangedDisc>,
    /// Whether the traversability layer was updated locally (false: estimated again
    /// as a whole, or no estimator).
    pub local_traversability: bool,
    /// Paths kept from earlier plans that pass near a new obstacle, checked again on
    /// the updated world.
    pub answers_checked: usize,
    /// Those found invalid and dropped.
    pub answers_dropped: usize,
    /// Whether the planner kept its roadmap (false: a new planner was built).
    pub planner_kept: bool,
}

impl MissionSession {
    /// Assembles the config's pipeline (as `smug plan` does) and keeps it.
    pub fn new(loaded: &LoadedConfig) -> Result<Self> {
        let pipeline = Pipeline::assemble(loaded)?;
        let estimator = match &loaded.config.traversability {
            Some(section) => Some(
                pipeline
                    .context()
                    .build::<TraversabilityStage>(section)?
                    .object,
            ),
            None => None,
        };
        Ok(Self {
            answers: KnownAnswers::default(),
            options: pipeline.config.plan,
            assembled: (pipeline.mission.clone(), pipeline.dropped_pois.clone()),
            pipeline,
            estimator,
            obstacles: Vec::new(),
        })
    }

    /// Plans the whole mission, as [`plan_mission`](crate::plan_mission) (the same plan as `smug plan`, bit
    /// for bit, when called first); the paths it plans are kept for the replans. After
    /// replans it plans the mission as assembled again, from its start, on the updated
    /// world.
    pub fn plan(&mut self) -> Result<Plan> {
        self.pipeline.build_times_s.clear();
        (self.pipeline.mission, self.pipeline.dropped_pois) = self.assembled.clone();
        plan_mission_keeping(&mut self.pipeline, self.options, Some(&mut self.answers))
    }

    /// Replans the rest of the mission from `state` (checked against the mission and the
    /// map, its obstacles as the module documentation says) on the session's
    /// world with the state's new obstacles applied; the same plan as [`replan_mission`](crate::replan_mission)
    /// on a pipeline assembled from scratch for the state, up to the paths reused (and,
    /// with `"full"` sequencing costs, the matrix filled lazily: see the
    /// module documentation).
    pub fn replan(&mut self, state: &MissionState) -> Result<Plan> {
        let world = self.world()?.clone();
        state
            .check(self.mission()?, &world.bounds(), "mission state")
            .map_err(|e| Error::stage("replan", e))?;
        self.pipeline.build_times_s.clear();
        self.apply_obstacles(&state.obstacles)?;
        replan_mission_keeping(
            &mut self.pipeline,
            self.options,
            state,
            Some(&mut self.answers),
        )
    }

    /// Applies the obstacles of `all` (a state's list) the session has not applied yet:
    /// the world's elevation, own occupancy and distance field in the cells each can
    /// reach, the traversability layer again where the estimator can see them (as a
    /// whole for an estimator that cannot update locally), then the objective, validity
    /// checker and motion validator rebuilt on the updated world, the planner told what
    /// changed, and the kept paths that pass near a new obstacle dropped.
    pub fn apply_obstacles(&mut self, all: &[DiscObstacle]) -> Result<WorldUpdate> {
        let new = self.new_obstacles(all)?.to_vec();
        if new.is_empty() {
            return Ok(WorldUpdate {
                planner_kept: true,
                ..WorldUpdate::default()
            });
        }
        let started = Instant::now();
        let mut world = (**self.world()?).clone();
        add_obstacles(&mut world, &new);
        let all: Vec<DiscObstacle> = self.obstacles.iter().chain(&new).copied().collect();
        let local_traversability = self.update_traversability(&mut world, &new, &all)?;
        let margin = self.change_margin(&world);
        let changed: Vec<ChangedDisc> = new
            .iter()
            .map(|o| ChangedDisc {
                center: o.center,
                radius: o.radius + margin,
            })
            .collect();
        self.pipeline
            .build_times_s
            .insert("world-update".into(), started.elapsed().as_secs_f64());
        let change = WorldChange {
            previous: self.world()?.clone(),
            obstacles: new.clone(),
        };
        self.pipeline
            .rebuild_on_world(Arc::new(world), Some(change))?;
        // The world holds them now: later states must list them.
        self.obstacles = all;
        let started = Instant::now();
        let mut planner_kept = false;
        if let Some(mut planner) = self.pipeline.planner.take() {
            planner_kept = planner
                .update_world(&self.pipeline.context(), &changed)
                .is_ok();
            if !planner_kept {
                planner = match &self.pipeline.config.planner {
                    Some(section) => {
                        self.pipeline
                            .context()
                            .build::<PlannerStage>(section)?
                            .object
                    }
                    None => planner,
                };
            }
            self.pipeline.planner = Some(planner);
        }
        let space = self.pipeline.space.clone();
        let answers = &mut self.answers;
        let (answers_checked, answers_dropped) = match &self.pipeline.motion_validator {
            Some(motions) => answers.recheck_touched(space.as_ref(), &changed, motions.as_ref()),
            None => {
                let n = answers.len();
                *answers = KnownAnswers::default();
                (n, n)
            }
        };
        self.pipeline
            .build_times_s
            .insert("planner-update".into(), started.elapsed().as_secs_f64());
        Ok(WorldUpdate {
            applied: new.len(),
            changed,
            local_traversability,
            answers_checked,
            answers_dropped,
            planner_kept,
        })
    }

    /// The obstacles of `all` after the ones applied already (which `all` must begin
    /// with, bit for bit).
    fn new_obstacles<'a>(&self, all: &'a [DiscObstacle]) -> Result<&'a [DiscObstacle]> {
        let refuse = |key: String, message: String| {
            Error::stage(
                "replan",
                StateError::Key {
                    path: "mission state".into(),
                    key,
                    message,
                },
            )
        };
        if all.len() < self.obstacles.len() {
            return Err(refuse(
                "obstacles".into(),
                format!(
                    "lists {} obstacles, the session applied {} already: obstacles only \
                     accumulate (start a new session for a world without them)",
                    all.len(),
                    self.obstacles.len()
                ),
            ));
        }
        let same = |a: &DiscObstacle, b: &DiscObstacle| {
            a.center[0].to_bits() == b.center[0].to_bits()
                && a.center[1].to_bits() == b.center[1].to_bits()
                && a.radius.to_bits() == b.radius.to_bits()
                && a.height.to_bits() == b.height.to_bits()
        };
        if let Some(k) = (0..self.obstacles.len()).find(|&k| !same(&all[k], &self.obstacles[k])) {
            return Err(refuse(
                format!("obstacles[{k}]"),
                format!(
                    "{:?} differs from the obstacle the session applied there ({:?}): a \
                     state lists the obstacles applied before first, in the same order",
                    all[k], self.obstacles[k]
                ),
            ));
        }
        Ok(&all[self.obstacles.len()..])
    }

    /// Brings the estimator's layer up to date for `world` (its elevation updated with
    /// the `latest` obstacles) and masks the cells of `all` the obstacles applied; true
    /// when done locally.
    fn update_traversability(
        &self,
        world: &mut World,
        latest: &[DiscObstacle],
        all: &[DiscObstacle],
    ) -> Result<bool> {
        let Some(estimator) = self.estimator.as_ref() else {
            return Ok(false);
        };
        let geometry = world.elevation.geometry;
        let empty = CellRect {
            i0: 0,
            j0: 0,
            i1: 0,
            j1: 0,
        };
        let changed = latest
            .iter()
            .map(|o| o.cell_rect(&geometry))
            .fold(empty, |a, b| a.union(&b));
        let mut previous = world.traversability.take();
        let local = match previous.as_mut() {
            Some(layer) => estimator.update_layer(world, layer, changed)?,
            None => false,
        };
        let mut layer = match (local, previous) {
            (true, Some(layer)) => layer,
            _ => estimator.estimate(world)?,
        };
        mask_layer(&mut layer, all);
        world.traversability = Some(layer);
        Ok(local)
    }

    /// How far beyond an obstacle's disc a validity verdict may change: the robot's
    /// reach (half its box's diagonal) or the estimator's reach, whichever is larger
    /// (unbounded for an estimator that does not say), plus two cells for the grids'
    /// rounding.
    fn change_margin(&self, world: &World) -> f64 {
        let estimator_reach = match &self.estimator {
            Some(e) => e.reach().unwrap_or(f64::INFINITY),
            None => 0.0,
        };
        robot_reach(&self.pipeline.config.robot).max(estimator_reach)
            + 2.0 * world.elevation.geometry.resolution
    }

    /// The session's world (with the obstacles applied so far).
    pub fn world(&self) -> Result<&Arc<World>> {
        self.pipeline.world.as_ref().ok_or(Error::MissingStage {
            stage: "a mission session".into(),
            needed: "world",
        })
    }

    /// The mission as the config's world gave it (PoIs invalid for the robot included).
    pub fn mission(&self) -> Result<&Mission> {
        self.pipeline
            .given_mission
            .as_ref()
            .ok_or(Error::MissingStage {
                stage: "a mission session".into(),
                needed: "world",
            })
    }

    /// The pipeline the session keeps (world, checkers, planner, kept paths).
    pub fn pipeline(&self) -> &Pipeline {
        &self.pipeline
    }

    /// The obstacles applied so far, in order.
    pub fn obstacles(&self) -> &[DiscObstacle] {
        &self.obstacles
    }

    /// The number of paths kept from earlier plans (each direction counts).
    pub fn known_paths(&self) -> usize {
        self.answers.len()
    }
}

/// Half the diagonal of the robot's base box (in 3D): no part of the box lies
/// farther from its centre.
fn robot_reach(robot: &RobotConfig) -> f64 {
    0.5 * (robot.length.powi(2) + robot.width.powi(2) + robot.height.powi(2)).sqrt()
}
