//! The messages of the interface as Rust types, laid out field for field as
//! ROS 2 (Jazzy) defines them, so that their CDR encoding is what any other
//! ROS 2 node sends: `std_msgs`, `geometry_msgs`, `nav2_msgs`,
//! `vision_msgs`, and this repository's `sitlog_msgs` (its `.msg`, `.srv`
//! and `.action` files are in `ros/sitlog_msgs/`, for a ROS workspace to
//! build). A message with no field is encoded, as ROS 2 does, with one
//! `uint8` placeholder.

use ros2_client::Message;
use serde::de::{SeqAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// `std_msgs/msg/String`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct StdString {
    pub data: String,
}
impl Message for StdString {}

/// `std_msgs/msg/Bool`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct StdBool {
    pub data: bool,
}
impl Message for StdBool {}

/// `builtin_interfaces/msg/Time`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Time {
    pub sec: i32,
    pub nanosec: u32,
}

impl Time {
    /// The wall clock now.
    pub fn now() -> Time {
        let d = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .unwrap_or_default();
        Time {
            sec: i32::try_from(d.as_secs()).unwrap_or(i32::MAX),
            nanosec: d.subsec_nanos(),
        }
    }
}

/// `builtin_interfaces/msg/Duration`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Duration {
    pub sec: i32,
    pub nanosec: u32,
}

/// `std_msgs/msg/Header`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Header {
    pub stamp: Time,
    pub frame_id: String,
}

/// `geometry_msgs/msg/Point`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Point {
    pub x: f64,
    pub y: f64,
    pub z: f64,
}

/// `geometry_msgs/msg/Quaternion`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Quaternion {
    pub x: f64,
    pub y: f64,
    pub z: f64,
    pub w: f64,
}

impl Default for Quaternion {
    fn default() -> Quaternion {
        Quaternion::yaw(0.0)
    }
}

impl Quaternion {
    /// A turn of `yaw` radians about +z.
    pub fn yaw(yaw: f64) -> Quaternion {
        let h = yaw / 2.0;
        Quaternion {
            x: 0.0,
            y: 0.0,
            z: h.sin(),
            w: h.cos(),
        }
    }
}

/// `geometry_msgs/msg/Pose`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Pose {
    pub position: Point,
    pub orientation: Quaternion,
}

/// `geometry_msgs/msg/PoseStamped`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PoseStamped {
    pub header: Header,
    pub pose: Pose,
}

/// `nav2_msgs/action/NavigateToPose`: the goal.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct NavigateToPoseGoal {
    pub pose: PoseStamped,
    pub behavior_tree: String,
}
impl Message for NavigateToPoseGoal {}

/// `nav2_msgs/action/NavigateToPose`: the result (Jazzy: an error code and
/// message; 0 when it succeeded).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct NavigateToPoseResult {
    pub error_code: u16,
    pub error_msg: String,
}
impl Message for NavigateToPoseResult {}

/// `nav2_msgs/action/NavigateToPose`: the feedback (never read here).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct NavigateToPoseFeedback {
    pub current_pose: PoseStamped,
    pub navigation_time: Duration,
    pub estimated_time_remaining: Duration,
    pub number_of_recoveries: i16,
    pub distance_remaining: f32,
}
impl Message for NavigateToPoseFeedback {}

/// `nav2_msgs` error code `UNKNOWN`: what the simulated robot's navigation
/// sends with a failure (the failure itself in `error_msg`).
pub const NAV2_UNKNOWN: u16 = 9000;

/// `geometry_msgs/msg/PoseWithCovariance`'s 6×6 covariance (a fixed array
/// of 36: serde's derives stop at 32).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Covariance(pub [f64; 36]);

impl Default for Covariance {
    fn default() -> Covariance {
        Covariance([0.0; 36])
    }
}

impl Serialize for Covariance {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeTuple;
        let mut t = s.serialize_tuple(36)?;
        for v in &self.0 {
            t.serialize_element(v)?;
        }
        t.end()
    }
}

impl<'de> Deserialize<'de> for Covariance {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Covariance, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = Covariance;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("36 numbers")
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Covariance, A::Error> {
                let mut out = [0.0; 36];
                for (i, slot) in out.iter_mut().enumerate() {
                    *slot = seq
                        .next_element()?
                        .ok_or_else(|| serde::de::Error::invalid_length(i, &self))?;
                }
                Ok(Covariance(out))
            }
        }
        d.deserialize_tuple(36, V)
    }
}

/// `geometry_msgs/msg/PoseWithCovariance`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PoseWithCovariance {
    pub pose: Pose,
    pub covariance: Covariance,
}

/// `vision_msgs/msg/ObjectHypothesis`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ObjectHypothesis {
    pub class_id: String,
    pub score: f64,
}

/// `vision_msgs/msg/ObjectHypothesisWithPose`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ObjectHypothesisWithPose {
    pub hypothesis: ObjectHypothesis,
    pub pose: PoseWithCovariance,
}

/// `vision_msgs/msg/Point2D`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Point2D {
    pub x: f64,
    pub y: f64,
}

/// `vision_msgs/msg/Pose2D`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Pose2D {
    pub position: Point2D,
    pub theta: f64,
}

/// `vision_msgs/msg/BoundingBox2D`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct BoundingBox2D {
    pub center: Pose2D,
    pub size_x: f64,
    pub size_y: f64,
}

/// `vision_msgs/msg/Detection2D`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Detection2D {
    pub header: Header,
    pub results: Vec<ObjectHypothesisWithPose>,
    pub bbox: BoundingBox2D,
    pub id: String,
}

/// `vision_msgs/msg/Detection2DArray`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Detection2DArray {
    pub header: Header,
    pub detections: Vec<Detection2D>,
}

/// `sitlog_msgs/srv/DetectObjects`: the request (which camera; empty: the
/// robot's default).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct DetectObjectsRequest {
    pub camera: String,
}
impl Message for DetectObjectsRequest {}

/// `sitlog_msgs/srv/DetectObjects`: the response, what the camera sees.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct DetectObjectsResponse {
    pub detections: Detection2DArray,
}
impl Message for DetectObjectsResponse {}

/// An empty request or feedback (ROS 2's placeholder byte).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Empty {
    pub structure_needs_at_least_one_member: u8,
}
impl Message for Empty {}

/// `sitlog_msgs/srv/GetHands`: the response (an object's name, or empty
/// for a free hand).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct GetHandsResponse {
    pub left: String,
    pub right: String,
}
impl Message for GetHandsResponse {}

/// `sitlog_msgs/action/Grasp`: the goal.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct GraspGoal {
    pub object: String,
    pub hand: String,
}
impl Message for GraspGoal {}

/// `sitlog_msgs/action/Place` and `sitlog_msgs/action/HandOver`: the goal.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct HandGoal {
    pub hand: String,
}
impl Message for HandGoal {}

/// `sitlog_msgs/action/Grasp`, `Place` and `HandOver`: the result, the
/// behaviour's status (`ok`, or why not: `grasp_failed`, `on_floor`, ...).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct StatusResult {
    pub status: String,
}
impl Message for StatusResult {}

/// `sitlog_msgs/action/WaitForPerson`: the goal.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct WaitForPersonGoal {
    pub max_seconds: f64,
}
impl Message for WaitForPersonGoal {}

/// `sitlog_msgs/action/WaitForPerson`: the result.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct WaitForPersonResult {
    pub present: bool,
}
impl Message for WaitForPersonResult {}

/// `sitlog_msgs/msg/TextMessage`: a text message to someone away.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct TextMessage {
    pub to: String,
    pub text: String,
}
impl Message for TextMessage {}
