//! Several robots in one world, stepped together: each with its own profile, start, noise stream
//! and wheel command; they collide with each other and their infra-red rays see each other
//! (`crate::simulator::Others`).
//!
//! A swarm is a list of simulators of one world, one per robot the world places
//! (`World::robots`), stepped in lockstep: every physics step, each robot moves held back by the
//! others at their poses before the step, then each settles its contacts and, at the end of the
//! control step, reads its sensors with every robot where it ended. A world of one robot is
//! stepped by that robot's own `Simulator::step`, at no extra cost.
//!
//! In a world with movable bodies the robots share one rapier scene
//! (`crate::simulator::share_scene`): they push the bodies, the bodies push them, and their rays
//! meet the bodies where they are.
//!
//! Noise streams: robot 0 draws from the seed itself (so a world of one robot runs as a plain
//! simulator does); robot `i > 0` from [`robot_seed`], a stream derived from the seed and the
//! robot's name.

mod batch;
mod snapshot;

use std::cell::RefCell;
use std::sync::Arc;

use crate::error::{Error, Result};
use crate::fingerprint::fnv1a;
use crate::limits;
use crate::robot::RobotProfile;
use crate::simulator::{
    move_in_scene, place_in_scene, pushed_out, share_scene, Drive, Neighbour, Others, Rig,
    SceneStep, SimConfig, Simulator, START_OVERLAP,
};
use crate::world::{Motion, MovableBody, RobotPlacement, World};

/// The seed of the noise stream of robot `index`, named `name`, of a world run with `seed`: the
/// seed itself for robot 0, and for the others the first SplitMix64 output of the seed mixed with
/// a hash of `robot/NAME`, so that each robot's stream depends on its name, not on its place in
/// the list.
pub fn robot_seed(seed: u64, index: usize, name: &str) -> u64 {
    if index == 0 {
        seed
    } else {
        crate::rng::next_seed(seed ^ fnv1a(format!("robot/{name}").as_bytes()))
    }
}

thread_local! {
    /// Per-step workspace of the lockstep (robots' discs, drives, poses before the step), one per
    /// thread, so that a swarm holds none of it.
    static WORKSPACE: RefCell<Workspace> = RefCell::new(Workspace::default());
}

#[derive(Default)]
struct Workspace {
    discs: Vec<Neighbour>,
    drives: Vec<Drive>,
    before: Vec<[f32; 3]>,
    scene: SceneStep,
}

/// The robots' discs at their current poses, each reaching as far as the shapes it carries
/// (`placements`: the world's, empty when no robot carries any).
fn discs_of(robots: &[Simulator], placements: &[RobotPlacement], discs: &mut Vec<Neighbour>) {
    discs.clear();
    discs.extend(robots.iter().enumerate().map(|(i, r)| {
        let [x, y, yaw] = r.pose();
        let radius = r.robot().body_radius as f32;
        let carried = placements.get(i).map_or(&[][..], |p| &p.carried[..]);
        Neighbour {
            center: [x, y],
            radius,
            yaw,
            extent: carried.iter().map(|s| s.reach()).fold(radius, f32::max),
        }
    }));
}

/// The world's robot placements when one of them carries a shape, else none (the robots are
/// their bodies alone).
fn carrying(world: &World) -> &[RobotPlacement] {
    let placements = world.robots();
    if placements.iter().any(|p| !p.carried.is_empty()) {
        placements
    } else {
        &[]
    }
}

/// The robots of `all` as robot `me` sees them: none when every other is beyond `reach` of it
/// (then it steps exactly as a robot alone does), else all of them.
#[inline]
fn near<'a>(
    all: &'a [Neighbour],
    me: usize,
    reach: f32,
    placements: &'a [RobotPlacement],
) -> Others<'a> {
    let others = Others::new(all, me, placements);
    if others.any_within(reach) {
        others
    } else {
        Others::NONE
    }
}

