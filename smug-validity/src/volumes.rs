//! Occupancy voxels and their Euclidean signed distance field, derived from a world's
//! elevation layer: every voxel whose centre lies at or below the terrain (or in a
//! column without data) is occupied. The union of occupied voxel cubes is the
//! geometry both box checkers test against.
//!
//! The checkers built for one world share its derived volumes ([`SharedVolumes`]):
//! derived once, on first use, so a checker that never needs them (the hierarchical
//! checker with `t_low = t_high`) never pays for them.

use crate::edt::squared_edt_3d;
use crate::volumes_update::{update_distances, update_occupancy};
use crate::ValidityError;
use smug_core::mission::DiscObstacle;
use smug_core::Counter;
use smug_core::{MemoryLimit, VoxelGeometry, VoxelGrid, World};
use std::sync::{Arc, Mutex, OnceLock, PoisonError, Weak};

/// Largest voxel count derived automatically (≈ 1.6 GB of distances).
const MAX_VOXELS: usize = 400_000_000;

/// Occupancy and signed distances of a world, with a query counter.
#[derive(Debug)]
pub struct Volumes {
    /// Occupied voxels.
    pub occupancy: VoxelGrid<bool>,
    /// Signed distance (metres) from each voxel centre to the nearest occupied voxel
    /// centre (positive), or minus the distance to the nearest free one (inside).
    pub esdf: VoxelGrid<f32>,
    queries: Counter,
}

impl Volumes {
    /// Volumes of `world`: its own occupancy/ESDF when it carries both, otherwise derived
    /// from the elevation with `headroom` metres of free space above the highest terrain.
    pub fn from_world(world: &World, headroom: f64) -> Result<Self, ValidityError> {
        if let (Some(occupancy), Some(esdf)) = (&world.occupancy, &world.esdf) {
            if occupancy.geometry != esdf.geometry {
                return Err(ValidityError::Map(
                    "the world's occupancy and ESDF grids differ in geometry".into(),
                ));
            }
            return Ok(Self::new(occupancy.clone(), esdf.clone()));
        }
        Ok(Self::from_occupancy(occupancy_from_elevation(
            world, headroom,
        )?))
    }

    /// Volumes of an occupancy grid (computes the ESDF).
    pub fn from_occupancy(occupancy: VoxelGrid<bool>) -> Self {
        let esdf = signed_distance_field(&occupancy);
        Self::new(occupancy, esdf)
    }

    fn new(occupancy: VoxelGrid<bool>, esdf: VoxelGrid<f32>) -> Self {
        Self {
            occupancy,
            esdf,
            queries: Counter::new(),
        }
    }

    /// The voxel geometry.
    pub fn geometry(&self) -> &VoxelGeometry {
        &self.occupancy.geometry
    }

    /// A lower bound of the distance from `p` to the occupied voxel cubes (≤ 0 when
    /// `p` may be inside); `None` outside the grid (unknown space). Counts one query.
    pub fn distance_lower_bound(&self, p: [f64; 3]) -> Option<f64> {
        self.queries.increment();
        let g = &self.occupancy.geometry;
        let v = g.voxel_of(p)?;
        let c = g.center_of(v);
        let offset = ((p[0] - c[0]).powi(2) + (p[1] - c[1]).powi(2) + (p[2] - c[2]).powi(2)).sqrt();
        let d = *self.esdf.get(v) as f64;
        // Distances run between voxel centres; a cube reaches √3/2·res closer than its
        // centre, and the distance field is 1-Lipschitz (the offset from the centre).
        Some(d - 0.5 * 3f64.sqrt() * g.resolution - offset)
    }

    /// Distance-field queries so far.
    pub fn queries(&self) -> u64 {
        self.queries.total()
    }

    /// True when the axis-aligned box `[min, max]` lies inside the grid.
    pub fn contains_box(&self, min: [f64; 3], max: [f64; 3]) -> bool {
        box_inside(&self.occupancy.geometry, min, max)
    }
}

