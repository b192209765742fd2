//! The peer's command line.

use std::path::PathBuf;
use std::time::Duration;

pub const USAGE: &str = "\
usage: ros2-peer [--distro humble|jazzy] [--cmd-vel twist|twist-stamped] [--steps N] [--seed N] [--out FILE]
                 [--step-timeout SECONDS] [--start-timeout SECONDS]

Drives mazesim's ROS 2 bridge in lockstep over ROS 2 (ros2-client over RustDDS): reads the
reset state, then answers each step's state with one /cmd_vel from a seeded sequence, for N
steps, and writes one JSON line per step (step 0 is the reset state) with every decoded field.
--distro sets the Range layout and, unless --cmd-vel says otherwise, the /cmd_vel type (Humble:
Twist, Jazzy: TwistStamped). The DDS domain is ROS_DOMAIN_ID (default 0).
Exit status: 0 done, 2 bad usage, 3 a message whose layout is not the distribution's,
4 a step (or the reset state) that did not arrive in time, 1 any other failure.";

/// The ROS 2 distribution whose message layouts the peer expects.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Distro {
    Humble,
    Jazzy,
}

impl Distro {
    pub fn name(self) -> &'static str {
        match self {
            Distro::Humble => "humble",
            Distro::Jazzy => "jazzy",
        }
    }
}

/// The `/cmd_vel` message type the peer writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CmdVel {
    Twist,
    TwistStamped,
}

impl CmdVel {
    /// The message's name in `geometry_msgs`.
    pub fn type_name(self) -> &'static str {
        match self {
            CmdVel::Twist => "Twist",
            CmdVel::TwistStamped => "TwistStamped",
        }
    }
}

#[derive(Clone, Debug)]
pub struct Options {
    pub distro: Distro,
    pub cmd_vel: CmdVel,
    pub steps: usize,
    pub seed: u64,
    pub out: Option<PathBuf>,
    pub step_timeout: Duration,
    pub start_timeout: Duration,
    pub domain_id: u16,
}

fn value<'a>(args: &'a [String], index: usize, flag: &str) -> Result<&'a str, String> {
    args.get(index + 1)
        .map(String::as_str)
        .ok_or_else(|| format!("{flag} expects a value"))
}

fn number<T: std::str::FromStr>(text: &str, flag: &str, expected: &str) -> Result<T, String> {
    text.parse()
        .map_err(|_| format!("{flag} expects {expected}, found {text:?}"))
}

fn seconds(text: &str, flag: &str) -> Result<Duration, String> {
    let value: f64 = number(text, flag, "a number of seconds")?;
    Duration::try_from_secs_f64(value)
        .ok()
        .filter(|d| !d.is_zero())
        .ok_or_else(|| format!("{flag} expects a positive number of seconds, found {text:?}"))
}

impl Options {
    /// Reads the arguments (without the program name) and `ROS_DOMAIN_ID`.
    pub fn parse(args: &[String], domain: Option<&str>) -> Result<Options, String> {
        let mut options = Options {
            distro: Distro::Humble,
            cmd_vel: CmdVel::Twist,
            steps: 2000,
            seed: 0,
            out: None,
            step_timeout: Duration::from_secs(10),
            start_timeout: Duration::from_secs(30),
            domain_id: 0,
        };
        if let Some(text) = domain.filter(|text| !text.is_empty()) {
            options.domain_id = number(text, "ROS_DOMAIN_ID", "a domain id from 0 to 232")?;
        }
        let mut cmd_vel = None;
        let mut index = 0;
        while index < args.len() {
            let flag = args[index].as_str();
            match flag {
                "--distro" => {
                    options.distro = match value(args, index, flag)? {
                        "humble" => Distro::Humble,
                        "jazzy" => Distro::Jazzy,
                        other => {
                            return Err(format!(
                                "--distro expects humble or jazzy, found {other:?}"
                            ))
                        }
                    }
                }
                "--cmd-vel" => {
                    cmd_vel = Some(match value(args, index, flag)? {
                        "twist" => CmdVel::Twist,
                        "twist-stamped" => CmdVel::TwistStamped,
                        other => {
                            return Err(format!(
                                "--cmd-vel expects twist or twist-stamped, found {other:?}"
                            ))
                        }
                    })
                }
                "--steps" => {
                    options.steps = number(value(args, index, flag)?, flag, "a count of steps")?
                }
                "--seed" => {
                    options.seed =
                        number(value(args, index, flag)?, flag, "a non-negative integer")?
                }
                "--out" => options.out = Some(PathBuf::from(value(args, index, flag)?)),
                "--step-timeout" => {
                    options.step_timeout = seconds(value(args, index, flag)?, flag)?
                }
                "--start-timeout" => {
                    options.start_timeout = seconds(value(args, index, flag)?, flag)?
                }
                "-h" | "--help" => return Err(String::new()),
                other => return Err(format!("unknown argument {other:?}")),
            }
            index += 2;
        }
        options.cmd_vel = cmd_vel.unwrap_or(match options.distro {
            Distro::Humble => CmdVel::Twist,
            Distro::Jazzy => CmdVel::TwistStamped,
        });
        Ok(options)
    }
}