/// Refuses robot `index`'s wheel command unless both speeds are finite: the one check of a
/// command, whether it is stepped at once or set to be stepped later (`Swarm::set_command`),
/// so a NaN is refused where it is given, not at a later step.
fn check_command(index: usize, left: f64, right: f64) -> Result<()> {
    if left.is_finite() && right.is_finite() {
        return Ok(());
    }
    Err(Error::InvalidAction(format!(
        "expected finite wheel speeds in rad/s, found ({left}, {right}) for robot {index}"
    )))
}

/// Steps the robots of one world one control step together, robot `i` with wheel speeds
/// `command(i)` (rad/s, left and right). Every command is checked before any robot moves.
pub fn step_robots(robots: &mut [Simulator], command: impl Fn(usize) -> [f64; 2]) -> Result<()> {
    if let [only] = robots {
        let [left, right] = command(0);
        return only.step(left, right);
    }
    for i in 0..robots.len() {
        let [left, right] = command(i);
        check_command(i, left, right)?;
    }
    let world = robots[0].world().clone();
    let carried = carrying(&world);
    WORKSPACE.with_borrow_mut(|w| {
        w.drives.clear();
        for (i, robot) in robots.iter_mut().enumerate() {
            let [left, right] = command(i);
            w.drives.push(robot.command(left, right)?);
        }
        let steps = robots[0].physics_steps();
        let shared = robots[0].in_shared_scene();
        for k in 1..=steps {
            discs_of(robots, carried, &mut w.discs);
            if shared {
                let discs = &w.discs;
                let others = |i: usize, r: &Simulator| near(discs, i, r.reach(), carried);
                move_in_scene(robots, &w.drives, others, &mut w.before, &mut w.scene);
            } else {
                w.before.clear();
                for (i, (robot, drive)) in robots.iter_mut().zip(&w.drives).enumerate() {
                    let others = near(&w.discs, i, robot.reach(), carried);
                    w.before.push(robot.physics_move(drive, others));
                }
            }
            discs_of(robots, carried, &mut w.discs);
            // Robot 0 holds a shared scene: the others' rays meet its movable bodies.
            let (first, rest) = robots.split_at_mut(1);
            let robot = &mut first[0];
            let others = near(&w.discs, 0, robot.reach(), carried);
            robot.physics_settle(&mut w.drives[0], k, w.before[0], others, None);
            let scene = shared.then_some(&first[0]);
            let moved = rest.iter_mut().zip(&mut w.drives[1..]).zip(&w.before[1..]);
            for (j, ((robot, drive), &before)) in moved.enumerate() {
                let others = near(&w.discs, j + 1, robot.reach(), carried);
                robot.physics_settle(drive, k, before, others, scene);
            }
        }
        for (robot, drive) in robots.iter_mut().zip(&w.drives) {
            robot.finish_step(drive);
        }
        Ok(())
    })
}

/// Reads every robot's sensors again with the others where they stand (after a reset or a move).
pub fn sense_robots(robots: &mut [Simulator]) {
    if robots.len() < 2 {
        return;
    }
    let world = robots[0].world().clone();
    let carried = carrying(&world);
    WORKSPACE.with_borrow_mut(|w| {
        discs_of(robots, carried, &mut w.discs);
        let all = &w.discs;
        let (first, rest) = robots.split_at_mut(1);
        first[0].sense_robots(Others::new(all, 0, carried), None);
        let scene = first[0].in_shared_scene().then_some(&first[0]);
        for (j, robot) in rest.iter_mut().enumerate() {
            robot.sense_robots(Others::new(all, j + 1, carried), scene);
        }
    });
}

/// Resets the robots of one world, each with its stream of `seed` when given (see
/// [`robot_seed`]).
pub fn reset_robots(robots: &mut [Simulator], names: &[String], seed: Option<u64>) {
    for (i, robot) in robots.iter_mut().enumerate() {
        robot.reset(seed.map(|s| robot_seed(s, i, &names[i])));
    }
    if robots[0].in_shared_scene() {
        // Every robot at its start and every movable body at its own.
        share_scene(robots);
    }
    sense_robots(robots);
}

