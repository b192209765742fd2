"""The lower level's training rounds in the core: the default and the randomised navigator, and a
fleet of several sensor sets.

Not a test: run it by hand::

    .venv/bin/python benches/bench_train.py [--envs 2048] [--rounds 5] [--threads 2] [--json]

Three trainers of ``mazesim train``'s lower-level settings (2,048 robots, rounds of 500 control
steps, the pool of 200 generated mazes) run the same rounds in turns, one round each:

- ``default``: the default navigator's options (``mazesim._core.train_lower_round``);
- ``randomised``: the shipped randomised navigator's options (``--randomise`` with its ranges,
  ``--door-distance --hold-heading --seed 11``, robots drawn anew each round), what ``mazesim
  train`` runs for it;
- ``fleet``: the same with a ``robot`` range of four profiles (``seed|e-puck|e-puck2|
  e-puck-hardware``), a batch per profile, the others read through their maps into seed volts.

The loops take turns in pairs (the order swapped every round), so that a load that comes and
goes on the machine falls on all alike. The figures are the medians of the rounds' wall times, in
env-steps per second, and the medians of the per-round ratios of each loop's speed to the default
navigator's in the same round (``randomised_against_default``): the acceptance figure of the
randomised navigator's training in the core. A randomised run also draws its robots anew and
builds their batch before every round; ``randomised_with_draw_against_default`` counts that too
(what a round of ``mazesim train`` costs it), and ``draw_seconds`` gives it alone.

With ``--baseline-python PYTHON`` (the interpreter of another build of mazesim, say a checkout of
an earlier commit), it compares builds instead: the randomised navigator's round of this build
against the default navigator's round of the other, each in a process of its own that keeps its
trainer between rounds (the same robot count and seed, round after round), the two processes
taking turns (the order swapped every round). It prints both medians and the median of the
per-round ratios (the other build's default round time over this build's randomised round time,
so above 1 is faster), in wall seconds and in the processes' processor seconds; with
``--threads 1`` the processor time is one thread's work, which a loaded machine disturbs least::

    .venv/bin/python benches/bench_train.py --baseline-python ../base/.venv/bin/python \
        --threads 1 --rounds 7

Timing on a shared machine scatters by several per cent; with ``--instructions`` (and
``--baseline-python``) it counts instead (valgrind's callgrind, which the machine's load does not
move): each build serves one round of its loop on one thread under callgrind, once with the round
and once without it (the same import, set-up and robots' draw), and the difference over the
round's env-steps is its instructions per env-step. The script exits with status 1 when this
build's randomised round needs more than ``TOLERANCE`` (a fraction, 0.01 unless given) more than
the other build's default round::

    .venv/bin/python benches/bench_train.py --baseline-python ../base/.venv/bin/python \
        --envs 256 --instructions [TOLERANCE]
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from typing import Any

from mazesim.learn.lower import LowerSettings, LowerTrainer
from mazesim.learn.tables import load_policy
from mazesim.transfer.randomise import parse_spec, robot_draw

#: The robot range of the fleet loop.
FLEET = "seed|e-puck|e-puck2|e-puck-hardware"


def measure(envs: int, rounds: int, threads: int) -> dict[str, Any]:
    """Times ``rounds`` rounds of each loop, in turns; see the module."""
    settings = LowerSettings(num_envs=envs, total_steps=envs * 500 * rounds)
    shipped = load_policy("randomised").training["settings"]
    randomised = dataclasses.replace(
        settings,
        seed=shipped["seed"],
        door_distance=True,
        blind_forward=True,
        hold_heading=True,
    )
    draws = {
        "randomised": robot_draw(parse_spec(shipped["randomise"]), shipped["seed"]),
        "fleet": robot_draw(parse_spec(f"robot={FLEET},{shipped['randomise']}"), shipped["seed"]),
    }
    trainers = {
        "default": LowerTrainer(settings, threads=threads),
        "randomised": LowerTrainer(randomised, threads=threads),
        "fleet": LowerTrainer(randomised, threads=threads),
    }
    seconds: dict[str, list[float]] = {name: [] for name in trainers}
    draw_seconds: dict[str, list[float]] = {name: [] for name in draws}
    names = list(trainers)
    for k in range(rounds):
        # Swap the order every round: a pair's ratio does not favour the loop that runs first.
        for name in names if k % 2 == 0 else names[::-1]:
            trainer = trainers[name]
            if name in draws:
                start = time.perf_counter()
                trainer.use_robots(draws[name](k, envs))
                draw_seconds[name].append(time.perf_counter() - start)
            start = time.perf_counter()
            trainer.run_round(k)
            seconds[name].append(time.perf_counter() - start)
    env_steps = envs * settings.round_steps
    median = {name: statistics.median(times) for name, times in seconds.items()}

    def against_default(name: str, with_draw: bool = False) -> float:
        """The median over rounds of the default's round time over ``name``'s."""
        extra = draw_seconds[name] if with_draw else [0.0] * rounds
        ratios = [
            default / (mine + drawn)
            for default, mine, drawn in zip(seconds["default"], seconds[name], extra)
        ]
        return statistics.median(ratios)

    return {
        "envs": envs,
        "round_steps": settings.round_steps,
        "rounds": rounds,
        "threads": threads,
        "seconds_per_round": median,
        "draw_seconds": {name: statistics.median(times) for name, times in draw_seconds.items()},
        "env_steps_per_second": {name: env_steps / t for name, t in median.items()},
        "randomised_against_default": against_default("randomised"),
        "randomised_with_draw_against_default": against_default("randomised", with_draw=True),
        "fleet_against_default": against_default("fleet"),
        "load_average": os.getloadavg()[0],
        "machine": platform.machine(),
        "cpus": os.cpu_count(),
    }


def serve(loop: str, envs: int, rounds: int, threads: int) -> None:
    """Runs one loop's rounds as stdin asks (a round index a line) and answers each with a JSON
    line of its wall and processor seconds (the randomised loop's draw and batch apart)."""
    shipped = load_policy("randomised").training["settings"]
    settings = LowerSettings(num_envs=envs, total_steps=envs * 500 * rounds, seed=shipped["seed"])
    draw = None
    if loop == "randomised":
        settings = dataclasses.replace(
            settings, door_distance=True, blind_forward=True, hold_heading=True
        )
        draw = robot_draw(parse_spec(shipped["randomise"]), shipped["seed"])
    trainer = LowerTrainer(settings, threads=threads)
    print("ready", flush=True)
    for line in sys.stdin:
        # "K" runs round K; "K skip" only draws its robots (what `counted` subtracts).
        k, *skip = line.split()
        k = int(k)
        drawn = 0.0
        if draw is not None:
            start = time.perf_counter()
            trainer.use_robots(draw(k, envs))
            drawn = time.perf_counter() - start
        if skip:
            print(json.dumps({"draw": drawn}), flush=True)
            continue
        wall, cpu = time.perf_counter(), time.process_time()
        trainer.run_round(k)
        wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
        print(json.dumps({"wall": wall, "cpu": cpu, "draw": drawn}), flush=True)


def against_baseline(python: str, envs: int, rounds: int, threads: int) -> dict[str, Any]:
    """This build's randomised rounds against ``python``'s build's default rounds, in turns."""
    args = ["--envs", str(envs), "--rounds", str(rounds), "--threads", str(threads)]
    workers = {
        "randomised": [sys.executable, __file__, "--serve", "randomised", *args],
        "baseline_default": [python, __file__, "--serve", "default", *args],
    }
    procs = {
        name: subprocess.Popen(command, stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
        for name, command in workers.items()
    }
    for proc in procs.values():
        assert proc.stdout is not None and proc.stdout.readline().strip() == "ready"
    times: dict[str, list[dict[str, float]]] = {name: [] for name in procs}
    names = list(procs)
    try:
        for k in range(rounds):
            for name in names if k % 2 == 0 else names[::-1]:
                proc = procs[name]
                assert proc.stdin is not None and proc.stdout is not None
                proc.stdin.write(f"{k}\n")
                proc.stdin.flush()
                times[name].append(json.loads(proc.stdout.readline()))
    finally:
        for proc in procs.values():
            assert proc.stdin is not None
            proc.stdin.close()
            proc.wait()

    def ratio(key: str) -> float:
        """The median over rounds of the baseline's default time over the randomised time."""
        pairs = zip(times["baseline_default"], times["randomised"])
        return statistics.median(base[key] / mine[key] for base, mine in pairs)

    return {
        "envs": envs,
        "rounds": rounds,
        "threads": threads,
        "baseline_python": python,
        "seconds_per_round": {
            name: {key: statistics.median(t[key] for t in ts) for key in ("wall", "cpu")}
            for name, ts in times.items()
        },
        "draw_seconds": statistics.median(t["draw"] for t in times["randomised"]),
        "randomised_against_baseline_default": {key: ratio(key) for key in ("wall", "cpu")},
        "load_average": os.getloadavg()[0],
        "machine": platform.machine(),
        "cpus": os.cpu_count(),
    }


def counted_instructions(python: str, loop: str, envs: int, skip: bool) -> int:
    """Callgrind's instruction total of ``python``'s build serving round 0 of ``loop`` on one
    thread (import and set-up included), or, with ``skip``, everything but the round itself."""
    with tempfile.TemporaryDirectory() as folder:
        out = os.path.join(folder, "callgrind.out")
        command = ["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}", python]
        command += [__file__, "--serve", loop, "--envs", str(envs), "--rounds", "1"]
        command += ["--threads", "1"]
        env = dict(os.environ, OPENBLAS_NUM_THREADS="1")
        stdin = "0 skip\n" if skip else "0\n"
        subprocess.run(command, input=stdin, check=True, capture_output=True, text=True, env=env)
        with open(out, encoding="utf-8") as file:
            totals = [line for line in file if line.startswith(("summary:", "totals:"))]
    return int(totals[0].split()[1])


def counted(baseline: str, envs: int, tolerance: float) -> int:
    """Instructions per env-step of this build's randomised round against ``baseline``'s default
    round (each the count of a round less that of the same run without it); 1 when this build
    needs more than ``tolerance`` (a fraction) more."""
    env_steps = envs * LowerSettings(num_envs=envs).round_steps
    per_step = {}
    runs = (("this", sys.executable, "randomised"), ("base", baseline, "default"))
    for name, python, loop in runs:
        with_round = counted_instructions(python, loop, envs, skip=False)
        without = counted_instructions(python, loop, envs, skip=True)
        per_step[name] = (with_round - without) / env_steps
    mine, theirs = per_step["this"], per_step["base"]
    print(f"lower-level round 0, {envs} robots, one thread, instructions per env-step:")
    print(f"randomised navigator, this build:  {mine:,.0f}")
    print(f"default navigator, the other build: {theirs:,.0f}")
    print(f"ratio (this / other): {mine / theirs:.3f}")
    if mine > theirs * (1.0 + tolerance):
        print(f"this build needs more than {tolerance:.1%} more instructions per env-step")
        return 1
    return 0


def print_against_baseline(result: dict[str, Any]) -> None:
    """The figures of ``against_baseline`` as lines of text."""
    print(
        f"lower-level rounds, {result['envs']} robots x 500 steps, {result['threads']} threads, "
        f"medians of {result['rounds']} rounds"
    )
    labels = {
        "baseline_default": "default, the other build",
        "randomised": "randomised, this build",
    }
    for name, label in labels.items():
        t = result["seconds_per_round"][name]
        print(f"  {label:26} {t['wall']:6.2f} s wall  {t['cpu']:6.2f} s processor a round")
    r = result["randomised_against_baseline_default"]
    print(
        f"  randomised (this build) / default (other build): {r['wall']:.3f}x the speed in wall "
        f"time, {r['cpu']:.3f}x in processor time (the draw apart: {result['draw_seconds']:.2f} s "
        f"a round; load average {result['load_average']:.1f})"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--envs", type=int, default=2048, help="robots (default: 2048)")
    parser.add_argument("--rounds", type=int, default=5, help="rounds of each loop (default: 5)")
    parser.add_argument("--threads", type=int, default=2, help="worker threads (default: 2)")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.add_argument(
        "--baseline-python",
        metavar="PYTHON",
        help="compare this build's randomised rounds with this interpreter's build's default ones",
    )
    parser.add_argument(
        "--instructions",
        nargs="?",
        type=float,
        const=0.01,
        metavar="TOLERANCE",
        help="with --baseline-python: count instructions per env-step of a round under "
        "callgrind; fail above the other build's by more than TOLERANCE (default: 0.01)",
    )
    parser.add_argument("--serve", choices=("default", "randomised"), help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.serve:
        serve(args.serve, args.envs, args.rounds, args.threads)
        return
    if args.baseline_python and args.instructions is not None:
        sys.exit(counted(args.baseline_python, args.envs, args.instructions))
    if args.baseline_python:
        paired = against_baseline(args.baseline_python, args.envs, args.rounds, args.threads)
        if args.json:
            print(json.dumps(paired, indent=2))
        else:
            print_against_baseline(paired)
        return
    result = measure(args.envs, args.rounds, args.threads)
    if args.json:
        print(json.dumps(result, indent=2))
        return
    rate = result["env_steps_per_second"]
    per_round = result["seconds_per_round"]
    print(f"lower-level rounds, {args.envs} robots x 500 steps, {args.threads} threads")
    labels = {
        "default": "default, in the core",
        "randomised": "randomised, in the core",
        "fleet": "fleet of four profiles",
    }
    for name, label in labels.items():
        print(f"  {label:26} {per_round[name]:6.2f} s a round  {rate[name]:12,.0f} env-steps/s")
    drawn = result["draw_seconds"]["randomised"]
    print(
        f"  randomised/default {result['randomised_against_default']:.2f}x the speed "
        f"({result['randomised_with_draw_against_default']:.2f}x with the robots' draw, "
        f"{drawn:.2f} s a round), fleet/default {result['fleet_against_default']:.2f}x "
        f"(medians of the rounds' ratios; load average {result['load_average']:.1f})"
    )


if __name__ == "__main__":
    main()