/// True when the axis-aligned box `[min, max]` lies inside the voxel grid `g`.
pub(crate) fn box_inside(g: &VoxelGeometry, min: [f64; 3], max: [f64; 3]) -> bool {
    (0..3).all(|a| min[a] >= g.origin[a] && max[a] <= g.origin[a] + g.size[a] as f64 * g.resolution)
}

/// The volumes of one world, derived on first use (occupancy alone, or occupancy and
/// distance field) and shared by every checker built for that world with the same
/// headroom, for as long as one of them lives.
#[derive(Clone, Debug)]
pub struct SharedVolumes(Arc<VolumeSource>);

/// What the volumes are derived from, and what has been derived so far.
#[derive(Debug)]
struct VolumeSource {
    world: Arc<World>,
    headroom: f64,
    /// The occupancy geometry to voxelise the elevation into; `None` when the world
    /// carries its own occupancy and distance field.
    derived_geometry: Option<VoxelGeometry>,
    /// The occupancy alone, when asked for before the volumes.
    occupancy: OnceLock<VoxelGrid<bool>>,
    volumes: OnceLock<Arc<Volumes>>,
}

impl SharedVolumes {
    /// The shared volumes of `world` with `headroom` metres of free space above the
    /// terrain (the ones already shared for it, else new ones). Fails, without deriving
    /// anything, when the world cannot give volumes (see [`Volumes::from_world`]).
    pub fn for_world(world: &Arc<World>, headroom: f64) -> Result<Self, ValidityError> {
        Self::for_world_within(world, headroom, MemoryLimit::default())
    }

    /// [`for_world`](Self::for_world) with a voxel grid that must fit `memory` (a run's
    /// limit).
    pub fn for_world_within(
        world: &Arc<World>,
        headroom: f64,
        memory: MemoryLimit,
    ) -> Result<Self, ValidityError> {
        let derived_geometry = match (&world.occupancy, &world.esdf) {
            (Some(occupancy), Some(esdf)) if occupancy.geometry != esdf.geometry => {
                return Err(ValidityError::Map(
                    "the world's occupancy and ESDF grids differ in geometry".into(),
                ))
            }
            (Some(_), Some(_)) => None,
            _ => Some(occupancy_geometry(world, headroom, memory)?),
        };
        Ok(Self(shared_source(world, headroom, derived_geometry)))
    }

    /// Volumes computed already (not shared with other checkers).
    pub fn ready(world: Arc<World>, volumes: Arc<Volumes>) -> Self {
        Self(Arc::new(VolumeSource {
            world,
            headroom: f64::NAN,
            derived_geometry: None,
            occupancy: OnceLock::new(),
            volumes: OnceLock::from(volumes),
        }))
    }

    /// The volumes (derived now if not yet).
    pub fn volumes(&self) -> &Arc<Volumes> {
        let source = &self.0;
        source
            .volumes
            .get_or_init(|| Arc::new(source.derive_volumes()))
    }

    /// The occupancy (derived now if not yet; the distance field is not needed).
    pub fn occupancy(&self) -> &VoxelGrid<bool> {
        let source = &self.0;
        match source.volumes.get() {
            Some(volumes) => &volumes.occupancy,
            None => source.occupancy.get_or_init(|| source.derive_occupancy()),
        }
    }

    /// True once the volumes (with the distance field) have been derived.
    pub fn is_derived(&self) -> bool {
        self.0.volumes.get().is_some()
    }