/// The simulators of the robots of `world`, robot `i` with `rigs[i]` and its stream of `config`'s
/// seed; in a world with movable bodies, all in one rapier scene. Refused: more rigs than robots
/// or fewer, robots whose bodies overlap at their starts.
pub fn make_robots(
    world: &Arc<World>,
    rigs: &[Arc<Rig>],
    config: SimConfig,
) -> Result<Vec<Simulator>> {
    let placements = world.robots();
    if rigs.len() != placements.len() {
        return Err(Error::InvalidArgument(format!(
            "expected one robot profile per robot of world {:?} ({}), found {}",
            world.name(),
            placements.len(),
            rigs.len()
        )));
    }
    if placements.len() == 1 {
        return Ok(vec![Simulator::with_rig(
            world.clone(),
            rigs[0].clone(),
            config,
        )?]);
    }
    let mut robots = Vec::with_capacity(placements.len());
    for (i, (placement, rig)) in placements.iter().zip(rigs).enumerate() {
        let seed = robot_seed(config.seed, i, &placement.name);
        // Made at its own start: a larger robot may not fit at the first robot's.
        let mut sim = Simulator::with_rig_at(
            world.clone(),
            rig.clone(),
            SimConfig { seed, ..config },
            placement.start,
        )
        .map_err(|e| name_robot(e, &placement.name))?;
        let [x, y, yaw] = placement.start;
        sim.set_start(x, y, yaw)
            .map_err(|e| name_robot(e, &placement.name))?;
        sim.reset(None);
        robots.push(sim);
    }
    let starts: Vec<[f64; 3]> = placements.iter().map(|p| p.start).collect();
    for i in 0..robots.len() {
        check_apart(&robots, i, starts[i], |j| starts[j], "start")?;
    }
    if !world.bodies().is_empty() {
        share_scene(&mut robots);
    }
    sense_robots(&mut robots);
    Ok(robots)
}

/// For each of `bodies`, the index of the one of `running` it is, if any: the bodies both
/// describe alike, matched in order (a body taken out leaves the others matched).
fn kept_bodies(running: &[MovableBody], bodies: &[MovableBody]) -> Vec<Option<usize>> {
    let mut next = 0;
    bodies
        .iter()
        .map(|body| {
            let found = running[next..].iter().position(|r| r == body)?;
            next += found + 1;
            Some(next - 1)
        })
        .collect()
}

/// `error` with the robot named in its message.
fn name_robot(error: Error, name: &str) -> Error {
    match error {
        Error::InvalidArgument(m) => Error::InvalidArgument(format!("robot {name:?}: {m}")),
        other => other,
    }
}

/// Refuses pose `at` of robot `i` when its body would overlap another robot's at `pose_of(j)`
/// by more than `START_OVERLAP` (`what` names the poses).
pub(crate) fn check_apart(
    robots: &[Simulator],
    i: usize,
    at: [f64; 3],
    pose_of: impl Fn(usize) -> [f64; 3],
    what: &str,
) -> Result<()> {
    let ri = robots[i].robot().body_radius;
    for (j, other) in robots.iter().enumerate() {
        if j == i {
            continue;
        }
        let p = pose_of(j);
        let d = ((at[0] - p[0]).powi(2) + (at[1] - p[1]).powi(2)).sqrt();
        let overlap = ri + other.robot().body_radius - d;
        if overlap > START_OVERLAP {
            return Err(Error::InvalidArgument(format!(
                "expected robots whose bodies do not overlap, found robot {i} at {what} ({}, {}) \
                 overlapping robot {j} at ({}, {}) by {overlap:.4} m",
                at[0], at[1], p[0], p[1]
            )));
        }
    }
    Ok(())
}

/// Several robots in one world (see the module notes).
pub struct Swarm {
    robots: Vec<Simulator>,
    names: Vec<String>,
    /// Each robot's wheel command, kept from step to step (as a Webots motor keeps its velocity).
    commands: Vec<[f64; 2]>,
    /// The profile of the robots whose placement names none.
    profile: Arc<RobotProfile>,
    /// The profiles given for some robots instead of their placements' (`with_profiles`), one
    /// per robot; empty when none was.
    overrides: Vec<Option<Arc<RobotProfile>>>,
    /// The world as the swarm was made of it (its walls where its file has them), which
    /// `reset_scene` puts back after `move_solid`.
    made_of: Arc<World>,
}

