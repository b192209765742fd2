"""What an evaluation reports, as text: the summary and the per-step trace of episode 0.

Both return strings; the commands print them or write them to files (:mod:`mazesim.cli`).
"""

from __future__ import annotations

from collections.abc import Sequence

from mazesim._core import World
from mazesim.batch import CONTROL_STEP_MS
from mazesim.learn.summary import Summary

__all__ = ["summary_text", "trace_text"]


def trace_text(lines: Sequence[str], world: World, seed: int, events: str) -> str:
    """The trace file of episode 0: its header, then ``lines`` (one step or event each)."""
    header = [
        f"# mazesim navigator trace: world {world.name}, episode 0 of seed {seed}, "
        f"checkpoint events from the {'ground truth' if events == 'truth' else 'robust decoder'}",
        "# levels: Table 4.1 levels of the sensors front, back, left, right, left-front, "
        "right-front (0: < 7 cm, 1: < 13, 2: < 20, 3: farther)",
        "# sub-task: CC Corridors and Corners, R / L right / left turn on a door, "
        "F going forward on a door; then its phase (a navigator trained with --door-distance: "
        "heading phase + 3 x distance bin)",
        "# time_s: simulated seconds; x, y: metres; yaw: degrees, counter-clockwise from +x",
        "# step  time_s      x      y    yaw  levels              state  sub-task  action",
    ]
    return "\n".join([*header, *lines]) + "\n"


def summary_text(summary: Summary, label: str) -> str:
    """A summary as text, under the heading ``label``."""
    ratio = "n/a" if summary.mean_path_ratio is None else f"{summary.mean_path_ratio:.2f}"
    steps = "n/a" if summary.mean_steps is None else f"{summary.mean_steps:.0f}"
    text = (
        f"{label}\n"
        f"  episodes            {summary.episodes}\n"
        f"  success rate        {100.0 * summary.success_rate:.1f}%\n"
        f"  without collision   {100.0 * summary.collision_free_rate:.1f}%\n"
        f"  mean collisions     {summary.mean_collisions:.3f}\n"
        f"  mean steps          {steps} (arrived episodes; {CONTROL_STEP_MS:.0f} ms each)\n"
        f"  mean path ratio     {ratio} (steps / shortest-path steps)\n"
    )
    if len(summary.world_success) > 1:
        always = sum(1 for rate in summary.world_success if rate == 1.0)
        never = sum(1 for rate in summary.world_success if rate == 0.0)
        text += (
            f"  worlds              {len(summary.world_success)}: every episode reached the goal "
            f"in {always}, none in {never}\n"
        )
    if summary.decisions:
        text += "  decisions at checkpoint events (event: sub-task x times)\n"
        for event, counts in summary.decisions.items():
            chosen = ", ".join(f"{code} x{count}" for code, count in counts.items())
            text += f"    {event:>4}: {chosen}\n"
    return text
