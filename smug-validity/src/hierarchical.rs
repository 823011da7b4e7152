//! `hierarchical`: the paper's two-level check. Traversability first (missing →
//! invalid, `< t_low` → invalid, `> t_high` → valid without a collision check), the
//! volumetric box check only in between.

use crate::robot_box::RobotBox;
use crate::verdicts::ThresholdVerdicts;
use crate::volumetric::{shared_volumes, VolumetricChecker, VolumetricParams};
use serde::{Deserialize, Serialize};
use smug_core::Counter;
use smug_core::{BuildContext, Counters, Error, GridLayer, Pose2, StateValidityChecker};

/// Parameters of the hierarchical checker.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct HierarchicalParams {
    /// Below this traversability a state is invalid (paper: 0.3).
    pub t_low: f64,
    /// Above this traversability a state is valid (paper: 0.3 or 0.8).
    pub t_high: f64,
    /// Subdivision levels of the volumetric check.
    pub max_depth: u32,
    /// Smallest sub-box side of the volumetric check, metres.
    pub min_size: f64,
}

impl Default for HierarchicalParams {
    fn default() -> Self {
        let volumetric = VolumetricParams::default();
        Self {
            t_low: 0.3,
            t_high: 0.3,
            max_depth: volumetric.max_depth,
            min_size: volumetric.min_size,
        }
    }
}

/// Traversability first, the volumetric check where traversability is unsure.
pub struct HierarchicalChecker {
    /// The thresholds' verdict per cell of the traversability layer.
    verdicts: ThresholdVerdicts,
    volumetric: VolumetricChecker,
    /// Every state asked (those traversability decides are these less the volumetric
    /// checker's own: one counter bump per state, not two).
    checks: Counter,
}

impl HierarchicalChecker {
    /// A checker over `traversability` with `volumetric` for the unsure band.
    pub fn new(
        traversability: &GridLayer,
        volumetric: VolumetricChecker,
        t_low: f64,
        t_high: f64,
    ) -> Result<Self, Error> {
        if !(0.0..=1.0).contains(&t_low) || !(0.0..=1.0).contains(&t_high) || t_low > t_high {
            return Err(Error::invalid_param(
                "validity",
                format!("need 0 ≤ t_low ≤ t_high ≤ 1, got t_low = {t_low}, t_high = {t_high}"),
            ));
        }
        Ok(Self {
            verdicts: ThresholdVerdicts::new(traversability, t_low, t_high),
            volumetric,
            checks: Counter::new(),
        })
    }

    /// The decision traversability alone makes, if any.
    fn traversability_verdict(&self, state: &Pose2) -> Option<bool> {
        self.verdicts.verdict(state.x, state.y)
    }
}

impl StateValidityChecker for HierarchicalChecker {
    fn is_valid(&self, state: &Pose2) -> bool {
        self.checks.increment();
        match self.traversability_verdict(state) {
            Some(verdict) => verdict,
            None => self.volumetric.is_valid(state),
        }
    }

    fn counters(&self) -> Counters {
        let mut counters = self.volumetric.counters();
        let volumetric = counters.get("checks").copied().unwrap_or(0);
        let checks = self.checks.total();
        counters.insert("volumetric_checks".into(), volumetric);
        counters.insert("checks".into(), checks);
        counters.insert(
            "traversability_decided".into(),
            checks.saturating_sub(volumetric),
        );
        counters
    }
}

fn build_hierarchical(
    params: HierarchicalParams,
    ctx: &BuildContext,
) -> Result<HierarchicalChecker, Error> {
    let world = ctx.world()?;
    let traversability = world.traversability.as_ref().ok_or_else(|| {
        Error::invalid_param(
            "validity",
            "the hierarchical checker needs a traversability layer: add a [traversability] section \
             (e.g. type = \"geometric\") or use a world that has one",
        )
    })?;
    let robot = RobotBox::from_robot(ctx.robot());
    let volumes = shared_volumes(ctx, &robot)?;
    let volumetric = VolumetricChecker::with_shared_volumes(
        world.clone(),
        volumes.clone(),
        robot,
        VolumetricParams {
            max_depth: params.max_depth,
            min_size: params.min_size,
        },
    )?;
    let checker =
        HierarchicalChecker::new(traversability, volumetric, params.t_low, params.t_high)?;
    if params.t_low < params.t_high {
        // States in the band need the volumes: derive them now, as part of the build.
        // With t_low = t_high only a traversability of exactly the threshold does, so
        // they are derived on first use, if ever.
        volumes.volumes();
    }
    Ok(checker)
}

smug_core::register_plugin!(
    smug_core::registry::ValidityStage,
    name = "hierarchical",
    summary = "traversability thresholds first, the volumetric box check only in between",
    params = HierarchicalParams,
    build = |params, ctx| Ok(Box::new(build_hierarchical(params, ctx)?)),
);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::volumes::SharedVolumes;
    use smug_core::{GridGeometry, RobotConfig, World};
    use std::sync::Arc;

    fn flat_world(traversability: f32) -> Arc<World> {
        let g = GridGeometry::new([0.0, 0.0], 0.1, [40, 40]).unwrap();
        let mut world = World::new("flat", GridLayer::filled(g, 0.0));
        world.traversability = Some(GridLayer::filled(g, traversability));
        Arc::new(world)
    }

    #[test]
    fn volumes_are_derived_when_the_band_is_open_and_shared_by_the_checkers() {
        let world = flat_world(0.5);
        let ctx = BuildContext::new(1, RobotConfig::default()).with_world(world.clone());
        let headroom = RobotBox::from_robot(ctx.robot()).headroom();
        let fastest = build_hierarchical(HierarchicalParams::default(), &ctx).unwrap();
        for k in 0..20 {
            assert!(fastest.is_valid(&Pose2::new(0.8 + 0.1 * k as f64, 2.0, 0.0)));
        }
        let shared = SharedVolumes::for_world(&world, headroom).unwrap();
        assert!(
            !shared.is_derived(),
            "t_low = t_high never needs the volumes"
        );
        let banded = HierarchicalParams {
            t_high: 0.8,
            ..Default::default()
        };
        let checker = build_hierarchical(banded, &ctx).unwrap();
        assert!(
            shared.is_derived(),
            "derived by the build, for every checker"
        );
        assert!(checker.is_valid(&Pose2::new(2.0, 2.0, 0.0)));
        assert_eq!(checker.counters()["volumetric_checks"], 1);
        assert_eq!(fastest.counters()["esdf_queries"], 0);
    }
}