impl Swarm {
    /// The robots of `world`: each of the profile its placement names, else `robot`.
    pub fn new(world: Arc<World>, robot: Arc<RobotProfile>, config: SimConfig) -> Result<Swarm> {
        Self::with_profiles(world, robot, &[], config)
    }

    /// The robots of `world`: robot `i` of `profiles[i]` when given, else of the profile its
    /// placement names, else `robot` (a robot node of an imported world whose own sensors
    /// differ from its built-in profile's). `profiles` is empty or holds one entry per robot.
    pub fn with_profiles(
        world: Arc<World>,
        robot: Arc<RobotProfile>,
        profiles: &[Option<Arc<RobotProfile>>],
        config: SimConfig,
    ) -> Result<Swarm> {
        let placements = world.robots();
        if !profiles.is_empty() && profiles.len() != placements.len() {
            return Err(Error::InvalidArgument(format!(
                "expected no robot profiles or one per robot of world {:?} ({}), found {}",
                world.name(),
                placements.len(),
                profiles.len()
            )));
        }
        let mut rigs: Vec<Arc<Rig>> = Vec::new();
        // The rigs of the robots without a given profile, which a placement naming a profile
        // shares by name (a given profile may bear a built-in's name and differ from it).
        let mut shared: Vec<Arc<Rig>> = Vec::new();
        let default = Rig::new(robot);
        for (i, placement) in placements.iter().enumerate() {
            if let Some(profile) = profiles.get(i).and_then(Option::as_ref) {
                rigs.push(Rig::new(profile.clone()));
                continue;
            }
            let rig = match &placement.profile {
                None => default.clone(),
                Some(name) => match shared.iter().find(|r| &r.robot().name == name) {
                    Some(r) => r.clone(),
                    None => Rig::new(Arc::new(RobotProfile::builtin(name)?)),
                },
            };
            shared.push(rig.clone());
            rigs.push(rig);
        }
        let mut swarm = Self::with_rigs(world, &rigs, config)?;
        swarm.profile = default.robot().clone();
        if profiles.iter().any(Option::is_some) {
            swarm.overrides = profiles.to_vec();
        }
        Ok(swarm)
    }

    /// The robots of `world`, robot `i` with `rigs[i]`.
    pub fn with_rigs(world: Arc<World>, rigs: &[Arc<Rig>], config: SimConfig) -> Result<Swarm> {
        let robots = make_robots(&world, rigs, config)?;
        let names = world.robots().iter().map(|p| p.name.clone()).collect();
        Ok(Swarm {
            commands: vec![[0.0; 2]; robots.len()],
            profile: rigs[0].robot().clone(),
            overrides: Vec::new(),
            robots,
            names,
            made_of: world,
        })
    }

    /// Number of robots, at least 1.
    pub fn len(&self) -> usize {
        self.robots.len()
    }

    /// Never true: a swarm has a robot at least.
    pub fn is_empty(&self) -> bool {
        self.robots.is_empty()
    }

    /// The profile of the robots whose placement names none (`Swarm::new`'s `robot`).
    pub fn default_profile(&self) -> &Arc<RobotProfile> {
        &self.profile
    }

    /// The profiles `with_profiles` was given, one per robot (empty when none was).
    pub fn profile_overrides(&self) -> &[Option<Arc<RobotProfile>>] {
        &self.overrides
    }

    /// The robots' names, in world order.
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// The robots' simulators, in world order.
    pub fn robots(&self) -> &[Simulator] {
        &self.robots
    }

    /// Robot `index`, or an error naming the valid indices.
    pub fn robot(&self, index: usize) -> Result<&Simulator> {
        let n = self.robots.len();
        self.robots.get(index).ok_or_else(|| bad_index(index, n))
    }

    /// Robot `index` to change (its goal, say); moving it goes through `set_pose`.
    pub fn robot_mut(&mut self, index: usize) -> Result<&mut Simulator> {
        let n = self.robots.len();
        self.robots
            .get_mut(index)
            .ok_or_else(|| bad_index(index, n))
    }

