//! `ros2-peer`: drives mazesim's ROS 2 bridge in lockstep from a second process built on an
//! independent ROS 2 implementation (ros2-client over RustDDS), and writes every decoded field
//! of every step as JSON lines, for the tests to compare with the in-process simulator.
//!
//! The protocol is the bridge's (docs/ros2.md, "Lockstep"): subscribe to the state topics, create
//! the `/cmd_vel` writer last, wait for the reset state (stamped 1 ns), then answer each step's
//! message set (its `/clock` and every state topic stamped with it) with one command.

mod commands;
mod layout;
mod messages;
mod options;
mod step;

use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::pin::Pin;
use std::process::ExitCode;
use std::time::{Duration, Instant};

use futures::stream::{self, Stream, StreamExt};
use ros2_client::qos::History;
use ros2_client::{
    Context, ContextOptions, MessageTypeName, Name, Node, NodeName, NodeOptions, Publisher,
    QosProfile, Subscription,
};
use serde::de::DeserializeSeed;
use smol::Timer;

use commands::{command_sequence, Command};
use layout::{Plain, WholePayload};
use messages::{
    Clock, Float64MultiArray, Header, LaserScan, Odometry, RangeLayout, TfMessage, Time, Twist,
    TwistStamped, Vector3,
};
use options::{CmdVel, Distro, Options, USAGE};
use step::{Sample, StepSet, RANGE_TOPICS};

/// How often the announced types are compared while the reset state is awaited.
const TYPE_CHECK_INTERVAL: Duration = Duration::from_millis(200);

/// How long a difference of types must last before it is reported: discovery announces a
/// participant's readers one by one, so the bridge's Twist reader of `/cmd_vel` may be known a
/// moment before its TwistStamped one.
const TYPE_SETTLE: Duration = Duration::from_secs(10);

/// Why the peer stopped: each kind has its exit status.
enum Failure {
    Layout(String),
    Timeout(String),
    Other(String),
}

impl Failure {
    fn exit_code(&self) -> u8 {
        match self {
            Failure::Layout(_) => 3,
            Failure::Timeout(_) => 4,
            Failure::Other(_) => 1,
        }
    }

    fn message(&self) -> String {
        match self {
            Failure::Layout(text) => format!("layout mismatch: {text}"),
            Failure::Timeout(text) => format!("timeout: {text}"),
            Failure::Other(text) => text.clone(),
        }
    }
}

fn other<E: std::fmt::Display>(context: &str) -> impl FnOnce(E) -> Failure + '_ {
    move |error| Failure::Other(format!("{context}: {error}"))
}

/// One decoded message or the layout error of its topic.
type Received = Result<Sample, Failure>;
type SampleStream<'a> = Pin<Box<dyn Stream<Item = Received> + 'a>>;

/// The state topics' QoS as the bridge offers them: reliable, volatile, keep last `depth`.
fn reliable(depth: usize) -> QosProfile {
    QosProfile::publisher_default().history(History::KeepLast { depth })
}

fn subscribe<M: 'static>(
    node: &mut Node,
    topic: &str,
    package: &str,
    type_name: &str,
    depth: usize,
) -> Result<Subscription<M>, Failure> {
    let name = Name::new("/", topic).map_err(other("topic name"))?;
    let qos = reliable(depth);
    let dds_topic = node
        .create_topic(&name, MessageTypeName::new(package, type_name), &qos)
        .map_err(other("create topic"))?;
    node.create_subscription(&dds_topic, Some(qos))
        .map_err(other("create subscription"))
}

/// A subscription's messages, decoded whole with `seed`, as `Sample`s.
fn samples<'a, M: 'static, S>(
    subscription: &'a Subscription<M>,
    seed: S,
    describe: String,
    wrap: impl Fn(M) -> Sample + 'a,
) -> SampleStream<'a>
where
    S: for<'de> DeserializeSeed<'de, Value = M> + Clone + 'a,
{
    subscription
        .async_stream_seed(WholePayload(seed))
        .map(move |result| match result {
            Ok((message, _info)) => Ok(wrap(message)),
            Err(error) => Err(Failure::Layout(format!("{describe}: {error}"))),
        })
        .boxed_local()
}

