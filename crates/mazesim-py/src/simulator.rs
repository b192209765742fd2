//! `Simulator` for Python: the robots of one world (one in most worlds), per-robot calls taking
//! a robot index that defaults to robot 0.

use mazesim_core::tasks::check_ordered;
use mazesim_core::{SimConfig, Simulator, Swarm};
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyTuple};

use crate::args::{bounded_items, typed_argument, Bytes, Flag, IntArg, Real};
use crate::buffers::{copied, readable};
use crate::errors::{invalid, IntoPy};
use crate::guard::{enter, enter_detached};
use crate::lock::Exclusive;
use crate::profile::{given_profiles, PyRobotProfile, RobotArg};
use crate::tasks::{PyStepBounds, PyTaskFeatures};
use crate::world::{dicts, goal_tuple, world_argument, PyWorld};

/// What a busy simulator is called in `SimulatorBusyError`.
const SIMULATOR: &str = "this Simulator";

/// The robots of one world, stepped in control steps.
#[pyclass(name = "Simulator", module = "mazesim._core", frozen)]
pub struct PySimulator {
    inner: Exclusive<Swarm>,
}

impl PySimulator {
    /// `with` on robot 0 for a Python entry point: a panic becomes `InternalError`.
    fn read<T>(&self, f: impl FnOnce(&Simulator) -> T) -> PyResult<T> {
        enter(|| self.inner.with(|s| f(&s.robots()[0])))
    }

    /// `with` on robot `robot_index` (checked) for a Python entry point.
    fn read_robot<T>(&self, robot_index: IntArg, f: impl FnOnce(&Simulator) -> T) -> PyResult<T> {
        enter(|| {
            let index = self.robot_index(&robot_index)?;
            self.inner.with(|s| s.robot(index).map(f))?.py()
        })
    }

    /// `robot_index` checked against the number of robots: an error names that number.
    fn robot_index(&self, robot_index: &IntArg) -> PyResult<usize> {
        let n = self.inner.with(|s| s.len())?;
        let found = match robot_index {
            IntArg::Int(v) => match usize::try_from(*v) {
                Ok(i) if i < n => return Ok(i),
                _ => v.to_string(),
            },
            IntArg::Huge(what) => what.clone(),
            IntArg::Other(_) => return robot_index.count("robot_index", n.max(1) - 1),
        };
        Err(mazesim_core::swarm::bad_index(found, n)).py()
    }

    /// `with` on the swarm for a Python entry point that changes robot `robot_index` (checked),
    /// given to `f` with the swarm.
    fn change_robot(
        &self,
        robot_index: IntArg,
        f: impl FnOnce(&mut Swarm, usize) -> mazesim_core::Result<()>,
    ) -> PyResult<()> {
        enter(|| {
            let index = self.robot_index(&robot_index)?;
            self.inner.with(|s| f(s, index))?.py()
        })
    }

    /// `with` on the whole swarm for a Python entry point.
    fn swarm<T>(&self, f: impl FnOnce(&mut Swarm) -> T) -> PyResult<T> {
        enter(|| self.inner.with(f))
    }
}

/// A sequence of at most `most` indices, named `name` in errors.
pub(crate) fn indices(obj: &Bound<'_, PyAny>, name: &str, most: usize) -> PyResult<Vec<usize>> {
    let items = bounded_items(obj, name, "indices", most)?;
    (items.iter().enumerate())
        .map(|(i, item)| {
            item.extract::<IntArg>()?
                .count(&format!("{name}[{i}]"), most)
        })
        .collect()
}

