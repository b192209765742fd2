"""Running a sweep: every setting as a Ray task, or one after the other in this process.

:func:`run_sweep` submits one Ray task per setting. Each task asks Ray for ``cpus_per_task`` CPUs
and drives its own batch engine with that many threads, so the tasks running at once never ask
for more cores than the cluster has. Results are gathered as the tasks finish: each run's files
go into the output folder (:mod:`mazesim.distributed.output`) and ``results.json`` is rewritten,
so a stopped sweep keeps every finished run.

**Failures.** A task whose worker process dies (killed, out of memory, a crash in native code) is
run again by Ray up to ``max_retries`` times. A task that raises, or that died on every attempt,
is reported as ``failed`` in the summary with the error; the other runs are unaffected.

:func:`run_sequential` runs the same settings with the same task in this process, one after the
other, writing the same output folder; a seeded task gives the same tables both ways.
"""

from __future__ import annotations

import datetime
import os
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from mazesim._atomic import atomic_file
from mazesim._core import __version__
from mazesim._paths import make_output_folder
from mazesim.distributed.cluster import local_cpus, ray_session
from mazesim.distributed.config import Setting, SweepConfig, load_sweep_config
from mazesim.distributed.output import (
    RESULTS_CSV,
    RESULTS_JSON,
    RUNS_DIR,
    SWEEP_PLOT,
    read_finished_run,
    remove_leftovers,
    save_plot,
    write_json,
    write_results_csv,
    write_run_folder,
)
from mazesim.distributed.tasks import Task, TaskOutput, execute_task, train_and_evaluate

__all__ = ["SweepSummary", "run_sequential", "run_sweep"]

Progress = Callable[[str], None]


@dataclass
class SweepSummary:
    """The outcome of a sweep, as written to ``results.json``.

    Attributes:
        out_dir: The output folder.
        runs: One dict per setting, in the sweep's order: its id, group, label, seed, status
            (``"ok"``, ``"failed"`` or ``"pending"``), result fields, folder and error.
        wall_seconds: Wall-clock time of the sweep (without runs reused from an earlier one).
        runner: ``"ray"`` or ``"sequential"``.
    """

    out_dir: str
    runs: list[dict[str, Any]]
    wall_seconds: float = 0.0
    runner: str = "sequential"
    extra: dict[str, Any] = field(default_factory=dict)

    @property
    def failed(self) -> list[dict[str, Any]]:
        """The runs that failed."""
        return [run for run in self.runs if run["status"] == "failed"]

    @property
    def env_steps(self) -> int:
        """Env-steps simulated by the runs of this sweep (training and evaluation)."""
        return sum(
            int(run.get("env_steps") or 0) + int(run.get("eval_env_steps") or 0)
            for run in self.runs
            if run["status"] == "ok" and not run.get("reused")
        )


class _SweepFolder:
    """The output folder of one sweep while it runs."""

    def __init__(self, config: SweepConfig, out_dir: str, runner: str, progress: Progress | None):
        self.config = config
        self.out_dir = out_dir
        self.progress = progress
        self.started = time.perf_counter()
        self.started_at = datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds")
        self.summary = SweepSummary(out_dir=out_dir, runs=[], runner=runner)
        make_output_folder(out_dir, "out_dir")
        remove_leftovers(out_dir)
        with atomic_file(os.path.join(out_dir, "sweep.toml")) as handle:
            handle.write(config.text.encode("utf-8"))
        write_json(
            os.path.join(out_dir, "settings.json"),
            [setting.to_json() for setting in config.settings],
        )
        self.rows: dict[str, dict[str, Any]] = {}
        for setting in config.settings:
            self.rows[setting.id] = {
                "id": setting.id,
                "group": setting.group,
                "label": setting.label,
                "seed": setting.seed,
                "status": "pending",
                "folder": None,
                "error": None,
                "params": dict(setting.params),
            }
        self.summary.runs = list(self.rows.values())
        self.done = 0

    def to_run(self) -> list[Setting]:
        """The settings without a finished run in the folder; the others are marked reused."""
        todo = []
        for setting in self.config.settings:
            result = read_finished_run(self.out_dir, setting)
            if result is None:
                todo.append(setting)
            else:
                row = self.rows[setting.id]
                row.update(result, status="ok", reused=True, folder=f"{RUNS_DIR}/{setting.id}")
                self._report(setting, "reused")
        self.save()
        return todo

    def record(self, setting: Setting, output: TaskOutput) -> None:
        write_run_folder(self.out_dir, setting.id, output.files)
        row = self.rows[setting.id]
        row.update(output.result, status="ok", folder=f"{RUNS_DIR}/{setting.id}")
        row["files"] = sorted(output.files)
        self._report(setting, "ok")
        self.save()

    def record_failure(self, setting: Setting, message: str) -> None:
        row = self.rows[setting.id]
        row.update(status="failed", error=" ".join(message.split())[:2000])
        self._report(setting, "failed")
        self.save()

    def _report(self, setting: Setting, status: str) -> None:
        self.done += 1
        if self.progress is None:
            return
        row = self.rows[setting.id]
        detail = (
            row["error"]
            if status == "failed"
            else (
                f"success {row.get('success_rate') or 0.0:.2f}, "
                f"training {row.get('training_seconds') or 0.0:.1f} s"
            )
        )
        self.progress(
            f"[{self.done}/{len(self.rows)}] {status:<6} {setting.id}  {setting.label}: {detail}"
        )

    def save(self, final: bool = False) -> None:
        """Writes ``results.json``; at the end also ``results.csv`` and the plot."""
        self.summary.wall_seconds = time.perf_counter() - self.started
        runs = self.summary.runs
        document = {
            "sweep": self.config.name,
            "source": self.config.source,
            "runner": self.summary.runner,
            "mazesim_version": __version__,
            "started": self.started_at,
            "wall_seconds": self.summary.wall_seconds,
            "env_steps": self.summary.env_steps,
            "env_steps_per_second": self.summary.env_steps / max(self.summary.wall_seconds, 1e-9),
            "axes": {name: list(values) for name, values in self.config.axes.items()},
            "counts": {
                status: sum(1 for run in runs if run["status"] == status)
                for status in ("ok", "failed", "pending")
            },
            **self.summary.extra,
            "runs": runs,
        }
        write_json(os.path.join(self.out_dir, RESULTS_JSON), document)
        if final:
            write_results_csv(os.path.join(self.out_dir, RESULTS_CSV), runs)
            save_plot(os.path.join(self.out_dir, SWEEP_PLOT), f"sweep {self.config.name}", runs)