/// The `/cmd_vel` writer of the distribution: `Twist` (Humble) or `TwistStamped` (Jazzy).
enum CommandWriter {
    Twist(Publisher<Twist>),
    TwistStamped(Publisher<TwistStamped>),
}

impl CommandWriter {
    fn create(node: &mut Node, kind: CmdVel) -> Result<CommandWriter, Failure> {
        let name = Name::new("/", "cmd_vel").map_err(other("topic name"))?;
        let qos = reliable(10);
        let type_name = MessageTypeName::new("geometry_msgs", kind.type_name());
        let topic = node
            .create_topic(&name, type_name, &qos)
            .map_err(other("create topic"))?;
        Ok(match kind {
            CmdVel::Twist => CommandWriter::Twist(
                node.create_publisher(&topic, Some(qos))
                    .map_err(other("create publisher"))?,
            ),
            CmdVel::TwistStamped => CommandWriter::TwistStamped(
                node.create_publisher(&topic, Some(qos))
                    .map_err(other("create publisher"))?,
            ),
        })
    }

    /// Sends `command`, stamped (Jazzy) with the simulation time of the state it answers.
    fn send(&self, command: Command, now: Time) -> Result<(), Failure> {
        let twist = Twist {
            linear: Vector3 {
                x: command.linear_x,
                y: 0.0,
                z: 0.0,
            },
            angular: Vector3 {
                x: 0.0,
                y: 0.0,
                z: command.angular_z,
            },
        };
        let sent = match self {
            CommandWriter::Twist(writer) => writer.publish(twist).map_err(|e| e.to_string()),
            CommandWriter::TwistStamped(writer) => writer
                .publish(TwistStamped {
                    header: Header {
                        stamp: now,
                        frame_id: "base_link".into(),
                    },
                    twist,
                })
                .map_err(|e| e.to_string()),
        };
        sent.map_err(|error| Failure::Other(format!("publishing /cmd_vel: {error}")))
    }
}

/// Gathers one step's message set from `incoming`, or fails after `timeout`.
async fn gather(
    incoming: &mut (impl Stream<Item = Received> + Unpin),
    timeout: Duration,
    what: &str,
) -> Result<(StepSet, Time), Failure> {
    let deadline = Instant::now() + timeout;
    let mut set = StepSet::default();
    loop {
        if let Some(clock) = set.complete().map_err(Failure::Other)? {
            return Ok((set, clock));
        }
        let next = smol::future::or(async { Some(incoming.next().await) }, async {
            Timer::at(deadline).await;
            None
        })
        .await;
        match next {
            None => {
                return Err(Failure::Timeout(format!(
                    "{what}: no {} within {:.1} s",
                    set.missing().join(", "),
                    timeout.as_secs_f64()
                )))
            }
            Some(None) => return Err(Failure::Other("the subscriptions ended".into())),
            Some(Some(sample)) => set.add(sample?).map_err(Failure::Other)?,
        }
    }
}