    /// Sets robot `index`'s wheel command for the next steps (rad/s; checked when stepped).
    pub fn set_command(&mut self, index: usize, left: f64, right: f64) -> Result<()> {
        self.robot(index)?;
        check_command(index, left, right)?;
        self.commands[index] = [left, right];
        Ok(())
    }

    /// Robot `index`'s wheel command.
    pub fn command(&self, index: usize) -> Result<[f64; 2]> {
        self.robot(index)?;
        Ok(self.commands[index])
    }

    /// One control step with every robot at its wheel command.
    pub fn step_commanded(&mut self) -> Result<()> {
        let commands = &self.commands;
        step_robots(&mut self.robots, |i| commands[i])
    }

    /// One control step, robot `i` at wheel speeds `commands[i]` (kept as its command).
    pub fn step(&mut self, commands: &[[f64; 2]]) -> Result<()> {
        if commands.len() != self.robots.len() {
            return Err(Error::InvalidArgument(format!(
                "expected wheel speeds for each of the {} robots, found {}",
                self.robots.len(),
                commands.len()
            )));
        }
        step_robots(&mut self.robots, |i| commands[i])?;
        self.commands.copy_from_slice(commands);
        Ok(())
    }

    /// Back to the starts, time and counters zeroed, the walls `move_solid` moved where the
    /// world has them; new streams of `seed` when given.
    pub fn reset(&mut self, seed: Option<u64>) {
        for robot in &mut self.robots {
            robot.forget_moves(&self.made_of);
        }
        reset_robots(&mut self.robots, &self.names, seed);
        self.commands.fill([0.0; 2]);
    }

    /// The seed of the last reset (robot 0's stream).
    pub fn seed(&self) -> u64 {
        self.robots[0].config().seed
    }

    /// Sets robot `index`'s start for later resets; it must be clear of the walls and of the
    /// other robots' starts.
    pub fn set_start(&mut self, index: usize, x: f64, y: f64, yaw: f64) -> Result<()> {
        self.robot(index)?;
        let starts: Vec<[f64; 3]> = self.robots.iter().map(Simulator::start_pose).collect();
        check_apart(&self.robots, index, [x, y, yaw], |j| starts[j], "start")?;
        self.robots[index].set_start(x, y, yaw)
    }

    /// Moves robot `index` to a pose at rest, clear of the walls and of the other robots; every
    /// robot's sensors are read again.
    pub fn set_pose(&mut self, index: usize, x: f64, y: f64, yaw: f64) -> Result<()> {
        self.robot(index)?;
        let poses: Vec<[f64; 3]> = (self.robots.iter())
            .map(|r| r.pose().map(f64::from))
            .collect();
        check_apart(&self.robots, index, [x, y, yaw], |j| poses[j], "pose")?;
        self.place(index, x, y, yaw)
    }

    /// Moves robot `index` to a pose at rest as `set_pose` (or, `overlap_robots`, `place`) does
    /// or, when the body would lie in a wall there, to the nearest pose that call accepts
    /// (`pushed_out`), as Webots' physics pushes out a body a supervisor put into a wall;
    /// returns the x and y it stands at. A pose with none accepted near enough stays refused.
    pub fn set_pose_pushed_out(
        &mut self,
        index: usize,
        [x, y]: [f64; 2],
        yaw: f64,
        overlap_robots: bool,
    ) -> Result<[f64; 2]> {
        let move_to = |swarm: &mut Swarm, [x, y]: [f64; 2]| {
            if overlap_robots {
                swarm.place(index, x, y, yaw)
            } else {
                swarm.set_pose(index, x, y, yaw)
            }
        };
        let Err(refusal) = move_to(self, [x, y]) else {
            return Ok([x, y]);
        };
        let in_wall = limits::check_pose("pose", x, y, yaw).is_ok()
            && self
                .robot(index)
                .is_ok_and(|r| r.check_start(x, y, yaw).is_err());
        let clear = in_wall.then(|| pushed_out([x, y], |p| move_to(self, p).is_ok()));
        clear.flatten().ok_or(refusal)
    }