    /// The shared volumes of `world`, which is `previous` with `obstacles` added
    /// ([`smug_core::mission::add_obstacles`]), updated from those derived for `previous`
    /// (with the same `headroom`, still held by a checker) instead of derived again: the
    /// obstacles' columns voxelised again and the distance field recomputed in a window
    /// around them (`volumes_update`), the same volumes bit for bit. `None` when that
    /// cannot be done (nothing derived for `previous`, a world carrying its own volumes,
    /// a voxel grid of another extent, a distance not settled in the window): derive
    /// them with [`for_world`](Self::for_world) instead.
    pub fn updated(
        previous: &Arc<World>,
        world: &Arc<World>,
        headroom: f64,
        obstacles: &[DiscObstacle],
    ) -> Option<Self> {
        let old = live_source(previous, headroom)?;
        let geometry = old.derived_geometry?;
        if occupancy_geometry(world, headroom, MemoryLimit::default()).ok()? != geometry {
            return None;
        }
        let occupancy = match old.volumes.get() {
            Some(volumes) => &volumes.occupancy,
            None => old.occupancy.get()?,
        };
        let mut occupancy = occupancy.clone();
        let added = update_occupancy(&mut occupancy, world, obstacles);
        let source = match old.volumes.get() {
            Some(volumes) => {
                let mut esdf = volumes.esdf.clone();
                if !update_distances(&mut esdf, &occupancy, &added) {
                    return None;
                }
                VolumeSource {
                    world: world.clone(),
                    headroom,
                    derived_geometry: Some(geometry),
                    occupancy: OnceLock::new(),
                    volumes: OnceLock::from(Arc::new(Volumes::new(occupancy, esdf))),
                }
            }
            None => VolumeSource {
                world: world.clone(),
                headroom,
                derived_geometry: Some(geometry),
                occupancy: OnceLock::from(occupancy),
                volumes: OnceLock::new(),
            },
        };
        Some(Self(register(source)))
    }
}

impl VolumeSource {
    fn derive_occupancy(&self) -> VoxelGrid<bool> {
        match (self.derived_geometry, &self.world.occupancy) {
            (Some(geometry), _) => voxelise(&self.world, geometry),
            (None, Some(occupancy)) => occupancy.clone(),
            (None, None) => unreachable!("volumes without a source are built ready"),
        }
    }

    fn derive_volumes(&self) -> Volumes {
        if let (None, Some(occupancy), Some(esdf)) = (
            self.derived_geometry,
            &self.world.occupancy,
            &self.world.esdf,
        ) {
            return Volumes::new(occupancy.clone(), esdf.clone());
        }
        let occupancy = match self.occupancy.get() {
            Some(occupancy) => occupancy.clone(),
            None => self.derive_occupancy(),
        };
        Volumes::from_occupancy(occupancy)
    }
}

/// The volume sources alive (held by a checker).
static SOURCES: Mutex<Vec<Weak<VolumeSource>>> = Mutex::new(Vec::new());

/// The live volume source of `world` and `headroom`, if any.
fn live_source(world: &Arc<World>, headroom: f64) -> Option<Arc<VolumeSource>> {
    let mut sources = SOURCES.lock().unwrap_or_else(PoisonError::into_inner);
    sources.retain(|source| source.strong_count() > 0);
    let same = |source: &Arc<VolumeSource>| {
        Arc::ptr_eq(&source.world, world) && source.headroom.to_bits() == headroom.to_bits()
    };
    sources.iter().filter_map(Weak::upgrade).find(same)
}

/// Registers `source` (for a world that has none yet).
fn register(source: VolumeSource) -> Arc<VolumeSource> {
    let source = Arc::new(source);
    let mut sources = SOURCES.lock().unwrap_or_else(PoisonError::into_inner);
    sources.push(Arc::downgrade(&source));
    source
}

/// The live volume source of `world` and `headroom`, or a new one (registered).
fn shared_source(
    world: &Arc<World>,
    headroom: f64,
    derived_geometry: Option<VoxelGeometry>,
) -> Arc<VolumeSource> {
    if let Some(found) = live_source(world, headroom) {
        return found;
    }
    register(VolumeSource {
        world: world.clone(),
        headroom,
        derived_geometry,
        occupancy: OnceLock::new(),
        volumes: OnceLock::new(),
    })
}

/// Voxelises the terrain: ground and everything below it occupied, columns without
/// elevation data occupied (unknown space is not free).
pub fn occupancy_from_elevation(
    world: &World,
    headroom: f64,
) -> Result<VoxelGrid<bool>, ValidityError> {
    let geometry = occupancy_geometry(world, headroom, MemoryLimit::default())?;
    Ok(voxelise(world, geometry))
}