/// The topics another participant reads (`/cmd_vel`) or writes (state topics) under a type name
/// other than this peer's (DDS then matches no reader with that writer), one line each.
fn foreign_types(context: &Context, options: &Options) -> Vec<String> {
    let participant = context.domain_participant();
    let ours = |topic: &str| -> Option<String> {
        let name = topic.strip_prefix("rt/")?;
        let (package, type_name) = match name {
            "cmd_vel" => ("geometry_msgs", options.cmd_vel.type_name()),
            "scan" => ("sensor_msgs", "LaserScan"),
            "odom" => ("nav_msgs", "Odometry"),
            "tf" => ("tf2_msgs", "TFMessage"),
            "sensors" | "pose" => ("std_msgs", "Float64MultiArray"),
            "clock" => ("rosgraph_msgs", "Clock"),
            _ if RANGE_TOPICS.contains(&name) => ("sensor_msgs", "Range"),
            _ => return None,
        };
        Some(format!("{package}::msg::dds_::{type_name}_"))
    };
    let remote_readers: Vec<(String, String)> = participant
        .discovered_readers()
        .into_iter()
        .map(|reader| {
            let data = reader.subscription_topic_data;
            (data.topic_name().clone(), data.type_name().clone())
        })
        .collect();
    // A topic read under several types (the bridge reads /cmd_vel as Twist and TwistStamped)
    // matches this peer's writer if one of them is this peer's type.
    let read_as_ours = |topic: &str| {
        remote_readers
            .iter()
            .any(|(name, type_name)| name == topic && ours(name).as_deref() == Some(type_name))
    };
    let remote_writers = participant.discovered_writers().into_iter().map(|writer| {
        let data = writer.publication_topic_data;
        (data.topic_name, data.type_name)
    });
    let mut differences: Vec<String> = remote_readers
        .iter()
        .filter(|(topic, _)| !read_as_ours(topic))
        .cloned()
        .chain(remote_writers)
        .filter_map(|(topic, type_name): (String, String)| {
            let expected = ours(&topic)?;
            (expected != type_name)
                .then(|| format!("{topic} is {type_name} there, {expected} here"))
        })
        .collect();
    differences.sort();
    differences.dedup();
    differences
}

/// Fails with a layout mismatch once the announced types have differed from this peer's for
/// [`TYPE_SETTLE`] without a break; runs until then.
async fn watch_types(context: &Context, options: &Options) -> Failure {
    let mut differing_since: Option<Instant> = None;
    loop {
        Timer::after(TYPE_CHECK_INTERVAL).await;
        let differences = foreign_types(context, options);
        if differences.is_empty() {
            differing_since = None;
            continue;
        }
        let since = *differing_since.get_or_insert_with(Instant::now);
        if since.elapsed() >= TYPE_SETTLE {
            return Failure::Layout(format!(
                "the bridge's types differ from this peer's ({}, /cmd_vel {}): {}",
                options.distro.name(),
                options.cmd_vel.type_name(),
                differences.join("; ")
            ));
        }
    }
}

