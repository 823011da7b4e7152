//! `DiscOnGrid::fault`: why a disc on a grid is invalid at a pose.

use smug_core::testing::walled_disc as walled;
use smug_core::{EndpointFault, Pose2};

#[test]
fn faults_name_the_map_border_and_the_inflated_obstacle() {
    let disc = walled();
    assert_eq!(disc.fault(&Pose2::new(1.5, 1.5, 0.0)), None);
    assert_eq!(
        disc.fault(&Pose2::new(0.1, 1.5, 0.0)),
        Some(EndpointFault::OffMap)
    );
    match disc.fault(&Pose2::new(1.9, 1.5, 0.0)) {
        Some(EndpointFault::InInflatedObstacle { distance }) => {
            assert!((distance - 0.1).abs() < 1e-12)
        }
        other => panic!("{other:?}"),
    }
    assert!(matches!(
        disc.fault(&Pose2::new(2.5, 1.5, 0.0)),
        Some(EndpointFault::InInflatedObstacle { distance }) if distance == 0.0
    ));
}
