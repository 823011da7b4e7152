//! Unit tests of the lattice's parts that need no motion model (the planner on real
//! models is tested in the workspace's `tests/lattice.rs`).

use super::*;
use smug_core::Bounds2;

#[test]
fn bad_parameters_name_their_key() {
    let cases = [
        (
            LatticeParams {
                headings: 12,
                ..Default::default()
            },
            "headings",
        ),
        (
            LatticeParams {
                headings: 60,
                ..Default::default()
            },
            "headings",
        ),
        (
            LatticeParams {
                resolution: Some(f64::NAN),
                ..Default::default()
            },
            "resolution",
        ),
        (
            LatticeParams {
                resolution: Some(0.0),
                ..Default::default()
            },
            "resolution",
        ),
        (
            LatticeParams {
                shot_radius: Some(-1.0),
                ..Default::default()
            },
            "shot_radius",
        ),
        (
            LatticeParams {
                reverse_penalty: 0.5,
                ..Default::default()
            },
            "reverse_penalty",
        ),
        (
            LatticeParams {
                gear_change_cost: f64::INFINITY,
                ..Default::default()
            },
            "gear_change_cost",
        ),
        (
            LatticeParams {
                time_limit: 0.0,
                ..Default::default()
            },
            "time_limit",
        ),
        (
            LatticeParams {
                order_heuristic_weight: 0.9,
                ..Default::default()
            },
            "order_heuristic_weight",
        ),
        (
            LatticeParams {
                order_heuristic_weight: f64::NAN,
                ..Default::default()
            },
            "order_heuristic_weight",
        ),
    ];
    for (params, key) in cases {
        let message = check_params(&params).unwrap_err().to_string();
        assert!(
            message.contains(&format!("planner.params.{key}")),
            "{message}"
        );
    }
    assert!(check_params(&LatticeParams::default()).is_ok());
}

#[test]
fn lattice_points_and_headings_round_trip() {
    let bounds = Bounds2 {
        min: [-1.0, 2.0],
        max: [4.0, 5.0],
    };
    let lattice = Lattice::new(bounds, 0.5, 16);
    assert_eq!((lattice.nx, lattice.ny), (10, 6));
    for id in [0, 17, 959] {
        let (ix, iy, k) = lattice.decode(id);
        assert_eq!(lattice.id(ix, iy, k), id);
        let pose = lattice.pose(id);
        assert_eq!(lattice.heading_bin(pose.yaw), k);
        assert!(pose.x > bounds.min[0] && pose.x < bounds.max[0]);
    }
    let near = lattice.points_near(0.0, 3.0, 0.6);
    assert!(!near.is_empty());
    for (ix, iy) in near {
        let [x, y] = lattice.position(ix, iy);
        assert!((x - 0.0).hypot(y - 3.0) <= 0.6);
    }
}
