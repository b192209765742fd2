//! The ROS 2 messages the peer reads and writes, laid out field for field as their `.msg` files
//! define them (CDR follows the declaration order), and their conversion to JSON.
//!
//! Only `sensor_msgs/msg/Range` differs between the distributions the bridge serves: Jazzy's ends
//! with `float32 variance`, Humble's does not ([`RangeLayout`]).

use std::fmt;

use serde::de::{self, DeserializeSeed, SeqAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize};
use serde_json::{json, Value};

/// `builtin_interfaces/msg/Time`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
pub struct Time {
    pub sec: i32,
    pub nanosec: u32,
}

impl Time {
    pub fn to_json(self) -> Value {
        json!({"sec": self.sec, "nanosec": self.nanosec})
    }
}

impl fmt::Display for Time {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}.{:09}", self.sec, self.nanosec)
    }
}

/// `std_msgs/msg/Header`.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub struct Header {
    pub stamp: Time,
    pub frame_id: String,
}

impl Header {
    fn to_json(&self) -> Value {
        json!({"stamp": self.stamp.to_json(), "frame_id": self.frame_id})
    }
}

/// A number for JSON: finite values exactly (an `f32` widened to `f64` loses nothing), the
/// others as the strings `"inf"`, `"-inf"` and `"nan"`, which JSON has no numbers for.
pub fn number(value: f64) -> Value {
    if value.is_finite() {
        json!(value)
    } else if value.is_nan() {
        json!("nan")
    } else if value > 0.0 {
        json!("inf")
    } else {
        json!("-inf")
    }
}

fn numbers32(values: &[f32]) -> Value {
    Value::Array(values.iter().map(|&v| number(f64::from(v))).collect())
}

fn numbers64(values: &[f64]) -> Value {
    Value::Array(values.iter().map(|&v| number(v)).collect())
}

/// `sensor_msgs/msg/Range`; `variance` is present in Jazzy's layout only.
#[derive(Clone, Debug)]
pub struct Range {
    pub header: Header,
    pub radiation_type: u8,
    pub field_of_view: f32,
    pub min_range: f32,
    pub max_range: f32,
    pub range: f32,
    pub variance: Option<f32>,
}

impl Range {
    pub fn to_json(&self) -> Value {
        let mut fields = json!({
            "header": self.header.to_json(),
            "radiation_type": self.radiation_type,
            "field_of_view": number(f64::from(self.field_of_view)),
            "min_range": number(f64::from(self.min_range)),
            "max_range": number(f64::from(self.max_range)),
            "range": number(f64::from(self.range)),
        });
        if let Some(variance) = self.variance {
            fields["variance"] = number(f64::from(variance));
        }
        fields
    }
}

/// Which distribution's `Range` to decode: the seed of its deserialisation.
#[derive(Clone, Copy, Debug)]
pub struct RangeLayout {
    pub with_variance: bool,
}

impl<'de> DeserializeSeed<'de> for RangeLayout {
    type Value = Range;

    fn deserialize<D: Deserializer<'de>>(self, deserializer: D) -> Result<Range, D::Error> {
        // Jazzy's fields; Humble's lack the last, `variance`.
        const JAZZY: &[&str] = &[
            "header",
            "radiation_type",
            "field_of_view",
            "min_range",
            "max_range",
            "range",
            "variance",
        ];
        let fields = if self.with_variance {
            JAZZY
        } else {
            &JAZZY[..JAZZY.len() - 1]
        };
        deserializer.deserialize_struct("Range", fields, self)
    }
}

fn field<'de, A: SeqAccess<'de>, T: Deserialize<'de>>(
    seq: &mut A,
    name: &str,
) -> Result<T, A::Error> {
    seq.next_element()?
        .ok_or_else(|| de::Error::custom(format!("Range ends before {name}")))
}

impl<'de> Visitor<'de> for RangeLayout {
    type Value = Range;

    fn expecting(&self, formatter: &mut fmt::Formatter) -> fmt::Result {
        formatter.write_str("a sensor_msgs/msg/Range")
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Range, A::Error> {
        Ok(Range {
            header: field(&mut seq, "header")?,
            radiation_type: field(&mut seq, "radiation_type")?,
            field_of_view: field(&mut seq, "field_of_view")?,
            min_range: field(&mut seq, "min_range")?,
            max_range: field(&mut seq, "max_range")?,
            range: field(&mut seq, "range")?,
            variance: if self.with_variance {
                Some(field(&mut seq, "variance")?)
            } else {
                None
            },
        })
    }
}

/// `sensor_msgs/msg/LaserScan`.
#[derive(Clone, Debug, Deserialize)]
pub struct LaserScan {
    pub header: Header,
    pub angle_min: f32,
    pub angle_max: f32,
    pub angle_increment: f32,
    pub time_increment: f32,
    pub scan_time: f32,
    pub range_min: f32,
    pub range_max: f32,
    pub ranges: Vec<f32>,
    pub intensities: Vec<f32>,
}

impl LaserScan {
    pub fn to_json(&self) -> Value {
        json!({
            "header": self.header.to_json(),
            "angle_min": number(f64::from(self.angle_min)),
            "angle_max": number(f64::from(self.angle_max)),
            "angle_increment": number(f64::from(self.angle_increment)),
            "time_increment": number(f64::from(self.time_increment)),
            "scan_time": number(f64::from(self.scan_time)),
            "range_min": number(f64::from(self.range_min)),
            "range_max": number(f64::from(self.range_max)),
            "ranges": numbers32(&self.ranges),
            "intensities": numbers32(&self.intensities),
        })
    }
}

/// `geometry_msgs/msg/Vector3` (also the layout of `Point`).
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize)]
pub struct Vector3 {
    pub x: f64,
    pub y: f64,
    pub z: f64,
}