def _as_config(config: SweepConfig | str | os.PathLike[str]) -> SweepConfig:
    return config if isinstance(config, SweepConfig) else load_sweep_config(config)


def run_sequential(
    config: SweepConfig | str | os.PathLike[str],
    out_dir: str | os.PathLike[str],
    *,
    task: Task = train_and_evaluate,
    threads: int | None = None,
    progress: Progress | None = None,
) -> SweepSummary:
    """Runs every setting of a sweep in this process, one after the other (no Ray).

    Args:
        config: The sweep, or the path of its file.
        out_dir: The output folder (created if missing); runs already finished there are kept.
        task: The task to run per setting.
        threads: Batch-engine threads (by default the sweep's ``cpus_per_task``).
        progress: Called with one line per finished run.

    Returns:
        The summary, also written to ``OUT/results.json``. A task that raises is reported as
        failed; the other settings still run.
    """
    sweep = _as_config(config)
    folder = _SweepFolder(sweep, os.fspath(out_dir), "sequential", progress)
    for setting in folder.to_run():
        try:
            output = task(setting, threads or sweep.cpus_per_task)
        except Exception as error:  # noqa: BLE001 - a failed run is reported, not fatal
            folder.record_failure(setting, f"{type(error).__name__}: {error}")
        else:
            folder.record(setting, output)
    folder.save(final=True)
    return folder.summary


def run_sweep(
    config: SweepConfig | str | os.PathLike[str],
    out_dir: str | os.PathLike[str],
    address: str | None = None,
    *,
    task: Task = train_and_evaluate,
    cpus: int | None = None,
    progress: Progress | None = None,
) -> SweepSummary:
    """Runs every setting of a sweep as a Ray task and gathers the results into ``out_dir``.

    Args:
        config: The sweep, or the path of its file.
        out_dir: The output folder (created if missing); runs already finished there are kept.
        address: A Ray cluster to join (see :func:`mazesim.distributed.cluster.ray_session`);
            ``None`` starts a local Ray instance for the sweep.
        task: The task to run per setting; it must be importable or picklable on the workers.
        cpus: CPUs of a local Ray instance (by default this machine's cores).
        progress: Called with one line per finished run.

    Returns:
        The summary, also written to ``OUT/results.json``.

    Raises:
        MissingDependencyError: Ray is not installed.
    """
    sweep = _as_config(config)
    folder = _SweepFolder(sweep, os.fspath(out_dir), "ray", progress)
    todo = folder.to_run()
    if not todo:
        folder.save(final=True)
        return folder.summary
    with ray_session(address, cpus or local_cpus()) as ray:
        folder.summary.extra["ray"] = {
            "address": address or "local",
            "cluster_cpus": ray.cluster_resources().get("CPU"),
            "cpus_per_task": sweep.cpus_per_task,
            "max_retries": sweep.max_retries,
        }
        remote = ray.remote(execute_task).options(
            num_cpus=sweep.cpus_per_task, max_retries=sweep.max_retries, retry_exceptions=False
        )
        pending = {remote.remote(task, setting, sweep.cpus_per_task): setting for setting in todo}
        try:
            while pending:
                ready, _ = ray.wait(list(pending), num_returns=1)
                for reference in ready:
                    setting = pending.pop(reference)
                    try:
                        output = ray.get(reference)
                    except ray.exceptions.RayError as error:
                        folder.record_failure(setting, _ray_error_message(error))
                    else:
                        folder.record(setting, output)
        finally:
            for reference in pending:
                ray.cancel(reference, force=True)
            folder.save(final=True)
    return folder.summary


def _ray_error_message(error: Exception) -> str:
    """The useful part of a Ray error: the task's own exception, or why its worker died."""
    cause = getattr(error, "cause", None)
    if isinstance(cause, BaseException):
        return f"{type(cause).__name__}: {cause}"
    lines = [line for line in str(error).splitlines() if line.strip()]
    return f"{type(error).__name__}: {lines[0] if lines else 'no message'}"
