//! The `ros2msg` schema texts of plan.mcap's message types: each top-level `.msg` text
//! followed by every type it uses, as `ros2 bag` writes them into MCAP files (a line of
//! 80 `=`, `MSG: package/Type`, the type's text), so readers need no ROS install.

/// `package/Type` and its `.msg` text, for every type plan.mcap's messages use.
const TYPES: &[(&str, &str)] = &[
    ("builtin_interfaces/Time", "int32 sec\nuint32 nanosec\n"),
    ("builtin_interfaces/Duration", "int32 sec\nuint32 nanosec\n"),
    (
        "std_msgs/Header",
        "builtin_interfaces/Time stamp\nstring frame_id\n",
    ),
    (
        "std_msgs/ColorRGBA",
        "float32 r\nfloat32 g\nfloat32 b\nfloat32 a\n",
    ),
    ("geometry_msgs/Point", "float64 x\nfloat64 y\nfloat64 z\n"),
    ("geometry_msgs/Vector3", "float64 x\nfloat64 y\nfloat64 z\n"),
    (
        "geometry_msgs/Quaternion",
        "float64 x 0\nfloat64 y 0\nfloat64 z 0\nfloat64 w 1\n",
    ),
    (
        "geometry_msgs/Pose",
        "Point position\nQuaternion orientation\n",
    ),
    (
        "geometry_msgs/PoseStamped",
        "std_msgs/Header header\nPose pose\n",
    ),
    (
        "geometry_msgs/PoseArray",
        "std_msgs/Header header\nPose[] poses\n",
    ),
    (
        "geometry_msgs/Transform",
        "Vector3 translation\nQuaternion rotation\n",
    ),
    (
        "geometry_msgs/TransformStamped",
        "std_msgs/Header header\nstring child_frame_id\nTransform transform\n",
    ),
    (
        "nav_msgs/Path",
        "std_msgs/Header header\ngeometry_msgs/PoseStamped[] poses\n",
    ),
    (
        "nav_msgs/MapMetaData",
        "builtin_interfaces/Time map_load_time\nfloat32 resolution\nuint32 width\n\
         uint32 height\ngeometry_msgs/Pose origin\n",
    ),
    (
        "nav_msgs/OccupancyGrid",
        "std_msgs/Header header\nMapMetaData info\nint8[] data\n",
    ),
    (
        "sensor_msgs/CompressedImage",
        "std_msgs/Header header\nstring format\nuint8[] data\n",
    ),
    ("visualization_msgs/UVCoordinate", "float32 u\nfloat32 v\n"),
    (
        "visualization_msgs/MeshFile",
        "string filename\nuint8[] data\n",
    ),
    (
        "visualization_msgs/Marker",
        "int32 ARROW=0\nint32 CUBE=1\nint32 SPHERE=2\nint32 CYLINDER=3\nint32 LINE_STRIP=4\n\
         int32 LINE_LIST=5\nint32 CUBE_LIST=6\nint32 SPHERE_LIST=7\nint32 POINTS=8\n\
         int32 TEXT_VIEW_FACING=9\nint32 MESH_RESOURCE=10\nint32 TRIANGLE_LIST=11\n\
         int32 ARROW_STRIP=12\nint32 ADD=0\nint32 MODIFY=0\nint32 DELETE=2\nint32 DELETEALL=3\n\
         std_msgs/Header header\nstring ns\nint32 id\nint32 type\nint32 action\n\
         geometry_msgs/Pose pose\ngeometry_msgs/Vector3 scale\nstd_msgs/ColorRGBA color\n\
         builtin_interfaces/Duration lifetime\nbool frame_locked\ngeometry_msgs/Point[] points\n\
         std_msgs/ColorRGBA[] colors\nstring texture_resource\n\
         sensor_msgs/CompressedImage texture\nUVCoordinate[] uv_coordinates\nstring text\n\
         string mesh_resource\nMeshFile mesh_file\nbool mesh_use_embedded_materials\n",
    ),
    (
        "visualization_msgs/MarkerArray",
        "visualization_msgs/Marker[] markers\n",
    ),
    (
        "tf2_msgs/TFMessage",
        "geometry_msgs/TransformStamped[] transforms\n",
    ),
];

/// The types each top-level type uses, directly or not (in the order they are listed).
const USES: &[(&str, &[&str])] = &[
    (
        "nav_msgs/Path",
        &[
            "std_msgs/Header",
            "builtin_interfaces/Time",
            "geometry_msgs/PoseStamped",
            "geometry_msgs/Pose",
            "geometry_msgs/Point",
            "geometry_msgs/Quaternion",
        ],
    ),
    (
        "geometry_msgs/PoseArray",
        &[
            "std_msgs/Header",
            "builtin_interfaces/Time",
            "geometry_msgs/Pose",
            "geometry_msgs/Point",
            "geometry_msgs/Quaternion",
        ],
    ),
    (
        "visualization_msgs/MarkerArray",
        &[
            "visualization_msgs/Marker",
            "std_msgs/Header",
            "builtin_interfaces/Time",
            "geometry_msgs/Pose",
            "geometry_msgs/Point",
            "geometry_msgs/Quaternion",
            "geometry_msgs/Vector3",
            "std_msgs/ColorRGBA",
            "builtin_interfaces/Duration",
            "sensor_msgs/CompressedImage",
            "visualization_msgs/UVCoordinate",
            "visualization_msgs/MeshFile",
        ],
    ),
    (
        "nav_msgs/OccupancyGrid",
        &[
            "std_msgs/Header",
            "builtin_interfaces/Time",
            "nav_msgs/MapMetaData",
            "geometry_msgs/Pose",
            "geometry_msgs/Point",
            "geometry_msgs/Quaternion",
        ],
    ),
    (
        "tf2_msgs/TFMessage",
        &[
            "geometry_msgs/TransformStamped",
            "std_msgs/Header",
            "builtin_interfaces/Time",
            "geometry_msgs/Transform",
            "geometry_msgs/Vector3",
            "geometry_msgs/Quaternion",
        ],
    ),
];

/// The `.msg` text of `package/Type` (empty for a type not listed).
fn text_of(name: &str) -> &'static str {
    TYPES
        .iter()
        .find(|(n, _)| *n == name)
        .map_or("", |(_, text)| text)
}

/// The MCAP schema name of a top-level type: `nav_msgs/Path` → `nav_msgs/msg/Path`.
pub fn schema_name(name: &str) -> String {
    name.replacen('/', "/msg/", 1)
}

/// The `ros2msg` schema text of a top-level type: its text, then each type it uses.
pub fn definition(name: &str) -> String {
    let uses = USES
        .iter()
        .find(|(n, _)| *n == name)
        .map_or(&[][..], |(_, uses)| uses);
    let mut text = text_of(name).to_owned();
    for used in uses {
        text.push_str(&"=".repeat(80));
        text.push_str(&format!("\nMSG: {used}\n"));
        text.push_str(text_of(used));
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_type_named_in_a_definition_is_listed_and_defined() {
        for (top, uses) in USES {
            assert!(!text_of(top).is_empty(), "{top}");
            for used in *uses {
                assert!(!text_of(used).is_empty(), "{top} uses {used}");
            }
        }
        let path = definition("nav_msgs/Path");
        assert!(path.starts_with("std_msgs/Header header\n"));
        assert!(path.contains("\nMSG: geometry_msgs/Quaternion\nfloat64 x 0\n"));
        assert_eq!(schema_name("nav_msgs/Path"), "nav_msgs/msg/Path");
    }
}