    /// Moves robot `index` to a pose at rest clear of the walls, where it may overlap other
    /// robots (as a Webots supervisor may put one onto another): the contacts of the next
    /// physics steps push the overlapping robots apart, each by half the overlap. Every robot's
    /// sensors are read again.
    pub fn place(&mut self, index: usize, x: f64, y: f64, yaw: f64) -> Result<()> {
        self.robot(index)?;
        self.robots[index].set_pose(x, y, yaw)?;
        if self.robots[0].in_shared_scene() {
            place_in_scene(&mut self.robots, index);
        }
        sense_robots(&mut self.robots);
        Ok(())
    }

    /// Moves an object of the world by `motion`, as a supervisor moves a node: the `[[walls]]`
    /// entries `walls` (see `World::with_walls_moved`), the movable bodies `bodies` (world
    /// order; each put at rest where the motion takes its pose now) and the `[[paint]]` entries
    /// `paint` (its floor marks, see `World::with_paint_moved`). The robots meet the walls and
    /// bodies there from the next step on, and their ground sensors read the paint there.
    /// Nothing moves when any index or pose is refused.
    pub fn move_solid(
        &mut self,
        walls: &[usize],
        bodies: &[usize],
        paint: &[usize],
        motion: Motion,
    ) -> Result<()> {
        motion.check()?;
        let poses = self.robots[0].body_poses();
        let mut placed = Vec::with_capacity(bodies.len());
        for &i in bodies {
            let Some(pose) = poses.get(i) else {
                return Err(Error::InvalidArgument(format!(
                    "expected movable body indices below the world's {} bodies, found {i}",
                    poses.len()
                )));
            };
            let [x, y, yaw] = motion.apply(pose.map(f64::from));
            limits::check_pose("movable body", x, y, yaw)?;
            placed.push((i, [x as f32, y as f32, yaw as f32]));
        }
        if !walls.is_empty() || !paint.is_empty() {
            let mut world = self.robots[0].world().clone();
            if !walls.is_empty() {
                world = Arc::new(world.with_walls_moved(walls, motion)?);
            }
            if !paint.is_empty() {
                world = Arc::new(world.with_paint_moved(paint, motion)?);
            }
            for robot in &mut self.robots {
                robot.take_world(world.clone());
            }
        }
        for (i, pose) in placed {
            self.robots[0].place_body(i, pose);
        }
        Ok(())
    }

    /// Takes `world` as the world the robots run in from the next step on, as a supervisor
    /// imports nodes into the running world or removes some: its walls are met and sensed
    /// there, while every robot keeps its pose, velocities, wheel encoders, noise stream, clock
    /// and counters. A movable body of the running world that `world` holds too (the same one,
    /// in the same order among those kept) goes on where it is; the others are taken out, and
    /// `world`'s new ones start at rest where it puts them (the robots of a world that had none
    /// are put into one rapier scene then, as a world made with movable bodies has them).
    /// `world` becomes the one a reset puts back. Refused, naming what was expected and found,
    /// when `world` holds another number of robots.
    pub fn change_world(&mut self, world: Arc<World>) -> Result<()> {
        let running = self.robots[0].world().clone();
        if world.robots().len() != running.robots().len() {
            return Err(Error::InvalidArgument(format!(
                "expected a world of the running world's {} robots, found {}",
                running.robots().len(),
                world.robots().len()
            )));
        }
        let kept = kept_bodies(running.bodies(), world.bodies());
        let shared_now = self.len() > 1 && running.bodies().is_empty();
        for robot in &mut self.robots {
            robot.take_changed_world(world.clone(), &kept);
        }
        if shared_now && !world.bodies().is_empty() {
            share_scene(&mut self.robots);
        }
        self.made_of = world;
        Ok(())
    }

