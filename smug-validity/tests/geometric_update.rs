//! The geometric estimator updated locally after the elevation changed equals the
//! layer estimated again as a whole, bit for bit.

use smug_core::{CellRect, GridGeometry, GridLayer, TraversabilityEstimator, World};
use smug_validity::geometric::{GeometricEstimator, GeometricParams};

#[test]
fn a_local_update_equals_the_layer_estimated_again() {
    let g = GridGeometry::new([0.0, 0.0], 0.1, [60, 50]).unwrap();
    let hills = GridLayer::from_fn(g, |i, j| {
        ((i as f32 * 0.3).sin() + (j as f32 * 0.2).cos()) * 0.2
    });
    let mut world = World::new("hills", hills);
    world.elevation.set(0, 0, f32::NAN);
    let estimator = GeometricEstimator::new(GeometricParams::default(), 0.6).unwrap();
    let mut layer = estimator.estimate(&world).unwrap();
    for (n, rect) in [
        CellRect {
            i0: 20,
            j0: 20,
            i1: 27,
            j1: 25,
        },
        CellRect {
            i0: 0,
            j0: 44,
            i1: 5,
            j1: 50,
        },
        CellRect {
            i0: 55,
            j0: 0,
            i1: 60,
            j1: 3,
        },
    ]
    .into_iter()
    .enumerate()
    {
        for j in rect.j0..rect.j1 {
            for i in rect.i0..rect.i1 {
                let z = world.elevation.get(i, j);
                world.elevation.set(i, j, z + 0.4 + 0.01 * n as f32);
            }
        }
        assert!(estimator.update_layer(&world, &mut layer, rect).unwrap());
        let whole = estimator.estimate(&world).unwrap();
        let bits = |l: &GridLayer| l.data.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&layer), bits(&whole), "change {n}");
    }
    assert_eq!(estimator.reach(), Some(0.6));
}