/// The voxel grid [`occupancy_from_elevation`] fills: the elevation's cells, from two
/// voxels below the lowest terrain to `headroom` above the highest, within `memory`.
fn occupancy_geometry(
    world: &World,
    headroom: f64,
    memory: MemoryLimit,
) -> Result<VoxelGeometry, ValidityError> {
    let elevation = &world.elevation;
    let (low, high) = elevation
        .data
        .iter()
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v as f64), hi.max(v as f64))
        });
    if !low.is_finite() {
        return Err(ValidityError::Map(format!(
            "world `{}` has no elevation data",
            world.name
        )));
    }
    let g = elevation.geometry;
    let res = g.resolution;
    let z0 = low - 2.0 * res;
    let nz = ((high + headroom.max(0.0) - z0) / res).ceil() as usize + 1;
    let [nx, ny] = g.size;
    if nx.saturating_mul(ny).saturating_mul(nz) > MAX_VOXELS {
        return Err(ValidityError::Map(format!(
            "world `{}` needs {nx}×{ny}×{nz} voxels at {res} m (more than {MAX_VOXELS}); use a coarser map",
            world.name
        )));
    }
    VoxelGeometry::new_within([g.origin[0], g.origin[1], z0], res, [nx, ny, nz], memory)
        .map_err(|e| ValidityError::Map(e.to_string()))
}

/// Fills `geometry` (from [`occupancy_geometry`]) with the terrain of `world`.
fn voxelise(world: &World, geometry: VoxelGeometry) -> VoxelGrid<bool> {
    let elevation = &world.elevation;
    let (z0, res) = (geometry.origin[2], geometry.resolution);
    let [nx, ny, nz] = geometry.size;
    let mut grid = VoxelGrid::filled(geometry, false);
    for j in 0..ny {
        for i in 0..nx {
            let h = elevation.get(i, j) as f64;
            for k in 0..nz {
                let z = z0 + (k as f64 + 0.5) * res;
                if h.is_nan() || z <= h {
                    grid.set([i, j, k], true);
                } else {
                    break;
                }
            }
        }
    }
    grid
}

/// The signed distance field of `occupancy` in metres.
pub fn signed_distance_field(occupancy: &VoxelGrid<bool>) -> VoxelGrid<f32> {
    let g = occupancy.geometry;
    // The two transforms are independent: side by side.
    let (outside, inside) = rayon::join(
        || squared_edt_3d(&occupancy.data, g.size),
        || {
            let free: Vec<bool> = occupancy.data.iter().map(|o| !o).collect();
            squared_edt_3d(&free, g.size)
        },
    );
    let data = occupancy
        .data
        .iter()
        .zip(outside.iter().zip(&inside))
        .map(|(&occupied, (&out, &ins))| {
            let d = if occupied { -ins.sqrt() } else { out.sqrt() };
            (d * g.resolution).clamp(-1e6, 1e6) as f32
        })
        .collect();
    VoxelGrid { geometry: g, data }
}

#[cfg(test)]
mod tests {
    use super::*;
    use smug_core::{GridGeometry, GridLayer};

    /// A small world of bumps and a hole (no data).
    fn bumpy_world() -> Arc<World> {
        let g = GridGeometry::new([0.0, 0.0], 0.1, [24, 20]).unwrap();
        let mut elevation = GridLayer::from_fn(g, |i, j| ((i * 7 + j * 3) % 5) as f32 * 0.04);
        elevation.set(3, 4, f32::NAN);
        Arc::new(World::new("bumps", elevation))
    }

    #[test]
    fn shared_volumes_are_derived_once_on_first_use_as_from_world_derives_them() {
        let world = bumpy_world();
        let (a, b) = (
            SharedVolumes::for_world(&world, 0.5).unwrap(),
            SharedVolumes::for_world(&world, 0.5).unwrap(),
        );
        let other_headroom = SharedVolumes::for_world(&world, 0.7).unwrap();
        let direct = Volumes::from_world(&world, 0.5).unwrap();
        assert!(!a.is_derived());
        assert_eq!(a.occupancy(), &direct.occupancy);
        assert!(
            !b.is_derived(),
            "the occupancy alone does not need the distance field"
        );
        let volumes = a.volumes().clone();
        assert!(b.is_derived() && Arc::ptr_eq(&volumes, b.volumes()));
        assert!(!other_headroom.is_derived());
        assert_eq!(volumes.occupancy, direct.occupancy);
        assert_eq!(volumes.esdf, direct.esdf);
        let equal_world = Arc::new((*world).clone());
        assert!(!SharedVolumes::for_world(&equal_world, 0.5)
            .unwrap()
            .is_derived());
    }