/// A pose (x, y, yaw) given as a sequence of three real numbers, named `name` in errors.
pub(crate) fn pose_argument(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<[f64; 3]> {
    let items = bounded_items(obj, name, "real numbers (x, y, yaw)", 3)?;
    let values: Vec<f64> = (items.iter().enumerate())
        .map(|(i, item)| item.extract::<Real>()?.value(&format!("{name}[{i}]")))
        .collect::<PyResult<_>>()?;
    values.try_into().map_err(|found: Vec<f64>| {
        invalid(format!(
            "expected {name} to be a pose (x, y, yaw), found {} numbers",
            found.len()
        ))
    })
}

/// A pose (x, y, yaw) as Python floats.
fn pose_tuple(p: [f32; 3]) -> (f64, f64, f64) {
    (p[0] as f64, p[1] as f64, p[2] as f64)
}

/// What one control step of robot 0 gives a gym step (see `Simulator.step_observe`).
struct Stepped {
    readings: Vec<f32>,
    pose: [f32; 3],
    colliding: bool,
    crossing: i32,
    collisions: u64,
}

impl PySimulator {
    /// Steps robot 0 with the wheel speeds `left` and `right`; its readings clamped to [`low`,
    /// `high`] and the rest of a gym step.
    fn stepped(
        &self,
        left: f64,
        right: f64,
        low: &Bound<'_, PyAny>,
        high: &Bound<'_, PyAny>,
    ) -> PyResult<Stepped> {
        // The bounds are read before the simulator is taken: reading them may run Python code
        // (a property of the argument) that uses this simulator.
        let width = self.inner.with(|s| {
            let r = &s.robots()[0];
            r.distance_sensors().len() + r.ground_sensors().len()
        })?;
        let low = readable::<f32>(low, "low", "float32", &[width])?;
        let high = readable::<f32>(high, "high", "float32", &[width])?;
        let contiguous = |name: &str| invalid(format!("expected {name} to be contiguous"));
        let low = low.as_slice().map_err(|_| contiguous("low"))?;
        let high = high.as_slice().map_err(|_| contiguous("high"))?;
        check_ordered(low, high, "reading bounds").py()?;
        self.stepped_within(left, right, low, high)
    }

    /// One step of robot 0 with wheel speeds `left` and `right`, its readings clamped to
    /// [`low`, `high`] (each of the robot's width).
    fn stepped_within(
        &self,
        left: f64,
        right: f64,
        low: &[f32],
        high: &[f32],
    ) -> PyResult<Stepped> {
        self.inner.with(|s| {
            let r = &s.robots()[0];
            let width = r.distance_sensors().len() + r.ground_sensors().len();
            if low.len() != width {
                return Err(invalid(format!(
                    "expected bounds of {width} readings (this robot's), found {}",
                    low.len()
                )));
            }
            s.set_command(0, left, right).py()?;
            s.step_commanded().py()?;
            let s = &s.robots()[0];
            let readings: Vec<f32> = (s.distance_sensors().iter())
                .chain(s.ground_sensors())
                .zip(low.iter().zip(high))
                .map(|(value, (least, most))| value.max(*least).min(*most))
                .collect();
            Ok(Stepped {
                readings,
                pose: s.pose(),
                colliding: s.colliding(),
                crossing: s.last_crossing(),
                collisions: s.collisions(),
            })
        })?
    }
}

#[pymethods]
impl PySimulator {
    #[new]
    #[pyo3(signature = (world, robot = RobotArg::default_robot(), seed = IntArg::ZERO, noise = Flag::Value(true), control_step_ms = None, *, robot_profiles = None),
        text_signature = "(world, robot='e-puck', seed=0, noise=True, control_step_ms=None, *, robot_profiles=None)")]
    fn new(
        world: &Bound<'_, PyAny>,
        robot: RobotArg,
        seed: IntArg,
        noise: Flag,
        control_step_ms: Option<Real>,
        robot_profiles: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        enter(|| {
            let world = world_argument(world, "world")?;
            let profile = robot.profile("robot")?;
            let given = robot_profiles.map(given_profiles).transpose()?;
            let noise = noise.value("noise", "a bool")?;
            let control_step_ms = control_step_ms
                .map(|ms| ms.value("control_step_ms"))
                .transpose()?;
            let config = SimConfig {
                seed: seed.seed("seed")?,
                noise,
                control_step: control_step_ms.map(|ms| ms / 1000.0),
            };
            let given = given.unwrap_or_default();
            let sim = Swarm::with_profiles(world, profile, &given, config).py()?;
            Ok(Self {
                inner: Exclusive::new(sim, SIMULATOR),
            })
        })
    }

    /// Back to the start pose, time and counters zeroed; a new seed if given.
    #[pyo3(signature = (seed = None))]
    fn reset(&self, seed: Option<IntArg>) -> PyResult<()> {
        enter(|| {
            let seed = seed.map(|s| s.seed("seed")).transpose()?;
            self.inner.with(|s| s.reset(seed))
        })
    }

    /// Advances one control step with robot 0's wheel speeds in rad/s (clamped to the motor
    /// limit); the other robots keep their wheel commands.
    fn step(&self, py: Python<'_>, left: Real, right: Real) -> PyResult<()> {
        let (left, right) = (left.value("left")?, right.value("right")?);
        enter_detached(py, || {
            self.inner.with_detached(|s| {
                s.set_command(0, left, right)?;
                s.step_commanded()
            })
        })
    }

    /// Advances one control step with every robot's wheel speeds: an (R, 2) float64 array.
    fn step_robots(&self, py: Python<'_>, commands: &Bound<'_, PyAny>) -> PyResult<()> {
        let n = self.swarm(|s| s.len())?;
        let rows = enter(|| copied::<f64>(commands, "commands", "float64", &[n, 2]))?;
        let commands: Vec<[f64; 2]> = rows.chunks_exact(2).map(|r| [r[0], r[1]]).collect();
        enter_detached(py, || self.inner.with_detached(|s| s.step(&commands)))
    }

    /// Sets robot `robot_index`'s wheel speeds (rad/s) for the next steps, as a Webots controller sets
    /// its motors' velocities.
    #[pyo3(signature = (left, right, robot_index = IntArg::ZERO), text_signature = "($self, left, right, robot_index=0)")]
    fn set_wheel_speeds(&self, left: Real, right: Real, robot_index: IntArg) -> PyResult<()> {
        let (left, right) = (left.value("left")?, right.value("right")?);
        self.change_robot(robot_index, |s, i| s.set_command(i, left, right))
    }

    /// Number of robots in the world.
    #[getter]
    fn num_robots(&self) -> PyResult<usize> {
        self.swarm(|s| s.len())
    }

    /// The robots' names, in world order.
    #[getter]
    fn robot_names(&self) -> PyResult<Vec<String>> {
        self.swarm(|s| s.names().to_vec())
    }

    /// Every robot's pose, an (R, 3) float32 array of x, y, yaw.
    fn poses<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f32>>> {
        let (v, n) = self.swarm(|s| {
            let v: Vec<f32> = s.robots().iter().flat_map(|r| r.pose()).collect();
            (v, s.len())
        })?;
        PyArray1::from_vec(py, v).reshape([n, 3])
    }

    /// Robot `robot`'s state as a dict: pose, colliding, touching_robot, collisions,
    /// distance_travelled, wheel_speeds, encoders, wheel_turns, wall_clearance, last_crossing,
    /// goal.
    #[pyo3(signature = (robot_index = IntArg::ZERO), text_signature = "($self, robot_index=0)")]
    fn robot_state<'py>(
        &self,
        py: Python<'py>,
        robot_index: IntArg,
    ) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        self.read_robot(robot_index, |s| -> PyResult<()> {
            d.set_item("pose", pose_tuple(s.pose()))?;
            d.set_item("colliding", s.colliding())?;
            d.set_item("touching_robot", s.touching_robot())?;
            d.set_item("collisions", s.collisions())?;
            d.set_item("distance_travelled", s.distance_travelled())?;
            let w = s.wheel_speeds();
            d.set_item("wheel_speeds", (w[0] as f64, w[1] as f64))?;
            let e = s.encoders();
            d.set_item("encoders", (e[0], e[1]))?;
            let t = s.wheel_turns();
            d.set_item("wheel_turns", (t[0], t[1]))?;
            d.set_item("wall_clearance", s.wall_clearance() as f64)?;
            d.set_item("last_crossing", s.last_crossing())?;
            d.set_item("goal", s.goal().map(goal_tuple))?;
            d.set_item("profile", s.robot().name.clone())?;
            Ok(())
        })??;
        Ok(d)
    }

    /// `step`, then what a gym step returns, in one call: the readings (float32, the distance
    /// sensors then the ground sensors) clamped to [`low`, `high`] (float32 arrays of that
    /// width), the pose (float32 x, y, yaw), whether the body touches a wall, the signed
    /// checkpoint crossed in this step (0: none) and the collisions so far (as `collisions`).
    #[allow(clippy::type_complexity)]
    fn step_observe<'py>(
        &self,
        py: Python<'py>,
        left: Real,
        right: Real,
        low: &Bound<'py, PyAny>,
        high: &Bound<'py, PyAny>,
    ) -> PyResult<(
        Bound<'py, PyArray1<f32>>,
        Bound<'py, PyArray1<f32>>,
        bool,
        i32,
        u64,
    )> {
        let (left, right) = (left.value("left")?, right.value("right")?);
        let stepped = enter(|| self.stepped(left, right, low, high))?;
        Ok((
            PyArray1::from_vec(py, stepped.readings),
            PyArray1::from_slice(py, &stepped.pose),
            stepped.colliding,
            stepped.crossing,
            stepped.collisions,
        ))
    }

    /// `step_observe`, then the task observation of environment 0 of `features` (a
    /// `TaskFeatures` of this robot's sensors) in the same call: the observation from the
    /// readings clamped to `bounds` (a `StepBounds` of this robot's width), the pose and the
    /// previous action (`left` and `right` over the bounds' `max_speed`, in float32), in place
    /// of the readings; then the pose, whether the body touches a wall, the signed checkpoint
    /// crossed (0: none), the collisions so far, the distance in metres to the features' goal
    /// and whether the pose is in the goal disc. The same values as `step_observe` followed by
    /// `features.observe_env(0, ...)`. With `observe=False` the first value is the clamped
    /// readings themselves, and the features only give the goal's distance (their explored map
    /// is left as it is).
    #[pyo3(signature = (features, bounds, left, right, observe = Flag::Value(true)),
        text_signature = "($self, features, bounds, left, right, observe=True)")]
    #[allow(clippy::type_complexity)]
    fn step_task<'py>(
        &self,
        py: Python<'py>,
        features: &Bound<'py, PyAny>,
        bounds: &Bound<'py, PyAny>,
        left: Real,
        right: Real,
        observe: Flag,
    ) -> PyResult<(
        Bound<'py, PyArray1<f32>>,
        Bound<'py, PyArray1<f32>>,
        bool,
        i32,
        u64,
        f64,
        bool,
    )> {
        let (left, right) = (left.value("left")?, right.value("right")?);
        let observe = observe.value("observe", "a bool")?;
        let features = typed_argument::<PyTaskFeatures>(features, "features", "a TaskFeatures")?;
        let bounds = typed_argument::<PyStepBounds>(bounds, "bounds", "a StepBounds")?;
        let bounds = bounds.get();
        let previous = bounds.previous_action(left, right);
        let features = features.get();
        let (mut stepped, (observation, distance, reached)) = enter(|| {
            let (low, high) = bounds.readings();
            let stepped = self.stepped_within(left, right, low, high)?;
            let task = if observe {
                features.observe_one(0, &stepped.readings, stepped.pose, previous)?
            } else {
                let (distance, reached) = features.goal_of(0, stepped.pose)?;
                (Vec::new(), distance, reached)
            };
            Ok((stepped, task))
        })?;
        let observation = if observe {
            observation
        } else {
            std::mem::take(&mut stepped.readings)
        };
        Ok((
            PyArray1::from_vec(py, observation),
            PyArray1::from_slice(py, &stepped.pose),
            stepped.colliding,
            stepped.crossing,
            stepped.collisions,
            distance,
            reached,
        ))
    }

    /// Sets the pose every later reset starts robot `robot_index` from (instead of the world's start).
    #[pyo3(signature = (x, y, yaw, robot_index = IntArg::ZERO), text_signature = "($self, x, y, yaw, robot_index=0)")]
    fn set_start(&self, x: Real, y: Real, yaw: Real, robot_index: IntArg) -> PyResult<()> {
        let (x, y, yaw) = (x.value("x")?, y.value("y")?, yaw.value("yaw")?);
        self.change_robot(robot_index, |s, i| s.set_start(i, x, y, yaw))
    }

    /// Sets robot `robot_index`'s goal disc, centre (x, y) and radius in metres, instead of the world's.
    #[pyo3(signature = (x, y, radius, robot_index = IntArg::ZERO), text_signature = "($self, x, y, radius, robot_index=0)")]
    fn set_goal(&self, x: Real, y: Real, radius: Real, robot_index: IntArg) -> PyResult<()> {
        let (x, y, radius) = (
            x.coordinate("x")?,
            y.coordinate("y")?,
            radius.value("radius")?,
        );
        self.change_robot(robot_index, |s, i| {
            s.robot_mut(i).and_then(|r| r.set_goal(x, y, radius))
        })
    }

    /// The goal disc (x, y, radius) the episodes end at (`set_goal`'s, else the world's), or None.
    #[getter]
    fn goal(&self) -> PyResult<Option<(f64, f64, f64)>> {
        self.read(|s| s.goal().map(goal_tuple))
    }

    /// Moves robot `robot_index` to (x, y, yaw) at rest and reads the sensors there. With
    /// `overlap_robots` the pose may overlap other robots (as a Webots supervisor may put one
    /// onto another): the next steps' contacts push them apart.
    #[pyo3(signature = (x, y, yaw, robot_index = IntArg::ZERO, overlap_robots = Flag::Value(false)), text_signature = "($self, x, y, yaw, robot_index=0, overlap_robots=False)")]
    fn set_pose(
        &self,
        x: Real,
        y: Real,
        yaw: Real,
        robot_index: IntArg,
        overlap_robots: Flag,
    ) -> PyResult<()> {
        let (x, y, yaw) = (x.value("x")?, y.value("y")?, yaw.value("yaw")?);
        let overlap = overlap_robots.value("overlap_robots", "a bool")?;
        self.change_robot(robot_index, |s, i| {
            if overlap {
                s.place(i, x, y, yaw)
            } else {
                s.set_pose(i, x, y, yaw)
            }
        })
    }

    /// Moves robot `robot_index` as `set_pose` does or, when its body would lie in a wall
    /// there, to the nearest pose within 5 cm that `set_pose` accepts, as Webots' physics pushes
    /// a body out of a wall; returns the (x, y) it stands at.
    #[pyo3(signature = (x, y, yaw, robot_index = IntArg::ZERO, overlap_robots = Flag::Value(false)), text_signature = "($self, x, y, yaw, robot_index=0, overlap_robots=False)")]
    fn set_pose_pushed_out(
        &self,
        x: Real,
        y: Real,
        yaw: Real,
        robot_index: IntArg,
        overlap_robots: Flag,
    ) -> PyResult<(f64, f64)> {
        let (x, y, yaw) = (x.value("x")?, y.value("y")?, yaw.value("yaw")?);
        let overlap = overlap_robots.value("overlap_robots", "a bool")?;
        let mut placed = [x, y];
        self.change_robot(robot_index, |s, i| {
            placed = s.set_pose_pushed_out(i, [x, y], yaw, overlap)?;
            Ok(())
        })?;
        Ok((placed[0], placed[1]))
    }

    /// Robot `robot`'s distance sensor readings (float32), device order.
    #[pyo3(signature = (robot_index = IntArg::ZERO), text_signature = "($self, robot_index=0)")]
    fn distance_sensors<'py>(
        &self,
        py: Python<'py>,
        robot_index: IntArg,
    ) -> PyResult<Bound<'py, PyArray1<f32>>> {
        self.read_robot(robot_index, |s| {
            PyArray1::from_slice(py, s.distance_sensors())
        })
    }

    /// Robot `robot`'s ground sensor readings (float32), device order.
    #[pyo3(signature = (robot_index = IntArg::ZERO), text_signature = "($self, robot_index=0)")]
    fn ground_sensors<'py>(
        &self,
        py: Python<'py>,
        robot_index: IntArg,
    ) -> PyResult<Bound<'py, PyArray1<f32>>> {
        self.read_robot(robot_index, |s| {
            PyArray1::from_slice(py, s.ground_sensors())
        })
    }

    #[getter]
    fn pose(&self) -> PyResult<(f64, f64, f64)> {
        self.read(|s| pose_tuple(s.pose()))
    }
    /// Current poses (x, y, yaw) of the world's movable bodies, in world order.
    fn body_poses(&self) -> PyResult<Vec<(f64, f64, f64)>> {
        let poses = self.read(|s| s.body_poses())?;
        Ok(poses.into_iter().map(pose_tuple).collect())
    }
    /// Current velocities (vx, vy in m/s, turn rate in rad/s) of the world's movable bodies, in
    /// world order.
    fn body_velocities(&self) -> PyResult<Vec<(f64, f64, f64)>> {
        let velocities = self.read(|s| s.body_velocities())?;
        Ok(velocities.into_iter().map(pose_tuple).collect())
    }

    /// Moves an object of the world, as a supervisor moves a node: the `[[walls]]` entries
    /// `walls`, the movable bodies `bodies` (indices, world order) and the `[[paint]]` entries
    /// `paint` (its floor marks) by the rigid motion that takes the pose `from_pose` (x, y, yaw)
    /// to `to_pose`; each body is put at rest. The robots meet them there from the next step
    /// on, and their ground sensors read the paint there. Nothing moves when an index or a pose
    /// is refused.
    #[pyo3(signature = (walls, bodies, from_pose, to_pose, paint=None), text_signature = "($self, walls, bodies, from_pose, to_pose, paint=None)")]
    fn move_solid(
        &self,
        walls: &Bound<'_, PyAny>,
        bodies: &Bound<'_, PyAny>,
        from_pose: &Bound<'_, PyAny>,
        to_pose: &Bound<'_, PyAny>,
        paint: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        let walls = indices(walls, "walls", mazesim_core::limits::MAX_WALLS)?;
        let bodies = indices(bodies, "bodies", mazesim_core::limits::MAX_BODIES)?;
        let most = mazesim_core::limits::MAX_PAINT_REGIONS;
        let paint = paint.map_or(Ok(Vec::new()), |p| indices(p, "paint", most))?;
        let motion = mazesim_core::world::Motion {
            from: pose_argument(from_pose, "from_pose")?,
            to: pose_argument(to_pose, "to_pose")?,
        };
        self.swarm(|s| s.move_solid(&walls, &bodies, &paint, motion))?
            .py()
    }

    /// Runs on in `world` from the next step on, as a Webots supervisor imports nodes into the
    /// running world or removes some: its walls are met and sensed, every robot keeping its
    /// pose, velocities, encoders, noise stream, clock and counters; a movable body both worlds
    /// hold goes on where it is, a new one starts at rest. `world` is what a `reset_scene` puts
    /// back. Without `kept_robots`, refused when `world` holds another number of robots; with
    /// it (one entry per robot of `world`: the index of the running robot it is, or None for a
    /// new one), robots are added and taken out as a supervisor imports and removes them (see
    /// `Swarm::change_world_with_robots`). `robot_profiles` (with `kept_robots`: one entry per
    /// robot of `world`, None but for new robots) gives a new robot its own profile, as the
    /// constructor's does.
    #[pyo3(signature = (world, kept_robots=None, robot_profiles=None), text_signature = "($self, world, kept_robots=None, robot_profiles=None)")]
    fn change_world(
        &self,
        world: &Bound<'_, PyAny>,
        kept_robots: Option<&Bound<'_, PyAny>>,
        robot_profiles: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        let world = world_argument(world, "world")?;
        let given = robot_profiles.map(given_profiles).transpose()?;
        let Some(kept) = kept_robots else {
            if given.is_some() {
                return Err(invalid(
                    "expected robot_profiles with kept_robots, found them alone".into(),
                ));
            }
            return self.swarm(|s| s.change_world(world))?.py();
        };
        let most = mazesim_core::limits::MAX_ROBOTS;
        let items = bounded_items(kept, "kept_robots", "robot indices or None", most)?;
        let kept = (items.iter().enumerate())
            .map(|(i, item)| {
                if item.is_none() {
                    return Ok(None);
                }
                let index = item.extract::<IntArg>()?;
                index.count(&format!("kept_robots[{i}]"), most).map(Some)
            })
            .collect::<PyResult<Vec<Option<usize>>>>()?;
        let given = given.unwrap_or_default();
        self.swarm(|s| s.change_world_with_robots(world, &kept, &given))?
            .py()
    }

    /// Puts the scene back as the world was made, as a Webots supervisor's `simulationReset`
    /// does: every robot at its start, the walls `move_solid` moved where the world has them and
    /// every movable body at its start, all at rest, and every robot's noise stream started again
    /// from its seed, as Webots' reset restarts its random seeds. Time, counters and wheel
    /// commands go on (`reset` zeroes them).
    fn reset_scene(&self) -> PyResult<()> {
        self.swarm(|s| s.reset_scene())
    }

    /// Sets the velocity of movable body `index` (world order): `vx`, `vy` in m/s and
    /// `turn_rate` in rad/s, as a Webots supervisor's `Node.setVelocity` does; the floor's
    /// friction slows it from the next step on.
    #[pyo3(text_signature = "($self, index, vx, vy, turn_rate)")]
    fn set_body_velocity(
        &self,
        index: IntArg,
        vx: Real,
        vy: Real,
        turn_rate: Real,
    ) -> PyResult<()> {
        let index = index.count("index", mazesim_core::limits::MAX_BODIES)?;
        let velocity = [
            vx.value("vx")?,
            vy.value("vy")?,
            turn_rate.value("turn_rate")?,
        ];
        self.swarm(|s| s.set_body_velocity(index, velocity))?.py()
    }

    #[getter]
    fn time(&self) -> PyResult<f64> {
        self.read(|s| s.time())
    }
    #[getter]
    fn steps(&self) -> PyResult<u64> {
        self.read(|s| s.steps())
    }
    #[getter]
    fn collisions(&self) -> PyResult<u64> {
        self.read(|s| s.collisions())
    }
    #[getter]
    fn colliding(&self) -> PyResult<bool> {
        self.read(|s| s.colliding())
    }
    #[getter]
    fn distance_travelled(&self) -> PyResult<f64> {
        self.read(|s| s.distance_travelled())
    }
    #[getter]
    fn wheel_speeds(&self) -> PyResult<(f64, f64)> {
        let w = self.read(|s| s.wheel_speeds())?;
        Ok((w[0] as f64, w[1] as f64))
    }
    #[getter]
    fn encoders(&self) -> PyResult<(f64, f64)> {
        let e = self.read(|s| s.encoders())?;
        Ok((e[0], e[1]))
    }
    /// The wheels' rotation (rad) unquantised: `encoders` before its rounding to the profile's
    /// `encoder_resolution`.
    #[getter]
    fn wheel_turns(&self) -> PyResult<(f64, f64)> {
        let e = self.read(|s| s.wheel_turns())?;
        Ok((e[0], e[1]))
    }
    #[getter]
    fn wall_clearance(&self) -> PyResult<f64> {
        self.read(|s| s.wall_clearance() as f64)
    }
    /// Barcode crossed in the last step: +id along the checkpoint's yaw (arrival), -id against it
    /// (departure), 0 for none.
    #[getter]
    fn last_crossing(&self) -> PyResult<i32> {
        self.read(|s| s.last_crossing())
    }

    /// Robot `robot`'s barcode crossings since reset: dicts of checkpoint, direction ("arrival"
    /// along the checkpoint's yaw, "departure" against it), step and time.
    #[pyo3(signature = (robot_index = IntArg::ZERO), text_signature = "($self, robot_index=0)")]
    fn crossings<'py>(
        &self,
        py: Python<'py>,
        robot_index: IntArg,
    ) -> PyResult<Vec<Bound<'py, PyDict>>> {
        let (list, dt) =
            self.read_robot(robot_index, |s| (s.crossings().to_vec(), s.control_step()))?;
        dicts(py, &list, |d, c| {
            d.set_item("checkpoint", c.checkpoint)?;
            d.set_item("direction", if c.forward { "arrival" } else { "departure" })?;
            d.set_item("step", c.step)?;
            d.set_item("time", c.step as f64 * dt)
        })
    }

    #[getter]
    fn control_step_ms(&self) -> PyResult<f64> {
        self.read(|s| s.control_step() * 1000.0)
    }
    #[getter]
    fn robot(&self) -> PyResult<PyRobotProfile> {
        Ok(PyRobotProfile {
            inner: self.read(|s| s.robot().clone())?,
        })
    }
    /// Robot `robot_index`'s profile itself: a built-in one or the one a profile file gave,
    /// so a multi-robot world's robots travel with their own profiles, not with a name.
    #[pyo3(signature = (robot_index = IntArg::ZERO), text_signature = "($self, robot_index=0)")]
    fn robot_profile(&self, robot_index: IntArg) -> PyResult<PyRobotProfile> {
        Ok(PyRobotProfile {
            inner: self.read_robot(robot_index, |s| s.robot().clone())?,
        })
    }
    #[getter]
    fn world(&self) -> PyResult<PyWorld> {
        Ok(PyWorld {
            inner: self.read(|s| s.world().clone())?,
        })
    }

    /// The whole state as bytes, for `restore` (pose, velocities, rapier's contact state, noise
    /// stream, time, counters, barcode tracker, readings).
    fn snapshot<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyBytes>> {
        let bytes = self.swarm(|s| s.snapshot())?;
        Ok(PyBytes::new(py, &bytes))
    }

    /// Puts the simulator in the state of a `snapshot` of a simulator of the same world, robot
    /// profile, control step and noise setting; it then goes on exactly as that one would.
    fn restore(&self, py: Python<'_>, snapshot: Bytes) -> PyResult<()> {
        let snapshot = enter(|| snapshot.value("snapshot", "bytes"))?.0;
        enter_detached(py, || self.inner.with_detached(|s| s.restore(&snapshot)))
    }

    /// An independent simulator in the same state, sharing the (immutable) world.
    fn __copy__(&self) -> PyResult<Self> {
        enter(|| {
            let copy = self.inner.with(|s| s.duplicate())?.py()?;
            Ok(Self {
                inner: Exclusive::new(copy, SIMULATOR),
            })
        })
    }

    fn __deepcopy__(&self, _memo: &Bound<'_, PyDict>) -> PyResult<Self> {
        self.__copy__()
    }

    /// Pickles as the constructor's arguments and a snapshot.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyTuple>> {
        let py = slf.py();
        let this = slf.get();
        let (world, robot, config, snapshot, given) = this.swarm(|s| {
            let first = &s.robots()[0];
            // A world of one robot pickles its robot's profile; one of several the profile of
            // the robots whose placement names none, and the profiles given for some.
            let robot = if s.len() == 1 {
                first.robot().clone()
            } else {
                s.default_profile().clone()
            };
            let given = if s.len() == 1 {
                Vec::new()
            } else {
                s.profile_overrides().to_vec()
            };
            (
                first.world().clone(),
                robot,
                first.config(),
                s.snapshot(),
                given,
            )
        })?;
        let control_step_ms = config.control_step.map(|c| c * 1000.0);
        let args = (
            PyWorld { inner: world },
            PyRobotProfile { inner: robot },
            config.seed,
            config.noise,
            control_step_ms,
        );
        let state = PyBytes::new(py, &snapshot);
        if given.is_empty() {
            return (slf.get_type(), args, state).into_pyobject(py);
        }
        // The constructor with the given profiles as its keyword argument.
        let profiles: Vec<Option<PyRobotProfile>> = (given.into_iter())
            .map(|p| p.map(|inner| PyRobotProfile { inner }))
            .collect();
        let keywords = PyDict::new(py);
        keywords.set_item("robot_profiles", profiles)?;
        let partial = py.import("functools")?.getattr("partial")?;
        let constructor = partial.call((slf.get_type(),), Some(&keywords))?;
        (constructor, args, state).into_pyobject(py)
    }

    fn __setstate__(&self, py: Python<'_>, state: Bytes) -> PyResult<()> {
        self.restore(py, state)
    }

    fn __repr__(&self) -> PyResult<String> {
        self.swarm(|w| {
            let s = &w.robots()[0];
            let robots = if w.len() > 1 {
                format!(", robots={}", w.len())
            } else {
                String::new()
            };
            format!(
                "Simulator(world={:?}, robot={:?}{robots}, time={:.3})",
                s.world().name(),
                s.robot().name,
                s.time()
            )
        })
    }
}
