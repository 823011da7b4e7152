//! The ROS 2 messages plan.mcap holds, field for field as their `.msg` files (Humble and
//! later), with their CDR encoding and decoding.

use super::cdr::{CdrError, CdrReader, CdrWriter};

/// A value with a CDR encoding.
pub trait Cdr: Sized {
    /// Appends the value.
    fn write(&self, w: &mut CdrWriter);
    /// Reads the value.
    fn read(r: &mut CdrReader<'_>) -> Result<Self, CdrError>;
}

/// Implements [`Cdr`] for primitives with their reader's and writer's method.
macro_rules! primitive {
    ($($ty:ty => $method:ident),*) => {$(
        impl Cdr for $ty {
            fn write(&self, w: &mut CdrWriter) {
                w.$method(*self);
            }
            fn read(r: &mut CdrReader<'_>) -> Result<Self, CdrError> {
                r.$method()
            }
        }
    )*};
}
primitive!(u8 => u8, i8 => i8, bool => bool, i32 => i32, u32 => u32, f32 => f32, f64 => f64);

impl Cdr for String {
    fn write(&self, w: &mut CdrWriter) {
        w.string(self);
    }
    fn read(r: &mut CdrReader<'_>) -> Result<Self, CdrError> {
        r.string()
    }
}

impl<T: Cdr> Cdr for Vec<T> {
    fn write(&self, w: &mut CdrWriter) {
        w.len(self.len());
        self.iter().for_each(|item| item.write(w));
    }
    fn read(r: &mut CdrReader<'_>) -> Result<Self, CdrError> {
        let n = r.count()?;
        // Never trust a count to reserve memory: each item reads at least one byte.
        let mut items = Vec::with_capacity(n.min(1 << 16));
        for _ in 0..n {
            items.push(T::read(r)?);
        }
        Ok(items)
    }
}

/// A message type's struct, its fields in the `.msg` order, and its [`Cdr`] impl.
macro_rules! message {
    ($(#[$doc:meta])* $name:ident { $($(#[$fdoc:meta])* $field:ident: $ty:ty,)* }) => {
        $(#[$doc])*
        #[derive(Clone, Debug, Default, PartialEq)]
        pub struct $name {
            $($(#[$fdoc])* pub $field: $ty,)*
        }
        impl Cdr for $name {
            #[allow(unused_variables)]
            fn write(&self, w: &mut CdrWriter) {
                $(self.$field.write(w);)*
            }
            #[allow(unused_variables)]
            fn read(r: &mut CdrReader<'_>) -> Result<Self, CdrError> {
                Ok(Self { $($field: Cdr::read(r)?,)* })
            }
        }
    };
}

message!(
    /// `builtin_interfaces/Time` (also `Duration`'s layout).
    Time {
        /// Seconds.
        sec: i32,
        /// Nanoseconds within the second.
        nanosec: u32,
    }
);

message!(
    /// `std_msgs/Header`.
    Header {
        /// When.
        stamp: Time,
        /// The frame the data is in.
        frame_id: String,
    }
);

message!(
    /// `geometry_msgs/Point` (also `Vector3`'s layout).
    Point {
        /// x.
        x: f64,
        /// y.
        y: f64,
        /// z.
        z: f64,
    }
);

message!(
    /// `geometry_msgs/Quaternion`.
    Quaternion {
        /// x.
        x: f64,
        /// y.
        y: f64,
        /// z.
        z: f64,
        /// w.
        w: f64,
    }
);

message!(
    /// `geometry_msgs/Pose`.
    Pose {
        /// Position.
        position: Point,
        /// Orientation.
        orientation: Quaternion,
    }
);

message!(
    /// `geometry_msgs/PoseStamped`.
    PoseStamped {
        /// Stamp and frame.
        header: Header,
        /// The pose.
        pose: Pose,
    }
);

message!(
    /// `nav_msgs/Path`.
    Path {
        /// Stamp and frame.
        header: Header,
        /// The poses from start to end.
        poses: Vec<PoseStamped>,
    }
);

message!(
    /// `geometry_msgs/PoseArray`.
    PoseArray {
        /// Stamp and frame.
        header: Header,
        /// The poses.
        poses: Vec<Pose>,
    }
);

message!(
    /// `std_msgs/ColorRGBA`.
    ColorRgba {
        /// Red in [0, 1].
        r: f32,
        /// Green.
        g: f32,
        /// Blue.
        b: f32,
        /// Opacity.
        a: f32,
    }
);

message!(
    /// `sensor_msgs/CompressedImage` (a marker's texture; SMUG leaves it empty).
    CompressedImage {
        /// Stamp and frame.
        header: Header,
        /// `jpeg` or `png`.
        format: String,
        /// The image bytes.
        data: Vec<u8>,
    }
);

message!(
    /// `visualization_msgs/UVCoordinate`.
    UvCoordinate {
        /// u.
        u: f32,
        /// v.
        v: f32,
    }
);

message!(
    /// `visualization_msgs/MeshFile`.
    MeshFile {
        /// The file name.
        filename: String,
        /// Its bytes.
        data: Vec<u8>,
    }
);

message!(
    /// `visualization_msgs/Marker`.
    Marker {
        /// Stamp and frame.
        header: Header,
        /// Namespace.
        ns: String,
        /// Id within the namespace.
        id: i32,
        /// Shape ([`Marker::ARROW`], [`Marker::SPHERE`], …).
        kind: i32,
        /// [`Marker::ADD`] or [`Marker::DELETE_ALL`].
        action: i32,
        /// Where.
        pose: Pose,
        /// Size (a `Vector3`).
        scale: Point,
        /// Colour.
        color: ColorRgba,
        /// How long it lives (a `Duration`; zero: forever).
        lifetime: Time,
        /// Re-transformed every frame.
        frame_locked: bool,
        /// Points (line lists).
        points: Vec<Point>,
        /// Per-point colours.
        colors: Vec<ColorRgba>,
        /// Texture URI.
        texture_resource: String,
        /// Texture image.
        texture: CompressedImage,
        /// Texture coordinates.
        uv_coordinates: Vec<UvCoordinate>,
        /// Text (text markers).
        text: String,
        /// Mesh URI.
        mesh_resource: String,
        /// Embedded mesh.
        mesh_file: MeshFile,
        /// Use the mesh's materials.
        mesh_use_embedded_materials: bool,
    }
);

impl Marker {
    /// `ARROW`.
    pub const ARROW: i32 = 0;
    /// `SPHERE`.
    pub const SPHERE: i32 = 2;
    /// `LINE_LIST`.
    pub const LINE_LIST: i32 = 5;
    /// `ADD`.
    pub const ADD: i32 = 0;
    /// `DELETEALL`.
    pub const DELETE_ALL: i32 = 3;
}

message!(
    /// `visualization_msgs/MarkerArray`.
    MarkerArray {
        /// The markers.
        markers: Vec<Marker>,
    }
);

message!(
    /// `nav_msgs/MapMetaData`.
    MapMetaData {
        /// When the map was loaded.
        map_load_time: Time,
        /// Cell size, metres.
        resolution: f32,
        /// Cells along x.
        width: u32,
        /// Cells along y.
        height: u32,
        /// Cell (0, 0)'s lower-left corner.
        origin: Pose,
    }
);

message!(
    /// `nav_msgs/OccupancyGrid`: row-major from the origin, 0-100 or -1 (unknown).
    OccupancyGrid {
        /// Stamp and frame.
        header: Header,
        /// Geometry.
        info: MapMetaData,
        /// The cells.
        data: Vec<i8>,
    }
);

message!(
    /// `geometry_msgs/Transform`.
    Transform {
        /// Translation (a `Vector3`).
        translation: Point,
        /// Rotation.
        rotation: Quaternion,
    }
);

message!(
    /// `geometry_msgs/TransformStamped`.
    TransformStamped {
        /// Stamp and parent frame.
        header: Header,
        /// The child frame.
        child_frame_id: String,
        /// Parent to child.
        transform: Transform,
    }
);

message!(
    /// `tf2_msgs/TFMessage`.
    TfMessage {
        /// The transforms.
        transforms: Vec<TransformStamped>,
    }
);

/// A message's CDR bytes, header first.
pub fn encode<M: Cdr>(message: &M) -> Vec<u8> {
    let mut w = CdrWriter::default();
    message.write(&mut w);
    w.into_bytes()
}

/// A message from its CDR bytes.
pub fn decode<M: Cdr>(bytes: &[u8]) -> Result<M, CdrError> {
    M::read(&mut CdrReader::new(bytes)?)
}

impl Quaternion {
    /// The rotation by `yaw` about z.
    pub fn from_yaw(yaw: f64) -> Self {
        let half = 0.5 * yaw;
        Self {
            x: 0.0,
            y: 0.0,
            z: half.sin(),
            w: half.cos(),
        }
    }

    /// The yaw of a rotation about z.
    pub fn yaw(&self) -> f64 {
        2.0 * self.z.atan2(self.w)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_header_is_stamp_then_frame() {
        let header = Header {
            stamp: Time { sec: 1, nanosec: 2 },
            frame_id: "map".into(),
        };
        #[rustfmt::skip]
        let expected = [
            0, 1, 0, 0,
            1, 0, 0, 0,  2, 0, 0, 0,          // stamp
            4, 0, 0, 0,  b'm', b'a', b'p', 0,  // frame_id
        ];
        assert_eq!(encode(&header), expected);
        assert_eq!(decode::<Header>(&expected).unwrap(), header);
    }

    #[test]
    fn a_path_of_one_pose_aligns_its_doubles_to_8() {
        let header = Header {
            stamp: Time::default(),
            frame_id: "m".into(),
        };
        let path = Path {
            header: header.clone(),
            poses: vec![PoseStamped {
                header,
                pose: Pose {
                    position: Point {
                        x: 1.0,
                        y: 0.0,
                        z: 0.0,
                    },
                    orientation: Quaternion::from_yaw(0.0),
                },
            }],
        };
        let one = 1.0f64.to_le_bytes();
        let zero = [0u8; 8];
        let mut expected = vec![0, 1, 0, 0];
        expected.extend([0, 0, 0, 0, 0, 0, 0, 0]); // stamp
        expected.extend([2, 0, 0, 0, b'm', 0]); // frame_id "m", at 8..14
        expected.extend([0, 0]); // pad to 16 for the count
        expected.extend([1, 0, 0, 0]); // one pose, at 16..20
        expected.extend([0, 0, 0, 0, 0, 0, 0, 0]); // its stamp, 20..28
        expected.extend([2, 0, 0, 0, b'm', 0]); // its frame, 28..34
        expected.extend([0, 0, 0, 0, 0, 0]); // pad to 40 for the doubles
        for v in [one, zero, zero, zero, zero, zero, one] {
            expected.extend(v); // x y z, qx qy qz qw
        }
        assert_eq!(encode(&path), expected);
        assert_eq!(decode::<Path>(&expected).unwrap(), path);
    }

    #[test]
    fn an_occupancy_grid_is_header_info_then_bytes() {
        let grid = OccupancyGrid {
            header: Header::default(),
            info: MapMetaData {
                map_load_time: Time::default(),
                resolution: 0.5,
                width: 2,
                height: 1,
                origin: Pose::default(),
            },
            data: vec![-1, 100],
        };
        let mut expected = vec![0, 1, 0, 0];
        expected.extend([0; 8]); // stamp
        expected.extend([1, 0, 0, 0, 0]); // frame_id "", at 8..13
        expected.extend([0, 0, 0]); // pad to 16
        expected.extend([0; 8]); // map_load_time, 16..24
        expected.extend(0.5f32.to_le_bytes()); // resolution, 24..28
        expected.extend([2, 0, 0, 0, 1, 0, 0, 0]); // width, height, 28..36
        expected.extend([0; 4]); // pad to 40
        expected.extend([0; 56]); // origin: 7 zero doubles (a default quaternion is 0)
        expected.extend([2, 0, 0, 0, 0xff, 100]); // the cells
        assert_eq!(encode(&grid), expected);
        assert_eq!(decode::<OccupancyGrid>(&expected).unwrap(), grid);
    }

    #[test]
    fn a_marker_round_trips_and_yaw_survives_the_quaternion() {
        let marker = Marker {
            ns: "pois".into(),
            id: 3,
            kind: Marker::ARROW,
            pose: Pose {
                position: Point {
                    x: 1.0,
                    y: 2.0,
                    z: 3.0,
                },
                orientation: Quaternion::from_yaw(-2.5),
            },
            color: ColorRgba {
                r: 1.0,
                g: 0.0,
                b: 0.0,
                a: 1.0,
            },
            points: vec![Point::default(); 2],
            ..Marker::default()
        };
        let array = MarkerArray {
            markers: vec![marker.clone(), marker],
        };
        assert_eq!(decode::<MarkerArray>(&encode(&array)).unwrap(), array);
        assert!((array.markers[0].pose.orientation.yaw() + 2.5).abs() < 1e-12);
    }
}