impl Vector3 {
    fn to_json(self) -> Value {
        json!({"x": number(self.x), "y": number(self.y), "z": number(self.z)})
    }
}

/// `geometry_msgs/msg/Quaternion`.
#[derive(Clone, Copy, Debug, Deserialize)]
pub struct Quaternion {
    pub x: f64,
    pub y: f64,
    pub z: f64,
    pub w: f64,
}

impl Quaternion {
    fn to_json(self) -> Value {
        json!({"x": number(self.x), "y": number(self.y), "z": number(self.z), "w": number(self.w)})
    }
}

/// A `float64[36]` covariance: a fixed-size array, so CDR writes no length before it.
#[derive(Clone, Debug)]
pub struct Covariance(pub Vec<f64>);

impl<'de> Deserialize<'de> for Covariance {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Elements;
        impl<'de> Visitor<'de> for Elements {
            type Value = Covariance;
            fn expecting(&self, formatter: &mut fmt::Formatter) -> fmt::Result {
                formatter.write_str("36 float64")
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Covariance, A::Error> {
                let mut values = Vec::with_capacity(36);
                while let Some(value) = seq.next_element::<f64>()? {
                    values.push(value);
                }
                Ok(Covariance(values))
            }
        }
        deserializer.deserialize_tuple(36, Elements)
    }
}

/// `nav_msgs/msg/Odometry` with its nested pose and twist.
#[derive(Clone, Debug, Deserialize)]
pub struct Odometry {
    pub header: Header,
    pub child_frame_id: String,
    pub position: Vector3,
    pub orientation: Quaternion,
    pub pose_covariance: Covariance,
    pub linear: Vector3,
    pub angular: Vector3,
    pub twist_covariance: Covariance,
}

impl Odometry {
    pub fn to_json(&self) -> Value {
        json!({
            "header": self.header.to_json(),
            "child_frame_id": self.child_frame_id,
            "pose": {
                "position": self.position.to_json(),
                "orientation": self.orientation.to_json(),
                "covariance": numbers64(&self.pose_covariance.0),
            },
            "twist": {
                "linear": self.linear.to_json(),
                "angular": self.angular.to_json(),
                "covariance": numbers64(&self.twist_covariance.0),
            },
        })
    }
}

/// `geometry_msgs/msg/TransformStamped`.
#[derive(Clone, Debug, Deserialize)]
pub struct TransformStamped {
    pub header: Header,
    pub child_frame_id: String,
    pub translation: Vector3,
    pub rotation: Quaternion,
}

/// `tf2_msgs/msg/TFMessage`.
#[derive(Clone, Debug, Deserialize)]
pub struct TfMessage {
    pub transforms: Vec<TransformStamped>,
}

impl TransformStamped {
    pub fn to_json(&self) -> Value {
        json!({
            "header": self.header.to_json(),
            "child_frame_id": self.child_frame_id,
            "transform": {
                "translation": self.translation.to_json(),
                "rotation": self.rotation.to_json(),
            },
        })
    }
}

/// `std_msgs/msg/MultiArrayDimension`.
#[derive(Clone, Debug, Deserialize)]
pub struct MultiArrayDimension {
    pub label: String,
    pub size: u32,
    pub stride: u32,
}

/// `std_msgs/msg/Float64MultiArray` (its `MultiArrayLayout` inlined).
#[derive(Clone, Debug, Deserialize)]
pub struct Float64MultiArray {
    pub dim: Vec<MultiArrayDimension>,
    pub data_offset: u32,
    pub data: Vec<f64>,
}

impl Float64MultiArray {
    pub fn to_json(&self) -> Value {
        let dim: Vec<Value> = self
            .dim
            .iter()
            .map(|d| json!({"label": d.label, "size": d.size, "stride": d.stride}))
            .collect();
        json!({"layout": {"dim": dim, "data_offset": self.data_offset}, "data": numbers64(&self.data)})
    }
}

/// `rosgraph_msgs/msg/Clock`.
#[derive(Clone, Copy, Debug, Deserialize)]
pub struct Clock {
    pub clock: Time,
}

/// `geometry_msgs/msg/Twist`: Humble's `/cmd_vel`.
#[derive(Clone, Copy, Debug, Default, Serialize)]
pub struct Twist {
    pub linear: Vector3,
    pub angular: Vector3,
}

/// `geometry_msgs/msg/TwistStamped`: Jazzy's `/cmd_vel`.
#[derive(Clone, Debug, Serialize)]
pub struct TwistStamped {
    pub header: Header,
    pub twist: Twist,
}