    #[test]
    fn shared_volumes_live_as_long_as_a_holder() {
        let world = bumpy_world();
        SharedVolumes::for_world(&world, 0.5).unwrap().volumes();
        assert!(!SharedVolumes::for_world(&world, 0.5).unwrap().is_derived());
    }

    #[test]
    fn a_world_without_elevation_fails_before_deriving() {
        let world = bumpy_world();
        let mut empty = (*world).clone();
        empty.elevation.data.iter_mut().for_each(|v| *v = f32::NAN);
        assert!(SharedVolumes::for_world(&Arc::new(empty), 0.5).is_err());
    }
}

/// Incremental updates (`volumes_update`) against volumes derived from scratch.
#[cfg(test)]
mod update_tests {
    use super::{SharedVolumes, Volumes};
    use proptest::prelude::*;
    use smug_core::mission::{add_obstacles, DiscObstacle};
    use smug_core::{GridGeometry, GridLayer, World};
    use std::sync::Arc;

    /// Hills, a pit and a hole without data.
    fn terrain() -> World {
        let g = GridGeometry::new([0.0, 0.0], 0.1, [40, 30]).unwrap();
        let mut elevation = GridLayer::from_fn(g, |i, j| {
            let pit = if (10..14).contains(&i) && (5..9).contains(&j) {
                -0.6
            } else {
                0.0
            };
            ((i as f32 * 0.4).sin() * 0.15 + (j as f32 * 0.3).cos() * 0.1) + pit
        });
        elevation.set(30, 20, f32::NAN);
        World::new("terrain", elevation)
    }

    fn bits(v: &Volumes) -> (Vec<bool>, Vec<u32>) {
        (
            v.occupancy.data.clone(),
            v.esdf.data.iter().map(|d| d.to_bits()).collect(),
        )
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(24))]
        /// Updated volumes equal the volumes derived from scratch, bit for bit, after
        /// one to three obstacles added in two steps (low ones, in the pit, on the
        /// border, over the hole); or the update declines.
        #[test]
        fn updated_volumes_equal_derived_ones(
            discs in prop::collection::vec((0.0..4.0f64, 0.0..3.0f64, 0.05..0.6f64, 0.05..0.25f64), 1..4),
            split in 0usize..3,
        ) {
            let headroom = 0.8;
            let obstacles: Vec<DiscObstacle> = discs
                .iter()
                .map(|&(x, y, radius, height)| DiscObstacle { center: [x, y], radius, height })
                .collect();
            let split = split.min(obstacles.len());
            let mut world = Arc::new(terrain());
            // The volumes of each world stay held (sources live while a holder does).
            let mut held = vec![SharedVolumes::for_world(&world, headroom).unwrap()];
            let mut geometry = *held[0].volumes().geometry();
            for step in [&obstacles[..split], &obstacles[split..]] {
                let mut next = (*world).clone();
                add_obstacles(&mut next, step);
                let next = Arc::new(next);
                let derived = Volumes::from_world(&next, headroom).unwrap();
                match SharedVolumes::updated(&world, &next, headroom, step) {
                    Some(updated) => {
                        prop_assert!(updated.is_derived());
                        prop_assert_eq!(bits(updated.volumes()), bits(&derived));
                        held.push(updated);
                    }
                    None => {
                        // Only a grid of another extent (an obstacle's top above the
                        // highest terrain) is declined here.
                        prop_assert_ne!(derived.geometry(), &geometry);
                        let volumes = SharedVolumes::for_world(&next, headroom).unwrap();
                        volumes.volumes();
                        held.push(volumes);
                    }
                }
                geometry = *derived.geometry();
                world = next;
            }
        }
    }
}
