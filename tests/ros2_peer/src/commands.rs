//! The seeded sequence of `/cmd_vel` commands the peer sends: runs of a few steps of one
//! (linear, angular) velocity, drawn from splitmix64 so that a seed names the same sequence on
//! every machine. Each command is printed with the step it caused, so a comparison needs the
//! peer's output only, not this generator.

/// Forward speed range in m/s: a little under the e-puck's 0.129 m/s, backwards too.
const LINEAR_MAX: f64 = 0.12;
/// Turn rate range in rad/s.
const ANGULAR_MAX: f64 = 3.0;
/// The longest run of one command, in steps.
const RUN_MAX: u64 = 25;

/// One `/cmd_vel`: `linear.x` in m/s and `angular.z` in rad/s.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Command {
    pub linear_x: f64,
    pub angular_z: f64,
}

/// splitmix64 (Steele, Lea and Flood, 2014): small, and the same everywhere.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in [-1, 1).
    fn symmetric(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
}

/// `steps` commands from `seed`.
pub fn command_sequence(seed: u64, steps: usize) -> Vec<Command> {
    let mut random = SplitMix64(seed);
    let mut commands = Vec::with_capacity(steps);
    while commands.len() < steps {
        let run = 1 + random.next() % RUN_MAX;
        let command = Command {
            linear_x: LINEAR_MAX * random.symmetric(),
            angular_z: ANGULAR_MAX * random.symmetric(),
        };
        for _ in 0..run {
            commands.push(command);
        }
    }
    commands.truncate(steps);
    commands
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_seed_names_one_sequence_within_the_ranges() {
        let commands = command_sequence(7, 500);
        assert_eq!(commands.len(), 500);
        assert_eq!(commands, command_sequence(7, 500));
        assert_ne!(commands, command_sequence(8, 500));
        assert!(commands
            .iter()
            .all(|c| c.linear_x.abs() <= LINEAR_MAX && c.angular_z.abs() <= ANGULAR_MAX));
        let changes = commands
            .windows(2)
            .filter(|pair| pair[0] != pair[1])
            .count();
        assert!(
            changes >= 500 / RUN_MAX as usize,
            "{changes} changes of command"
        );
    }
}
