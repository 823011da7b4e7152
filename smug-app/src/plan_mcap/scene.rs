//! One plan as ROS 2 messages: the path, the chosen PoIs, markers for targets and PoIs,
//! the occupancy and traversability grids, and the robot's pose along the path on `/tf`.

use crate::ros::msgs::{
    encode, ColorRgba, Header, MapMetaData, Marker, MarkerArray, OccupancyGrid, Path, Point, Pose,
    PoseArray, PoseStamped, Quaternion, TfMessage, Time, Transform, TransformStamped,
};
use smug_core::{GridLayer, Mission, Plan, Pose2, World};
use smug_worlds::export::{cell_occupancy, CellOccupancy, DEFAULT_OBSTACLE_THRESHOLD};

/// The fixed frame of every message.
pub const FRAME: &str = "map";
/// The robot's frame, moved along the path on `/tf`.
pub const ROBOT_FRAME: &str = "base_link";
/// `nav_msgs/Path`: the plan's waypoints.
pub const PLAN_TOPIC: &str = "/smug/plan";
/// `geometry_msgs/PoseArray`: the chosen PoIs in visiting order.
pub const POIS_TOPIC: &str = "/smug/pois";
/// `visualization_msgs/MarkerArray`: targets and every PoI, coloured.
pub const MARKERS_TOPIC: &str = "/smug/markers";
/// `nav_msgs/OccupancyGrid`: the occupancy (the rule of `smug worlds --export`'s PGM).
pub const OCCUPANCY_TOPIC: &str = "/smug/occupancy";
/// `nav_msgs/OccupancyGrid`: `round(100 · (1 − traversability))`, -1 where unknown.
pub const TRAVERSABILITY_TOPIC: &str = "/smug/traversability";
/// `tf2_msgs/TFMessage`: `map` → `base_link` at each waypoint.
pub const TF_TOPIC: &str = "/tf";
/// Time between two waypoints' transforms on `/tf`, nanoseconds.
pub const WAYPOINT_STEP_NS: u64 = 100_000_000;

/// A chosen PoI's colour (green).
pub const CHOSEN: ColorRgba = rgba(0.1, 0.8, 0.2, 1.0);
/// A valid PoI the plan does not use (blue).
pub const UNUSED: ColorRgba = rgba(0.3, 0.5, 0.95, 0.8);
/// A PoI the robot's validity checker rejects (red).
pub const INVALID: ColorRgba = rgba(0.9, 0.1, 0.1, 0.8);
/// A target's colour (orange).
const TARGET: ColorRgba = rgba(1.0, 0.6, 0.0, 1.0);

/// A colour.
const fn rgba(r: f32, g: f32, b: f32, a: f32) -> ColorRgba {
    ColorRgba { r, g, b, a }
}

/// What one plan's messages show.
pub struct PlanScene<'a> {
    /// The plan.
    pub plan: &'a Plan,
    /// The world it was made in.
    pub world: &'a World,
    /// The mission as given (invalid PoIs included).
    pub mission: &'a Mission,
    /// `(target, PoI index)` of the PoIs the validity checker rejected.
    pub invalid_pois: &'a [(String, usize)],
}

/// One message: topic, ROS type (`package/Type`), log time and CDR bytes.
pub struct Stamped {
    /// The topic.
    pub topic: &'static str,
    /// The ROS type, `nav_msgs/Path`.
    pub type_name: &'static str,
    /// Log (and header) time, nanoseconds.
    pub time_ns: u64,
    /// CDR bytes.
    pub data: Vec<u8>,
}

/// Every message of `scene`, stamped from `t0_ns` on (the transforms one
/// [`WAYPOINT_STEP_NS`] apart), in log-time order.
pub fn scene_messages(scene: &PlanScene<'_>, t0_ns: u64) -> Vec<Stamped> {
    let header = header_at(t0_ns);
    let stamped = |topic, type_name, data| Stamped {
        topic,
        type_name,
        time_ns: t0_ns,
        data,
    };
    let mut messages = vec![
        stamped(
            OCCUPANCY_TOPIC,
            "nav_msgs/OccupancyGrid",
            encode(&occupancy_grid(scene.world, &header)),
        ),
        stamped(
            PLAN_TOPIC,
            "nav_msgs/Path",
            encode(&path(scene.plan, &header)),
        ),
        stamped(
            POIS_TOPIC,
            "geometry_msgs/PoseArray",
            encode(&chosen_pois(scene, &header)),
        ),
        stamped(
            MARKERS_TOPIC,
            "visualization_msgs/MarkerArray",
            encode(&markers(scene, &header)),
        ),
    ];
    if let Some(layer) = &scene.world.traversability {
        messages.push(stamped(
            TRAVERSABILITY_TOPIC,
            "nav_msgs/OccupancyGrid",
            encode(&traversability_grid(layer, &header)),
        ));
    }
    for (k, w) in scene.plan.waypoints.iter().enumerate() {
        let time_ns = t0_ns + k as u64 * WAYPOINT_STEP_NS;
        let transform = TransformStamped {
            header: header_at(time_ns),
            child_frame_id: ROBOT_FRAME.into(),
            transform: Transform {
                translation: Point {
                    x: w.x,
                    y: w.y,
                    z: w.z,
                },
                rotation: Quaternion::from_yaw(w.yaw),
            },
        };
        messages.push(Stamped {
            topic: TF_TOPIC,
            type_name: "tf2_msgs/TFMessage",
            time_ns,
            data: encode(&TfMessage {
                transforms: vec![transform],
            }),
        });
    }
    messages
}