    /// `change_world` with a world whose robots may differ from the running ones, as a Webots
    /// supervisor imports robots or removes some: robot `i` of `world` is the running robot
    /// `kept[i]` where given, which goes on with its state (pose, encoders, noise stream,
    /// counters, wheel command); the others are new robots, at their world poses, at rest, with
    /// fresh counters, no wheel command, the running robots' clock and a noise stream derived
    /// from the seed and their name (`robot_seed` as for a robot after the first); the running
    /// robots `kept` does not name are taken out. A new robot is of `profiles[i]` when given
    /// (a robot node of an imported world whose own sensors differ from its built-in profile's,
    /// as `with_profiles` takes them), else of the profile its placement names, else the
    /// swarm's default; a kept robot keeps its own. The movable bodies go on as `change_world`
    /// has them. With `kept` naming every running robot in order, this is `change_world`.
    /// Refused, naming what was expected and found, nothing changed: `kept` of another length
    /// than `world`'s robots, naming a running robot twice or one past the running robots, or
    /// `profiles` neither empty nor of that length, or giving a kept robot a profile.
    pub fn change_world_with_robots(
        &mut self,
        world: Arc<World>,
        kept: &[Option<usize>],
        profiles: &[Option<Arc<RobotProfile>>],
    ) -> Result<()> {
        let placements = world.robots();
        if kept.len() != placements.len() {
            return Err(Error::InvalidArgument(format!(
                "expected one entry per robot of the new world ({}), found {}",
                placements.len(),
                kept.len()
            )));
        }
        if !profiles.is_empty() && profiles.len() != placements.len() {
            return Err(Error::InvalidArgument(format!(
                "expected no robot profiles or one per robot of the new world ({}), found {}",
                placements.len(),
                profiles.len()
            )));
        }
        let given = |i: usize| profiles.get(i).and_then(Option::as_ref);
        if let Some(i) = (0..kept.len()).find(|&i| kept[i].is_some() && given(i).is_some()) {
            return Err(Error::InvalidArgument(format!(
                "expected a profile for new robots only, found one for robot {i}, the running \
                 robot {}",
                kept[i].unwrap_or_default()
            )));
        }
        let mut taken = vec![false; self.len()];
        for &j in kept.iter().flatten() {
            if j >= self.len() || std::mem::replace(&mut taken[j], true) {
                return Err(Error::InvalidArgument(format!(
                    "expected each running robot (0 to {}) kept at most once, found robot {j} {}",
                    self.len() - 1,
                    if j >= self.len() {
                        "past them"
                    } else {
                        "twice"
                    }
                )));
            }
        }
        let same: Vec<Option<usize>> = (0..self.len()).map(Some).collect();
        if kept == same.as_slice() {
            return self.change_world(world);
        }
        let config = self.robots[0].config();
        let (time, steps) = (self.robots[0].time(), self.robots[0].steps());
        // The new robots first, so that a refusal leaves the running ones as they are.
        let mut fresh = Vec::with_capacity(kept.len());
        for (i, (placement, from)) in placements.iter().zip(kept).enumerate() {
            if from.is_some() {
                fresh.push(None);
                continue;
            }
            let rig = match given(i) {
                Some(profile) => Ok(Rig::new(profile.clone())),
                None => self.rig_for(placement),
            };
            let seed = robot_seed(config.seed, i.max(1), &placement.name);
            let mut sim = Simulator::with_rig_at(
                world.clone(),
                rig?,
                SimConfig { seed, ..config },
                placement.start,
            )
            .map_err(|e| name_robot(e, &placement.name))?;
            let [x, y, yaw] = placement.start;
            sim.set_start(x, y, yaw)
                .map_err(|e| name_robot(e, &placement.name))?;
            sim.reset(None);
            sim.join_clock(time, steps);
            fresh.push(Some(sim));
        }
        let running = self.robots[0].world().clone();
        let bodies = kept_bodies(running.bodies(), world.bodies());
        let poses = self.robots[0].body_poses();
        let velocities = self.robots[0].body_velocities();
        let mut old: Vec<Option<Simulator>> = self.robots.drain(..).map(Some).collect();
        let mut robots = Vec::with_capacity(kept.len());
        let mut commands = Vec::with_capacity(kept.len());
        let mut overrides = Vec::with_capacity(kept.len());
        for (i, (&from, new)) in kept.iter().zip(fresh).enumerate() {
            match (from, new) {
                (Some(j), _) => {
                    robots.extend(old[j].take());
                    commands.push(self.commands[j]);
                    overrides.push(self.overrides.get(j).cloned().flatten());
                }
                (None, new) => {
                    robots.extend(new);
                    commands.push([0.0; 2]);
                    overrides.push(given(i).cloned());
                }
            }
        }
        for robot in &mut robots {
            robot.join_world(world.clone());
        }
        if robots.len() > 1 && !world.bodies().is_empty() {
            share_scene(&mut robots);
        }
        for (i, from) in bodies.iter().enumerate() {
            if let Some(k) = *from {
                robots[0].place_body(i, poses[k]);
                if let Some(&velocity) = velocities.get(k) {
                    robots[0].set_body_velocity(i, velocity);
                }
            }
        }
        self.names = placements.iter().map(|p| p.name.clone()).collect();
        self.overrides = if overrides.iter().any(Option::is_some) {
            overrides
        } else {
            Vec::new()
        };
        self.robots = robots;
        self.commands = commands;
        self.made_of = world;
        Ok(())
    }

