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
    pub topic: String,
    /// The ROS type, `nav_msgs/Path`.
    pub type_name: &'static str,
    /// Log (and header) time, nanoseconds.
    pub time_ns: u64,
    /// CDR bytes.
    pub data: Vec<u8>,
}

/// Where one robot's messages go: its path and chosen PoIs' topics, its frame on `/tf`.
pub struct RobotTopics {
    /// `nav_msgs/Path` topic.
    pub plan: String,
    /// `geometry_msgs/PoseArray` topic.
    pub pois: String,
    /// The child frame of its transforms.
    pub frame: String,
}

impl RobotTopics {
    /// A single robot's: [`PLAN_TOPIC`], [`POIS_TOPIC`], `ROBOT_FRAME`.
    pub fn single() -> Self {
        Self {
            plan: PLAN_TOPIC.into(),
            pois: POIS_TOPIC.into(),
            frame: ROBOT_FRAME.into(),
        }
    }

    /// Team robot `name`'s: `/smug/<name>/plan`, `/smug/<name>/pois` and frame
    /// `<name>/base_link`, the name made a ROS name (characters other than letters,
    /// digits and `_` become `_`; a leading digit gets an `r`).
    pub fn of_robot(name: &str) -> Self {
        let mut ros: String = name
            .chars()
            .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
            .collect();
        if !ros.starts_with(|c: char| c.is_ascii_alphabetic()) {
            ros.insert(0, 'r');
        }
        Self {
            plan: format!("/smug/{ros}/plan"),
            pois: format!("/smug/{ros}/pois"),
            frame: format!("{ros}/{ROBOT_FRAME}"),
        }
    }
}

/// A message on `topic` of `type_name` at `time_ns`.
fn stamped(topic: &str, type_name: &'static str, time_ns: u64, data: Vec<u8>) -> Stamped {
    Stamped {
        topic: topic.into(),
        type_name,
        time_ns,
        data,
    }
}

/// Every message of `scene`, stamped from `t0_ns` on (the transforms one
/// `WAYPOINT_STEP_NS` apart), in log-time order.
pub fn scene_messages(scene: &PlanScene<'_>, t0_ns: u64) -> Vec<Stamped> {
    let topics = RobotTopics::single();
    let mut messages = vec![occupancy_message(scene, t0_ns)];
    messages.extend(route_messages(scene, &topics, t0_ns));
    messages.extend(map_messages(scene, t0_ns));
    messages.extend(transforms(scene.plan, &topics, t0_ns));
    messages
}

/// The occupancy grid of `scene`'s world at `t0_ns`.
pub(super) fn occupancy_message(scene: &PlanScene<'_>, t0_ns: u64) -> Stamped {
    let grid = occupancy_grid(scene.world, &header_at(t0_ns));
    stamped(
        OCCUPANCY_TOPIC,
        "nav_msgs/OccupancyGrid",
        t0_ns,
        encode(&grid),
    )
}

/// `scene`'s markers (targets, every PoI coloured) and traversability grid at `t0_ns`.
pub(super) fn map_messages(scene: &PlanScene<'_>, t0_ns: u64) -> Vec<Stamped> {
    let header = header_at(t0_ns);
    let mut messages = vec![stamped(
        MARKERS_TOPIC,
        "visualization_msgs/MarkerArray",
        t0_ns,
        encode(&markers(scene, &header)),
    )];
    if let Some(layer) = &scene.world.traversability {
        messages.push(stamped(
            TRAVERSABILITY_TOPIC,
            "nav_msgs/OccupancyGrid",
            t0_ns,
            encode(&traversability_grid(layer, &header)),
        ));
    }
    messages
}

/// `scene.plan`'s path and chosen PoIs on `topics` at `t0_ns`.
pub(super) fn route_messages(
    scene: &PlanScene<'_>,
    topics: &RobotTopics,
    t0_ns: u64,
) -> [Stamped; 2] {
    let header = header_at(t0_ns);
    [
        stamped(
            &topics.plan,
            "nav_msgs/Path",
            t0_ns,
            encode(&path(scene.plan, &header)),
        ),
        stamped(
            &topics.pois,
            "geometry_msgs/PoseArray",
            t0_ns,
            encode(&chosen_pois(scene, &header)),
        ),
    ]
}

/// `map` → `topics.frame` at each of `plan`'s waypoints, one [`WAYPOINT_STEP_NS`]
/// apart from `t0_ns` on.
pub(super) fn transforms(plan: &Plan, topics: &RobotTopics, t0_ns: u64) -> Vec<Stamped> {
    let mut messages = Vec::with_capacity(plan.waypoints.len());
    for (k, w) in plan.waypoints.iter().enumerate() {
        let time_ns = t0_ns + k as u64 * WAYPOINT_STEP_NS;
        let transform = TransformStamped {
            header: header_at(time_ns),
            child_frame_id: topics.frame.clone(),
            transform: Transform {
                translation: Point {
                    x: w.x,
                    y: w.y,
                    z: w.z,
                },
                rotation: Quaternion::from_yaw(w.yaw),
            },
        };
        let message = TfMessage {
            transforms: vec![transform],
        };
        messages.push(stamped(
            TF_TOPIC,
            "tf2_msgs/TFMessage",
            time_ns,
            encode(&message),
        ));
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