/// A header in the [`FRAME`] at `time_ns`.
pub fn header_at(time_ns: u64) -> Header {
    Header {
        stamp: Time {
            sec: i32::try_from(time_ns / 1_000_000_000).unwrap_or(i32::MAX),
            nanosec: (time_ns % 1_000_000_000) as u32,
        },
        frame_id: FRAME.into(),
    }
}

/// A pose at `(x, y, z)` heading `yaw`.
fn pose(x: f64, y: f64, z: f64, yaw: f64) -> Pose {
    Pose {
        position: Point { x, y, z },
        orientation: Quaternion::from_yaw(yaw),
    }
}

/// A PoI's pose on the terrain.
fn poi_pose(world: &World, p: &Pose2) -> Pose {
    pose(p.x, p.y, world.height_at(p.x, p.y).unwrap_or(0.0), p.yaw)
}

/// The plan's waypoints as a path.
fn path(plan: &Plan, header: &Header) -> Path {
    Path {
        header: header.clone(),
        poses: plan
            .waypoints
            .iter()
            .map(|w| PoseStamped {
                header: header.clone(),
                pose: pose(w.x, w.y, w.z, w.yaw),
            })
            .collect(),
    }
}

/// The chosen PoIs in visiting order.
fn chosen_pois(scene: &PlanScene<'_>, header: &Header) -> PoseArray {
    PoseArray {
        header: header.clone(),
        poses: scene
            .plan
            .pois
            .iter()
            .map(|c| poi_pose(scene.world, &c.pose))
            .collect(),
    }
}

/// A marker in `ns` with `id`.
fn marker(header: &Header, ns: &str, id: usize, kind: i32) -> Marker {
    Marker {
        header: header.clone(),
        ns: ns.into(),
        id: i32::try_from(id).unwrap_or(i32::MAX),
        kind,
        action: Marker::ADD,
        pose: pose(0.0, 0.0, 0.0, 0.0),
        ..Marker::default()
    }
}

/// A PoI's colour: chosen, invalid or unused.
fn poi_color(scene: &PlanScene<'_>, target: &str, index: usize) -> ColorRgba {
    let is = |t: &String, i: &usize| t == target && *i == index;
    if scene.plan.pois.iter().any(|c| is(&c.target, &c.index)) {
        CHOSEN
    } else if scene.invalid_pois.iter().any(|(t, i)| is(t, i)) {
        INVALID
    } else {
        UNUSED
    }
}

/// A marker that clears the earlier plan's, then the targets (spheres) and every PoI
/// (arrows, coloured by [`poi_color`]).
fn markers(scene: &PlanScene<'_>, header: &Header) -> MarkerArray {
    let mut clear = marker(header, "", 0, Marker::ARROW);
    clear.action = Marker::DELETE_ALL;
    let mut markers = vec![clear];
    for (k, target) in scene.mission.targets.iter().enumerate() {
        let p = &target.position;
        let mut sphere = marker(header, "targets", k, Marker::SPHERE);
        sphere.pose = pose(p.x, p.y, p.z, 0.0);
        sphere.scale = Point {
            x: 0.6,
            y: 0.6,
            z: 0.6,
        };
        sphere.color = TARGET;
        sphere.text = target.id.clone();
        markers.push(sphere);
    }
    let pois = scene
        .mission
        .targets
        .iter()
        .flat_map(|t| t.pois.iter().enumerate().map(move |(i, p)| (t, i, p)));
    for (id, (target, index, p)) in pois.enumerate() {
        let mut arrow = marker(header, "pois", id, Marker::ARROW);
        arrow.pose = poi_pose(scene.world, p);
        arrow.scale = Point {
            x: 0.6,
            y: 0.1,
            z: 0.1,
        };
        arrow.color = poi_color(scene, &target.id, index);
        arrow.text = format!("{}#{index}", target.id);
        markers.push(arrow);
    }
    MarkerArray { markers }
}

/// An occupancy grid over `layer`'s cells with `data`.
fn grid(layer: &GridLayer, header: &Header, data: Vec<i8>) -> OccupancyGrid {
    let g = &layer.geometry;
    OccupancyGrid {
        header: header.clone(),
        info: MapMetaData {
            map_load_time: header.stamp.clone(),
            resolution: g.resolution as f32,
            width: u32::try_from(g.size[0]).unwrap_or(u32::MAX),
            height: u32::try_from(g.size[1]).unwrap_or(u32::MAX),
            origin: pose(g.origin[0], g.origin[1], 0.0, 0.0),
        },
        data,
    }
}

/// The occupancy: 100 occupied, 0 free, -1 unknown (the rule of the exported PGM).
fn occupancy_grid(world: &World, header: &Header) -> OccupancyGrid {
    let cells = cell_occupancy(&world.elevation, DEFAULT_OBSTACLE_THRESHOLD);
    let data = cells
        .iter()
        .map(|c| match c {
            CellOccupancy::Free => 0,
            CellOccupancy::Occupied => 100,
            CellOccupancy::Unknown => -1,
        })
        .collect();
    grid(&world.elevation, header, data)
}

/// A traversability value as an occupancy cell: `round(100 · (1 − t))`, -1 for NaN.
pub fn traversability_cell(t: f32) -> i8 {
    if t.is_nan() {
        -1
    } else {
        (100.0 * (1.0 - t.clamp(0.0, 1.0))).round() as i8
    }
}

/// The traversability layer as an occupancy grid (see [`traversability_cell`]).
fn traversability_grid(layer: &GridLayer, header: &Header) -> OccupancyGrid {
    let data = layer.data.iter().map(|&t| traversability_cell(t)).collect();
    grid(layer, header, data)
}