    /// The rig of a new robot placed by `placement`: that of a running robot of the profile it
    /// names (or of the swarm's default profile when it names none) that was given no profile
    /// of its own, else a new one.
    fn rig_for(&self, placement: &crate::world::RobotPlacement) -> Result<Arc<Rig>> {
        let own = |j: usize| self.overrides.get(j).is_some_and(Option::is_some);
        let found = (self.robots.iter().enumerate())
            .filter(|&(j, _)| !own(j))
            .map(|(_, r)| r.rig())
            .find(|r| match &placement.profile {
                Some(name) => &r.robot().name == name,
                None => Arc::ptr_eq(r.robot(), &self.profile),
            });
        Ok(match (found, &placement.profile) {
            (Some(rig), _) => rig.clone(),
            (None, Some(name)) => Rig::new(Arc::new(RobotProfile::builtin(name)?)),
            (None, None) => Rig::new(self.profile.clone()),
        })
    }

    /// Puts the scene back as the world was made, as a Webots supervisor's
    /// `simulationReset` does: every robot at its start, the walls `move_solid` moved where the
    /// world has them and every movable body at its start, all at rest, each robot's noise
    /// stream started again from its seed (Webots' reset restarts its random seeds). Time,
    /// counters and wheel commands go on.
    pub fn reset_scene(&mut self) {
        for robot in &mut self.robots {
            robot.restart_among(&self.made_of);
        }
        if self.robots[0].in_shared_scene() {
            share_scene(&mut self.robots);
        }
        sense_robots(&mut self.robots);
    }

    /// Sets the velocity of movable body `index` (world order): `vx`, `vy` in m/s and a turn
    /// rate in rad/s, as a Webots supervisor's `Node.setVelocity` does; the floor's friction
    /// slows it from the next step on.
    pub fn set_body_velocity(&mut self, index: usize, velocity: [f64; 3]) -> Result<()> {
        let count = self.robots[0].body_poses().len();
        if index >= count {
            return Err(Error::InvalidArgument(format!(
                "expected a movable body index below the world's {count} bodies, found {index}"
            )));
        }
        // A body goes no faster than a robot can, so that a step of it stays resolved.
        let [vx, vy, turn] = velocity;
        limits::check_bounded("the body's vx (m/s)", vx, limits::MAX_ROBOT_SPEED)?;
        limits::check_bounded("the body's vy (m/s)", vy, limits::MAX_ROBOT_SPEED)?;
        limits::check_bounded("the body's turn rate (rad/s)", turn, limits::MAX_TURN_RATE)?;
        self.robots[0].set_body_velocity(index, velocity.map(|v| v as f32));
        Ok(())
    }
}

/// The error of robot index `index` in a world of `n` robots.
pub fn bad_index(index: impl std::fmt::Display, n: usize) -> Error {
    Error::InvalidArgument(format!(
        "robot_index: expected a robot index from 0 to {} (the world has {n} robot{}), found {index}",
        n - 1,
        if n == 1 { "" } else { "s" }
    ))
}

#[cfg(test)]
mod tests;

#[cfg(test)]
mod robots_changed_tests;