async fn drive(
    context: &Context,
    node: &mut Node,
    options: &Options,
    out: &mut dyn Write,
) -> Result<(), Failure> {
    let with_variance = options.distro == Distro::Jazzy;
    let distro = options.distro.name();
    let mut ranges = Vec::new();
    for topic in RANGE_TOPICS {
        ranges.push(subscribe(node, topic, "sensor_msgs", "Range", 5)?);
    }
    let scan: Subscription<LaserScan> = subscribe(node, "scan", "sensor_msgs", "LaserScan", 5)?;
    let odom: Subscription<Odometry> = subscribe(node, "odom", "nav_msgs", "Odometry", 5)?;
    let tf: Subscription<TfMessage> = subscribe(node, "tf", "tf2_msgs", "TFMessage", 100)?;
    let sensors: Subscription<Float64MultiArray> =
        subscribe(node, "sensors", "std_msgs", "Float64MultiArray", 5)?;
    let pose: Subscription<Float64MultiArray> =
        subscribe(node, "pose", "std_msgs", "Float64MultiArray", 5)?;
    let clock: Subscription<Clock> = subscribe(node, "clock", "rosgraph_msgs", "Clock", 10)?;

    let mut streams: Vec<SampleStream> = Vec::new();
    for (index, subscription) in ranges.iter().enumerate() {
        let describe = format!(
            "/{} (sensor_msgs/msg/Range, {distro} layout)",
            RANGE_TOPICS[index]
        );
        streams.push(samples(
            subscription,
            RangeLayout { with_variance },
            describe,
            move |r| Sample::Range(index, r),
        ));
    }
    streams.push(samples(
        &scan,
        Plain::new(),
        "/scan (sensor_msgs/msg/LaserScan)".into(),
        Sample::Scan,
    ));
    streams.push(samples(
        &odom,
        Plain::new(),
        "/odom (nav_msgs/msg/Odometry)".into(),
        Sample::Odom,
    ));
    streams.push(samples(
        &tf,
        Plain::new(),
        "/tf (tf2_msgs/msg/TFMessage)".into(),
        Sample::Tf,
    ));
    streams.push(samples(
        &sensors,
        Plain::new(),
        "/sensors (std_msgs/msg/Float64MultiArray)".into(),
        Sample::Sensors,
    ));
    streams.push(samples(
        &pose,
        Plain::new(),
        "/pose (std_msgs/msg/Float64MultiArray)".into(),
        Sample::Pose,
    ));
    streams.push(samples(
        &clock,
        Plain::new(),
        "/clock (rosgraph_msgs/msg/Clock)".into(),
        |c: Clock| Sample::Clock(c.clock),
    ));
    let mut incoming = stream::select_all(streams);

    // The command writer last: the bridge publishes its reset state once it has matched it.
    let writer = CommandWriter::create(node, options.cmd_vel)?;
    // Silence is what DDS makes of a type the other side does not share: while the reset state
    // is awaited, the types the other participants announce are compared with this peer's.
    let reset = gather(&mut incoming, options.start_timeout, "the reset state");
    let (reset, mut now) =
        smol::future::or(reset, async { Err(watch_types(context, options).await) }).await?;
    if now != (Time { sec: 0, nanosec: 1 }) {
        return Err(Failure::Other(format!(
            "the reset state is stamped {now}, not 0.000000001"
        )));
    }
    let mut write_line =
        |set: &StepSet, step: usize, command: Option<Command>| -> Result<(), Failure> {
            writeln!(out, "{}", set.to_json(step, command)).map_err(other("writing the output"))
        };
    write_line(&reset, 0, None)?;
    let stepping = Instant::now();
    for (index, command) in command_sequence(options.seed, options.steps)
        .into_iter()
        .enumerate()
    {
        let step = index + 1;
        writer.send(command, now)?;
        let (set, clock) =
            gather(&mut incoming, options.step_timeout, &format!("step {step}")).await?;
        if clock <= now {
            return Err(Failure::Other(format!(
                "step {step}: /clock went from {now} to {clock}"
            )));
        }
        now = clock;
        write_line(&set, step, Some(command))?;
    }
    let seconds = stepping.elapsed().as_secs_f64();
    eprintln!(
        "ros2-peer: {} steps ({}) in {seconds:.2} s after the reset state: {:.0} steps/s",
        options.steps,
        options.distro.name(),
        options.steps as f64 / seconds
    );
    Ok(())
}

fn run(options: &Options) -> Result<(), Failure> {
    let mut out: Box<dyn Write> = match &options.out {
        Some(path) => Box::new(BufWriter::new(
            File::create(path).map_err(other(&format!("creating {}", path.display())))?,
        )),
        None => Box::new(BufWriter::new(io::stdout().lock())),
    };
    let context = Context::with_options(ContextOptions::new().domain_id(options.domain_id))
        .map_err(other("creating the DDS participant"))?;
    let mut node = context
        .new_node(
            NodeName::new("/", "mazesim_ros2_peer").map_err(other("node name"))?,
            NodeOptions::new()
                .enable_rosout(false)
                .start_parameter_services(false),
        )
        .map_err(other("creating the node"))?;
    let executor = smol::LocalExecutor::new();
    executor
        .spawn(node.spinner().map_err(other("node spinner"))?.spin())
        .detach();
    smol::block_on(executor.run(drive(&context, &mut node, options, &mut out)))?;
    out.flush().map_err(other("writing the output"))?;
    Ok(())
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let domain = std::env::var("ROS_DOMAIN_ID").ok();
    let options = match Options::parse(&args, domain.as_deref()) {
        Ok(options) => options,
        Err(message) if message.is_empty() => {
            // A closed pipe (`ros2-peer --help | head`) is no failure.
            let _ = writeln!(io::stdout(), "{USAGE}");
            return ExitCode::SUCCESS;
        }
        Err(message) => {
            eprintln!("ros2-peer: {message}\n{USAGE}");
            return ExitCode::from(2);
        }
    };
    match run(&options) {
        Ok(()) => ExitCode::SUCCESS,
        Err(failure) => {
            eprintln!("ros2-peer: {}", failure.message());
            ExitCode::from(failure.exit_code())
        }
    }
}
