//! One step's message set: what the bridge publishes after each command (and once, stamped
//! 1 ns, before the first), gathered until complete, its stamps checked against `/clock`.

use serde_json::{json, Value};

use crate::commands::Command;
use crate::messages::{number, Float64MultiArray, LaserScan, Odometry, Range, TfMessage, Time};

/// The e-puck's `Range` topics: eight proximity sensors, then three ground sensors.
pub const RANGE_TOPICS: [&str; 11] = [
    "ps0", "ps1", "ps2", "ps3", "ps4", "ps5", "ps6", "ps7", "gs0", "gs1", "gs2",
];

/// A decoded message and the topic (index into `RANGE_TOPICS` for ranges) it came on.
#[derive(Debug)]
pub enum Sample {
    Range(usize, Range),
    Scan(LaserScan),
    Odom(Odometry),
    Tf(TfMessage),
    Sensors(Float64MultiArray),
    Pose(Float64MultiArray),
    Clock(Time),
}

/// The messages of one step received so far.
#[derive(Debug, Default)]
pub struct StepSet {
    ranges: [Option<Range>; RANGE_TOPICS.len()],
    scan: Option<LaserScan>,
    odom: Option<Odometry>,
    tf: Option<TfMessage>,
    sensors: Option<Float64MultiArray>,
    pose: Option<Float64MultiArray>,
    clock: Option<Time>,
}

fn put<T>(slot: &mut Option<T>, value: T, topic: &str) -> Result<(), String> {
    if slot.replace(value).is_some() {
        return Err(format!(
            "/{topic} arrived twice in one step (one command, one message set)"
        ));
    }
    Ok(())
}

impl StepSet {
    /// Files a message; a second one on the same topic within a step is an error.
    pub fn add(&mut self, sample: Sample) -> Result<(), String> {
        match sample {
            Sample::Range(index, range) => put(&mut self.ranges[index], range, RANGE_TOPICS[index]),
            Sample::Scan(scan) => put(&mut self.scan, scan, "scan"),
            Sample::Odom(odom) => put(&mut self.odom, odom, "odom"),
            Sample::Tf(tf) => put(&mut self.tf, tf, "tf"),
            Sample::Sensors(sensors) => put(&mut self.sensors, sensors, "sensors"),
            Sample::Pose(pose) => put(&mut self.pose, pose, "pose"),
            Sample::Clock(clock) => put(&mut self.clock, clock, "clock"),
        }
    }

    /// The topics still awaited.
    pub fn missing(&self) -> Vec<String> {
        let mut missing: Vec<String> = RANGE_TOPICS
            .iter()
            .zip(&self.ranges)
            .filter(|(_, range)| range.is_none())
            .map(|(topic, _)| format!("/{topic}"))
            .collect();
        let others = [
            ("/scan", self.scan.is_none()),
            ("/odom", self.odom.is_none()),
            ("/tf", self.tf.is_none()),
            ("/sensors", self.sensors.is_none()),
            ("/pose", self.pose.is_none()),
            ("/clock", self.clock.is_none()),
        ];
        missing.extend(
            others
                .iter()
                .filter(|(_, absent)| *absent)
                .map(|(topic, _)| topic.to_string()),
        );
        missing
    }

    /// The step's simulation time, once every message is in and stamped with it.
    pub fn complete(&self) -> Result<Option<Time>, String> {
        if !self.missing().is_empty() {
            return Ok(None);
        }
        let clock = self.clock.expect("a complete set has a clock");
        let mut stamps: Vec<(String, Time)> = RANGE_TOPICS
            .iter()
            .zip(&self.ranges)
            .map(|(topic, range)| {
                (
                    format!("/{topic}"),
                    range.as_ref().expect("complete").header.stamp,
                )
            })
            .collect();
        stamps.push((
            "/scan".into(),
            self.scan.as_ref().expect("complete").header.stamp,
        ));
        stamps.push((
            "/odom".into(),
            self.odom.as_ref().expect("complete").header.stamp,
        ));
        let tf = self.tf.as_ref().expect("complete");
        if tf.transforms.is_empty() {
            return Err("/tf carried no transform".into());
        }
        stamps.extend(
            tf.transforms
                .iter()
                .map(|t| ("/tf".to_string(), t.header.stamp)),
        );
        for (topic, stamp) in stamps {
            if stamp != clock {
                return Err(format!(
                    "{topic} is stamped {stamp}, but /clock says {clock}"
                ));
            }
        }
        Ok(Some(clock))
    }

    /// The step as one JSON object: every decoded field; `command` is what caused it.
    pub fn to_json(&self, step: usize, command: Option<Command>) -> Value {
        let ranges: serde_json::Map<String, Value> = RANGE_TOPICS
            .iter()
            .zip(&self.ranges)
            .filter_map(|(topic, range)| range.as_ref().map(|r| (topic.to_string(), r.to_json())))
            .collect();
        json!({
            "step": step,
            "command": command.map(|c| json!({"linear_x": number(c.linear_x), "angular_z": number(c.angular_z)})),
            "clock": self.clock.map(Time::to_json),
            "ranges": ranges,
            "scan": self.scan.as_ref().map(LaserScan::to_json),
            "odom": self.odom.as_ref().map(Odometry::to_json),
            "tf": self.tf.as_ref().map(|tf| tf.transforms.iter().map(|t| t.to_json()).collect::<Vec<_>>()),
            "sensors": self.sensors.as_ref().map(Float64MultiArray::to_json),
            "pose": self.pose.as_ref().map(Float64MultiArray::to_json),
        })
    }
}
