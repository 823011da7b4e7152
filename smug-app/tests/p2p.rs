//! `p2p` through the application layer: the typed result names its planner and both
//! front ends' rules for the default config hold.

use smug_app::p2p::{p2p, P2pPlanner, P2pRequest, P2pWorld};
use std::path::PathBuf;

#[test]
fn the_default_config_plans_with_its_own_planner_or_visibility_when_asked() {
    let yaml =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../configs/maps/random-32x32-d10-s1.yaml");
    let request = P2pRequest {
        config: None,
        set: Vec::new(),
        world: P2pWorld::Map {
            path: yaml,
            obstacle_height: 2.0,
        },
        prefer_exact: false,
    };
    let (planner, note) = P2pPlanner::assemble(&request).unwrap();
    assert_eq!(note, None);
    assert_ne!(planner.planner_type(), "visibility");
    let exact = P2pRequest {
        prefer_exact: true,
        ..request.clone()
    };
    let (planner, _) = P2pPlanner::assemble(&exact).unwrap();
    assert_eq!(planner.planner_type(), "visibility");
    let results = p2p(&request, &[]).unwrap();
    assert!(results.queries.is_empty());
    assert_eq!(results.first_bad_query(), None);
}
