"""mazesim against what a Python user could write instead, on the canonical workload.

Not a test: run it by hand or with `make bench-peers` (which installs pymunk and jax into .venv
first).

The workload is the canonical one of docs/performance.md: per environment a distinct 5 x 5 maze
of 0.25 m cells and 0.01 m walls (``generate_maze(seed=i, loops=0.1)``), the e-puck with ps0-ps7
and gs0-gs2 read every step with noise, a 32 ms control step (= one physics step) and wheel
speeds from the same Braitenberg rule (``peers.workload.braitenberg``). One env-step is one
control step of one robot with all 11 sensors read. It runs up to five ways in this process:

- mazesim: ``BatchSimulator`` stepping into preallocated buffers, the rule in numpy (one step
  per call), or many steps per call with the same rule in the engine (``BatchSimulator.run``);
- numpy: a tuned kinematic simulator in plain vectorised float32 numpy, worked in cache-sized
  chunks of environments (``peers.numpy_peer``; chunk size from a quick sweep unless given);
- pymunk: one Chipmunk space per environment, hand-built (``peers.pymunk_peer``);
- jax: the numpy peer's model in jax.numpy, one env's step jitted, vmapped over the envs and run
  ``--steps-per-call`` steps per call by ``lax.scan`` (``peers.jax_peer``);
- jax-lean: the same without sensor noise and ground sensors, the leaner env a JAX user may
  write first (it does less work than the others).

Steady state: every runner first steps ``--warmup`` control steps (or ``--warmup-seconds``,
whichever ends first). Then the runners are timed in interleaved rounds (mazesim, numpy, ...,
mazesim, numpy, ...) so that any other load on the machine falls on all of them alike; each
round runs ``--steps / --rounds`` control steps, or by default enough to take
``--seconds / --rounds`` of wall time. A runner's figure is the median of its rounds' rates.
mazesim uses every core (rayon) unless ``--threads`` says otherwise; numpy and pymunk use one;
JAX uses XLA's own CPU threads. At more than one step per call only the runners that can run
several steps in one call (mazesim and the JAX peers) are timed.

    .venv/bin/python benches/bench_vs_peers.py [--envs 1,1024,4096] [--steps-per-call 1,100]
        [--steps K] [--json] [--check]

``--check`` also runs the physical and sensor checks: robots stay inside their mazes, the deepest
wall penetration over a run, each peer's noise-free readings against mazesim's at the same
poses, and the JAX peer's trajectories against the numpy peer's from the same start.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import statistics
import sys
import time
from collections.abc import Callable, Sequence
from typing import Any, Protocol

import numpy as np

import mazesim
from mazesim.benchmark.size_sweep import machine

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from peers import workload as wl  # noqa: E402
from peers.fidelity import step_agreement, trajectory_agreement  # noqa: E402
from peers.numpy_peer import NumpyPeer  # noqa: E402

PEERS = ("mazesim", "numpy", "pymunk", "jax", "jax-lean")
# The runners that can run several control steps in one call.
MULTI_STEP = ("mazesim", "jax", "jax-lean")
CHUNKS = (64, 128, 256, 512, 1024, 2048)
# Metres apart at which two peers' twin robots count as parted.
TRAJECTORY_TOLERANCE = 1e-3
# The targets: (peer, steps per call) -> (mazesim at least this many times the peer, at these
# env counts).
TARGETS = {
    ("numpy", 1): (3.0, (1024,)),
    ("pymunk", 1): (25.0, (1024,)),
    ("jax", 1): (2.0, (1024, 4096)),
    ("jax", 100): (1.0, (1024, 4096)),
}


class Runner(Protocol):
    name: str
    steps_per_call: int

    def reset(self) -> None: ...
    def step(self) -> None: ...
    def poses(self) -> np.ndarray: ...


class MazesimRunner:
    """``BatchSimulator`` with caller-owned buffers; the Braitenberg rule reads obs[:, :8].
    A call runs ``steps_per_call`` control steps."""

    name = "mazesim"

    def __init__(
        self,
        worlds: Sequence[mazesim.World],
        threads: int = 0,
        noise: bool = True,
        steps_per_call: int = 1,
    ) -> None:
        self.steps_per_call = steps_per_call
        n = len(worlds)
        self.batch = mazesim.BatchSimulator(
            list(worlds), robot="e-puck", seeds=0, noise=noise, threads=threads
        )
        self.obs = np.zeros((n, self.batch.observation_width), np.float32)
        self.pose = np.zeros((n, 3), np.float32)
        self.colliding = np.zeros(n, np.bool_)
        self.crossings = np.zeros(n, np.int32)
        self.actions = np.zeros((n, 2), np.float32)
        self.scratch = np.zeros((8, n), np.float32)
        self.no_autoreset = mazesim.RunSettings(mazesim.EpisodeLimits(autoreset=False))

    def reset(self) -> None:
        self.batch.reset(self.obs, self.pose, self.colliding, self.crossings)

    def step(self) -> None:
        if self.steps_per_call > 1:
            # The same rule in the engine (bit for bit), many steps per call, no episode limit.
            self.batch.run(
                self.steps_per_call,
                "braitenberg",
                self.obs,
                self.pose,
                self.colliding,
                self.crossings,
                settings=self.no_autoreset,
            )
            return
        wl.braitenberg(self.obs[:, :8].T, self.actions[:, 0], self.actions[:, 1], self.scratch)
        self.batch.step(self.actions, self.obs, self.pose, self.colliding, self.crossings)

    def poses(self) -> np.ndarray:
        return self.pose


def versions() -> dict[str, str]:
    out = {
        "python": platform.python_version(),
        "mazesim": mazesim.__version__,
        "numpy": np.__version__,
    }
    try:
        import pymunk

        out["pymunk"] = f"{pymunk.version} (Chipmunk {pymunk.chipmunk_version.split('-')[0]})"
    except ImportError:
        out["pymunk"] = "not installed"
    try:
        import jax

        out["jax"] = jax.__version__
    except ImportError:
        out["jax"] = "not installed"
    return out


def rate_of(runner: Runner, envs: int, seconds: float) -> float:
    """Env-steps/s over at least `seconds` (and two steps) of stepping."""
    steps, started = 0, time.perf_counter()
    while True:
        runner.step()
        steps += 1
        elapsed = time.perf_counter() - started
        if elapsed >= seconds and steps >= 2:
            return envs * steps / elapsed


def sweep_chunks(
    mazes: Sequence[wl.Maze], robot: wl.Robot, say: Callable[[str], None]
) -> tuple[int, dict[int, float]]:
    """The numpy peer's best chunk size: the best of five short bursts of each candidate, the
    candidates taken in turn so that other load on the machine falls on all of them. Large
    batches are swept on their first 2 * max(CHUNKS) environments."""
    mazes = mazes[: 2 * max(CHUNKS)]
    envs = len(mazes)
    peers = {c: NumpyPeer(mazes, robot, chunk=c) for c in sorted({min(c, envs) for c in CHUNKS})}
    rates = dict.fromkeys(peers, 0.0)
    for peer in peers.values():
        peer.reset()
        peer.step()
    for _ in range(5):
        for chunk, peer in peers.items():
            rates[chunk] = max(rates[chunk], rate_of(peer, envs, 0.05))
    best = max(rates, key=rates.__getitem__)
    say(
        "numpy chunk sweep (env-steps/s): "
        + ", ".join(f"{c}: {r:,.0f}" for c, r in rates.items())
        + f" -> chunk {best}"
    )
    return best, rates


def make_runner(
    name: str,
    worlds: Sequence[mazesim.World],
    mazes: Sequence[wl.Maze],
    robot: wl.Robot,
    chunk: int,
    threads: int,
    noise: bool = True,
    steps_per_call: int = 1,
) -> Runner:
    if steps_per_call > 1 and name not in MULTI_STEP:
        raise ValueError(f"{name} runs one step per call")
    if name == "mazesim":
        return MazesimRunner(worlds, threads=threads, noise=noise, steps_per_call=steps_per_call)
    if name == "numpy":
        return NumpyPeer(mazes, robot, chunk=chunk, noise=noise)
    if name in ("jax", "jax-lean"):
        from peers.jax_peer import JaxPeer

        lean = name == "jax-lean"
        return JaxPeer(
            mazes, robot, noise=noise and not lean, steps_per_call=steps_per_call, ground=not lean
        )
    from peers.pymunk_peer import PymunkPeer

    return PymunkPeer(mazes, robot, noise=noise)


def sync(runner: Runner) -> None:
    """Waits for the steps a runner has dispatched (JAX's calls return before they are done)."""
    wait = getattr(runner, "sync", None)
    if wait is not None:
        wait()


def warm_up(runner: Runner, steps: int, seconds: float) -> int:
    """Steps `runner` for `steps` control steps or `seconds`, whichever ends first (at least one
    call, which also compiles the JAX peers); returns the control steps done."""
    done, started = 0, time.perf_counter()
    while True:
        runner.step()
        done += runner.steps_per_call
        if done >= steps:
            break
        if time.perf_counter() - started >= seconds:
            sync(runner)
            if time.perf_counter() - started >= seconds:
                break
    sync(runner)
    return done


def threads_of(name: str, threads: int) -> int | str:
    if name == "mazesim":
        return threads or int(machine()["usable_cores"])
    return "XLA CPU" if name.startswith("jax") else 1


def measure(
    envs: int,
    peers: Sequence[str],
    steps_per_call: int,
    settings: argparse.Namespace,
    say: Callable[[str], None],
) -> dict[str, Any]:
    worlds = wl.make_worlds(envs)
    mazes = [wl.maze_of(w) for w in worlds]
    robot = wl.epuck()
    sanity = wl.Sanity(mazes, robot.body_radius)
    sweep: dict[int, float] = {}
    chunk = settings.chunk
    if "numpy" in peers and chunk is None:
        chunk, sweep = sweep_chunks(mazes, robot, say)
    chunk = chunk or 256

    runners: list[Runner] = []
    warmed: dict[str, int] = {}
    for name in peers:
        runner = make_runner(
            name, worlds, mazes, robot, chunk, settings.threads, steps_per_call=steps_per_call
        )
        runner.reset()
        warmed[name] = warm_up(runner, settings.warmup, settings.warmup_seconds)
        runners.append(runner)

    # Each round runs a runner for `steps / rounds` control steps, or by default for
    # `seconds / rounds` of wall time (then every call is timed and the round ends on the first
    # call past it).
    rounds = settings.rounds
    elapsed = {r.name: 0.0 for r in runners}
    done = {r.name: 0 for r in runners}
    rates: dict[str, list[float]] = {r.name: [] for r in runners}
    per_round = None if settings.steps is None else max(1, math.ceil(settings.steps / rounds))
    for _ in range(rounds):
        for runner in runners:
            k, started = 0, time.perf_counter()
            while True:
                runner.step()
                k += runner.steps_per_call
                if per_round is not None:
                    if k >= per_round:
                        break
                elif time.perf_counter() - started >= settings.seconds / rounds:
                    break
            sync(runner)
            dt = time.perf_counter() - started
            elapsed[runner.name] += dt
            done[runner.name] += k
            rates[runner.name].append(envs * k / dt)

    results = []
    for runner in runners:
        total = done[runner.name]
        results.append(
            {
                "envs": envs,
                "peer": runner.name,
                "steps_per_call": steps_per_call,
                "env_steps_per_s": statistics.median(rates[runner.name]),
                "round_env_steps_per_s": rates[runner.name],
                "mean_env_steps_per_s": envs * total / elapsed[runner.name],
                "warmup_steps": warmed[runner.name],
                "steps": total,
                "seconds": elapsed[runner.name],
                "threads": threads_of(runner.name, settings.threads),
                "sanity": sanity(runner.poses()),
            }
        )
    out: dict[str, Any] = {"envs": envs, "steps_per_call": steps_per_call, "results": results}
    if "numpy" in peers:
        out["numpy_chunk"] = chunk
        if sweep:
            out["numpy_chunk_sweep"] = {str(c): r for c, r in sweep.items()}
    return out


def ratios(results: Sequence[dict[str, Any]]) -> dict[str, float]:
    """mazesim's median rate over each peer's, of runs at the same env count and steps per call."""
    by = {r["peer"]: r["env_steps_per_s"] for r in results}
    if "mazesim" not in by:
        return {}
    return {f"mazesim/{p}": by["mazesim"] / by[p] for p in PEERS[1:] if p in by}


def target_of(peer: str, steps_per_call: int, envs: int) -> float | None:
    goal = TARGETS.get((peer, steps_per_call))
    return goal[0] if goal is not None and envs in goal[1] else None


def check(envs: int, steps: int, chunk: int, threads: int, peers: Sequence[str]) -> dict[str, Any]:
    """Untimed checks: the sanity of each runner's robots over a run (every step), each peer's
    noise-free readings against mazesim's ``Simulator`` at poses mazesim's robots visited, and
    the JAX peers' steps and trajectories against the numpy peer's (noise off)."""
    worlds = wl.make_worlds(envs)
    mazes = [wl.maze_of(w) for w in worlds]
    robot = wl.epuck()
    sanity = wl.Sanity(mazes, robot.body_radius)
    report: dict[str, Any] = {
        "envs": envs,
        "steps": steps,
        "runs": {},
        "sensors": {},
        "against_numpy": {},
    }
    visited: list[np.ndarray] = []
    for name in peers:
        runner = make_runner(name, worlds, mazes, robot, chunk, threads)
        runner.reset()
        deepest, inside = 0.0, 1.0
        for k in range(steps):
            runner.step()
            s = sanity(runner.poses())
            deepest = max(deepest, s["max_penetration_m"])
            inside = min(inside, s["inside_share"])
            if name == "mazesim" and k % 25 == 24:
                visited.append(np.array(runner.poses(), copy=True))
        report["runs"][name] = {
            "min_inside_share": inside,
            "max_penetration_m": deepest,
            "mean_distance_from_start_m": s["mean_distance_from_start_m"],
        }
    if not visited:
        return report
    # Sensor models: noise off, poses from the mazesim run (many of them close to walls).
    poses = np.concatenate(visited)[: 4 * envs].astype(np.float32)
    env_of = np.arange(len(poses)) % envs
    reference = np.empty((len(poses), 11), np.float32)
    for k, (i, pose) in enumerate(zip(env_of, poses)):
        sim = mazesim.Simulator(worlds[i], robot="e-puck", seed=0, noise=False)
        sim.set_pose(*(float(v) for v in pose))
        reference[k, :8] = sim.distance_sensors()
        reference[k, 8:] = sim.ground_sensors()
    for name in peers:
        if name == "mazesim":
            continue
        maze_list = [mazes[i] for i in env_of]
        runner = make_runner(name, [worlds[i] for i in env_of], maze_list, robot, chunk, 0, False)
        runner.set_poses(poses)  # type: ignore[attr-defined]
        obs = runner.observations()  # type: ignore[attr-defined]
        ps_err = np.abs(obs[:, :8] - reference[:, :8])
        report["sensors"][name] = {
            "poses": len(poses),
            "ps_max_abs_diff": float(ps_err.max()),
            "ps_max_rel_diff": float((ps_err / np.maximum(reference[:, :8], 1.0)).max()),
        }
        if obs.shape[1] > 8:
            gs_err = np.abs(obs[:, 8:] - reference[:, 8:])
            report["sensors"][name]["gs_share_within_1"] = float((gs_err <= 1.0).mean())
            report["sensors"][name]["gs_max_abs_diff"] = float(gs_err.max())
    # The JAX peers against the numpy peer, whose model they share: one step from the same poses,
    # then whole trajectories from the same starts (noise off).
    for name in (p for p in peers if p.startswith("jax")):
        maze_list = [mazes[i] for i in env_of]
        visited_worlds = [worlds[i] for i in env_of]
        peer = make_runner(name, visited_worlds, maze_list, robot, chunk, 0, False)
        numpy_peer = make_runner("numpy", visited_worlds, maze_list, robot, chunk, 0, False)
        agreement = step_agreement(peer, numpy_peer, poses)  # type: ignore[arg-type]
        peer = make_runner(name, worlds, mazes, robot, chunk, 0, False)
        numpy_peer = make_runner("numpy", worlds, mazes, robot, chunk, 0, False)
        agreement["trajectories"] = trajectory_agreement(
            peer,  # type: ignore[arg-type]
            numpy_peer,  # type: ignore[arg-type]
            steps,
            TRAJECTORY_TOLERANCE,
        )
        report["against_numpy"][name] = agreement
    return report


def parse(argv: Sequence[str] | None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--envs", default="1,1024,4096", help="environment counts, comma-separated")
    parser.add_argument(
        "--steps-per-call",
        default="1,100",
        help="control steps per call, comma-separated (above 1: mazesim and the JAX peers only)",
    )
    parser.add_argument(
        "--steps", type=int, help="control steps per runner (default: enough for --seconds)"
    )
    parser.add_argument("--seconds", type=float, default=2.0, help="wall time per runner")
    parser.add_argument("--rounds", type=int, default=5, help="interleaved timing rounds")
    parser.add_argument("--warmup", type=int, default=1000, help="control steps before timing")
    parser.add_argument(
        "--warmup-seconds", type=float, default=5.0, help="the longest warm-up per runner"
    )
    parser.add_argument("--chunk", type=int, help="numpy peer's chunk size (default: sweep)")
    parser.add_argument("--threads", type=int, default=0, help="mazesim threads (0: all cores)")
    parser.add_argument("--peers", default=",".join(PEERS), help="runners, comma-separated")
    parser.add_argument("--check", action="store_true", help="also run the physical checks")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    args = parser.parse_args(argv)
    try:
        args.envs = [int(e) for e in args.envs.split(",")]
        args.steps_per_call = [int(k) for k in args.steps_per_call.split(",")]
    except ValueError:
        parser.error("--envs and --steps-per-call take whole numbers, comma-separated")
    args.peers = [p.strip() for p in args.peers.split(",") if p.strip()]
    unknown = set(args.peers) - set(PEERS)
    if unknown or not args.peers or min(args.envs) < 1 or args.rounds < 1:
        parser.error(f"runners are among {', '.join(PEERS)}; envs and rounds at least 1")
    if min(args.steps_per_call) < 1 or args.warmup < 0:
        parser.error("steps per call at least 1, warm-up at least 0")
    missing = [
        package
        for package, needed_by in (("pymunk", ("pymunk",)), ("jax", ("jax", "jax-lean")))
        if set(needed_by) & set(args.peers) and not installed(package)
    ]
    if missing:
        parser.error(
            f"{' and '.join(missing)} not installed: `.venv/bin/pip install {' '.join(missing)}` "
            "or `make bench-peers`"
        )
    return args


def installed(package: str) -> bool:
    try:
        __import__(package)
    except ImportError:
        return False
    return True


def say_results(runs: Sequence[dict[str, Any]], say: Callable[[str], None]) -> None:
    say("")
    say(
        f"{'envs':>6}  {'per call':>8}  {'peer':<8} {'env-steps/s':>12}  {'vs mazesim':>10}  "
        f"{'rounds (min-max)':>25}  {'steps':>7}  seconds"
    )
    for run in runs:
        base = {r["peer"]: r["env_steps_per_s"] for r in run["results"]}.get("mazesim")
        for r in run["results"]:
            vs = f"{r['env_steps_per_s'] / base:.3f}" if base else "-"
            spread = (
                f"{min(r['round_env_steps_per_s']):,.0f}-{max(r['round_env_steps_per_s']):,.0f}"
            )
            say(
                f"{r['envs']:>6}  {r['steps_per_call']:>8}  {r['peer']:<8} "
                f"{r['env_steps_per_s']:>12,.0f}  {vs:>10}  {spread:>25}  {r['steps']:>7}  "
                f"{r['seconds']:.1f}"
            )
    for run in runs:
        for key, value in ratios(run["results"]).items():
            target = target_of(key.split("/")[1], run["steps_per_call"], run["envs"])
            say(
                f"{run['envs']} envs, {run['steps_per_call']} per call: "
                f"{key.replace('/', ' / ')} = {value:.2f}x"
                + (f" (target >= {target:g}x)" if target else "")
            )
        if "numpy_chunk" in run:
            say(f"{run['envs']} envs: numpy peer chunk = {run['numpy_chunk']} envs")
    for run in runs:
        for r in run["results"]:
            s = r["sanity"]
            say(
                f"sanity {r['envs']} {r['peer']} ({r['steps_per_call']} per call): inside "
                f"{s['inside_share']:.3f}, penetration {s['max_penetration_m'] * 1000:.2f} mm, "
                f"{s['mean_distance_from_start_m']:.2f} m from start"
            )


def say_checks(checks: dict[str, Any], say: Callable[[str], None]) -> None:
    say("")
    say(f"checks over {checks['steps']} steps of {checks['envs']} envs (every step):")
    for name, c in checks["runs"].items():
        say(
            f"  {name:<8} min inside share {c['min_inside_share']:.3f}, "
            f"deepest penetration {c['max_penetration_m'] * 1000:.2f} mm, "
            f"mean {c['mean_distance_from_start_m']:.3f} m from start"
        )
    for name, c in checks["sensors"].items():
        ground = (
            f", gs within 1 count {c['gs_share_within_1']:.1%} (max |diff| "
            f"{c['gs_max_abs_diff']:.0f}: mazesim averages a 3 mm spot, the peer samples a point)"
            if "gs_max_abs_diff" in c
            else ""
        )
        say(
            f"  {name:<8} vs mazesim, noise off, {c['poses']} poses: ps max |diff| "
            f"{c['ps_max_abs_diff']:.3g} ({c['ps_max_rel_diff']:.2%}){ground}"
        )
    for name, c in checks["against_numpy"].items():
        t = c["trajectories"]
        say(
            f"  {name:<8} vs numpy, noise off, one step from {c['poses']} poses: position "
            f"{c['max_position_gap_m']:.2g} m, heading {c['max_heading_gap_rad']:.2g} rad, "
            f"readings {c['max_relative_reading_gap']:.2%} apart at most; over {t['steps']} "
            f"steps from the starts {t['share_within_tolerance']:.1%} of robots within "
            f"{t['tolerance_m'] * 1000:g} mm of their twin"
        )


def main(argv: Sequence[str] | None = None) -> int:
    args = parse(argv)

    def say(line: str) -> None:
        if not args.json:
            print(line, flush=True)

    info = machine()
    vers = versions()
    threads = args.threads or info["usable_cores"]  # 0: rayon's global pool, one per core
    say(f"machine: {info['cpu']}, {info['cores']} cores (load {info.get('load_average_1min')})")
    say("versions: " + ", ".join(f"{k} {v}" for k, v in vers.items()))
    say(
        f"threads: mazesim {threads} (rayon), numpy 1 (elementwise ufuncs), pymunk 1 "
        "(Python loop), jax XLA's CPU threads"
    )

    runs = []
    for n in args.envs:
        for per_call in args.steps_per_call:
            peers = [p for p in args.peers if per_call == 1 or p in MULTI_STEP]
            if peers:
                runs.append(measure(n, peers, per_call, args, say))
    results = [r for run in runs for r in run["results"]]
    say_results(runs, say)

    checks = None
    if args.check:
        chunk = runs[0].get("numpy_chunk") or args.chunk or 256
        checks = check(min(max(args.envs), 256), 500, chunk, args.threads, args.peers)
        say_checks(checks, say)

    if args.json:
        doc: dict[str, Any] = {
            "workload": {
                "maze": f"{wl.MAZE_CELLS} x {wl.MAZE_CELLS} cells of {wl.CELL_SIZE} m, "
                f"{wl.WALL_THICKNESS} m walls, loops {wl.LOOPS}, env i = seed i",
                "robot": "e-puck, ps0-ps7 and gs0-gs2 with noise (jax-lean: ps0-ps7, no noise)",
                "control_step_s": wl.CONTROL_STEP,
                "controller": "braitenberg (peers/workload.py)",
                "rounds": args.rounds,
                "warmup_steps": args.warmup,
                "statistic": "median of the rounds' env-steps/s",
            },
            "machine": info,
            "versions": vers,
            "threads": {"mazesim": threads, "numpy": 1, "pymunk": 1, "jax": "XLA CPU"},
            "results": results,
            "ratios": {
                f"{run['envs']}x{run['steps_per_call']}": ratios(run["results"]) for run in runs
            },
            "numpy_chunk": {str(run["envs"]): run.get("numpy_chunk") for run in runs},
        }
        if checks is not None:
            doc["checks"] = checks
        print(json.dumps(doc, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
