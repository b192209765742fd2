"""Concurrency and signal stress, each case in a child process under a time limit (``hostile.py``):
no call waits for a busy simulator while holding the GIL, re-entrant use is refused or served,
Python's signal handlers never run while a batch holds its lock (they run once it is free), a
forked child never waits for a lock its parent's thread held, and Ctrl-C still stops a long
step and the wait for a busy batch."""

from __future__ import annotations

import textwrap

import pytest

from hostile import run_hostile

#: A batch, and a call on it long enough (about a second or more) that the others meet it busy.
LONG_RUN = """
import os, signal, sys, threading, time
world = mazesim.World.builtin('seed-maze')
batch = _core.BatchSimulator(world, num_envs=64, threads=1)
out = buffers(batch)
def long_run(steps=4000):
    return batch.run(steps, 'braitenberg', *out)
def forked_child():
    # How a child forked now reads the batch: 0 refused as forked, 1 read (the batch was free at
    # the fork), 2 refused for another reason, 'HUNG' (a ceiling of 60 s, half the case's own, so
    # that a hung child is told as one); the child then steps a batch of its own.
    pid = os.fork()
    if pid == 0:
        code = 1
        try:
            batch.steps()
        except mazesim.SimulatorBusyError as e:
            code = 0 if 'forked' in str(e) else 2
        except BaseException:
            code = 3
        try:
            fresh = _core.BatchSimulator(world, num_envs=2)
            fresh.step(np.zeros((2, 2), np.float32), *buffers(fresh))
        finally:
            os._exit(code)
    for _ in range(1200):  # the loop ends with the child
        done, status = os.waitpid(pid, os.WNOHANG)
        if done:
            return os.waitstatus_to_exitcode(status)
        time.sleep(0.05)
    os.kill(pid, signal.SIGKILL)
    return 'HUNG'
def in_long_run(thread):
    # Waits until `thread` is in long_run (True), or has ended (False).
    while thread.is_alive():
        frame = sys._current_frames().get(thread.ident)
        if frame is not None and frame.f_code.co_name == 'long_run':
            return True
        time.sleep(0.01)
    return False
def held_by_another_thread(thread):
    # Waits until `thread` holds the batch (a child forked then finds it held) or has ended.
    while in_long_run(thread):
        if forked_child() == 0:
            return True
    return False
"""


def _run(body: str) -> list[str]:
    outcome = run_hostile(LONG_RUN + textwrap.dedent(body))
    assert outcome.ok, outcome.describe()
    assert "DONE" in outcome.stdout, outcome.describe()
    return outcome.stdout.splitlines()


def test_another_thread_reads_a_stepping_batch_without_a_deadlock() -> None:
    lines = _run(
        """
        seen = []
        running = threading.Event()
        def reader():
            running.wait()
            while runner.is_alive():
                seen.append(int(batch.steps().sum()))
        runner = threading.Thread(target=lambda: (running.set(), long_run()))
        watcher = threading.Thread(target=reader)
        watcher.start(); runner.start(); runner.join(); watcher.join()
        print('READS', len(seen), 'STEPS', int(batch.steps().sum()))
        """
    )
    reads = next(line for line in lines if line.startswith("READS")).split()
    assert int(reads[1]) >= 1 and int(reads[3]) > 0


def test_a_signal_handler_that_reads_the_batch_runs_once_the_batch_is_free() -> None:
    lines = _run(
        """
        seen = []
        def on_alarm(*_):
            seen.append(int(batch.steps().sum()))
            # The timer stops at the first handled alarm: on a starved machine a handler slower
            # than the 10 ms period would otherwise find the next alarm pending each time it
            # returns, and the main thread would never reach the line after the run.
            signal.setitimer(signal.ITIMER_REAL, 0, 0)
        signal.signal(signal.SIGALRM, on_alarm)
        signal.setitimer(signal.ITIMER_REAL, 0.01, 0.01)
        long_run()
        signal.setitimer(signal.ITIMER_REAL, 0, 0)
        total = int(batch.steps().sum())
        print('HANDLED', len(seen), 'ALL_AFTER', all(s == total for s in seen))
        """
    )
    handled = next(line for line in lines if line.startswith("HANDLED")).split()
    assert int(handled[1]) >= 1
    # The handler never saw the batch half-way: it ran when the call had returned.
    assert handled[3] == "True"


def test_ctrl_c_stops_a_long_run_and_its_handler_may_read_the_batch() -> None:
    lines = _run(
        """
        seen = []
        early = []
        stopped = threading.Event()
        def on_ctrl_c(*_):
            steps = int(batch.steps().sum())
            if stopped.is_set():
                return  # pressed again before the presser saw the run stopped
            if steps == 0:
                early.append(steps)  # before the run stepped: the next press waits twice as long
                return
            seen.append(steps)
            stopped.set()
            raise KeyboardInterrupt
        signal.signal(signal.SIGINT, on_ctrl_c)
        def press_until_stopped():  # Ctrl-C until the handler stopped a run that had stepped
            while not stopped.wait(0.05 * 2 ** len(early)):
                os.kill(os.getpid(), signal.SIGINT)
        threading.Thread(target=press_until_stopped, daemon=True).start()
        while True:
            try:
                long_run(10**6)
                print('NOT STOPPED')
                break
            except KeyboardInterrupt:
                if stopped.is_set():
                    print('STOPPED', len(seen), int(batch.steps().max()))
                    break
                # stopped before its first step, which the handler let pass: run again
        """
    )
    stopped = next(line for line in lines if line.startswith(("STOPPED", "NOT"))).split()
    assert stopped[0] == "STOPPED"
    assert int(stopped[1]) == 1 and 0 < int(stopped[2]) < 10**6


def test_ctrl_c_ends_the_wait_for_a_batch_busy_on_another_thread() -> None:
    lines = _run(
        """
        batch.steps()  # made here, before any fork: the extension's own once-made state
        # 2.5 million env-steps: a second or more, however quiet the machine.
        runner = threading.Thread(target=long_run, args=(40000,))
        runner.start()
        print('HELD', held_by_another_thread(runner))
        main = threading.get_ident()
        def wait_for_the_batch():
            return batch.steps()
        def press_once_waiting():  # Ctrl-C once the main thread is in the wait
            while sys._current_frames()[main].f_code.co_name != 'wait_for_the_batch':
                time.sleep(0.01)
            os.kill(os.getpid(), signal.SIGINT)
        threading.Thread(target=press_once_waiting, daemon=True).start()
        started = time.monotonic()
        try:
            wait_for_the_batch()
            print('WAITED', runner.is_alive())
        except KeyboardInterrupt:
            print('INTERRUPTED', runner.is_alive(), round(time.monotonic() - started, 2))
        runner.join()
        """
    )
    assert "HELD True" in lines, lines
    line = next(line for line in lines if line.startswith(("WAITED", "INTERRUPTED"))).split()
    # Still running when Ctrl-C came: the wait ended, not the other thread's call.
    assert line[:2] == ["INTERRUPTED", "True"], line


def test_a_property_of_an_argument_may_read_the_same_simulator() -> None:
    lines = _run(
        """
        sim = mazesim.Simulator(world)
        class Sneaky:
            @property
            def dtype(self):
                return sim.pose
            shape = (11,)
        high = np.full(11, 5000.0, np.float32)
        try:
            sim.step_observe(1.0, 1.0, Sneaky(), high)
            print('ACCEPTED')
        except mazesim.InvalidArgumentError as e:
            print('REFUSED_ARG', 'low' in str(e))
        """
    )
    assert "REFUSED_ARG True" in lines


@pytest.mark.parametrize("threads", [1, 2])
def test_a_forked_child_refuses_a_batch_its_parent_was_stepping(threads: int) -> None:
    lines = _run(
        f"""
        batch = _core.BatchSimulator(world, num_envs=64, threads={threads})
        out = buffers(batch)
        batch.steps()  # made here, before any fork: the extension's own once-made state
        # 2.5 million env-steps: a second or more, however quiet the machine.
        runner = threading.Thread(target=long_run, args=(40000,))
        runner.start()
        # A child forked before the runner took the batch reads it (1): fork again until one is
        # forked while the runner holds it, or the runner has ended.
        code = 1
        while code == 1 and in_long_run(runner):
            code = forked_child()
        runner.join()
        print('CHILD', code)
        batch.steps()
        """
    )
    assert "CHILD 0" in lines, lines


def test_the_import_makes_numpy_s_once_made_state_before_any_thread_can() -> None:
    # numpy's C API and the array borrow registry are each made once, on first use; a child
    # forked while another thread was making one would wait for it for ever. The import makes
    # them while it holds the interpreter alone: the registry (a capsule in numpy's multiarray
    # module) is there before any array went through the extension.
    import subprocess
    import sys

    code = textwrap.dedent(
        """
        import importlib, numpy
        major = int(numpy.__version__.split('.')[0])
        package = 'numpy._core' if major >= 2 else 'numpy.core'
        multiarray = importlib.import_module(package + '.multiarray')
        key = '_RUST_NUMPY_BORROW_CHECKING_API'
        print('BEFORE', hasattr(multiarray, key))
        import mazesim._core
        print('AFTER', hasattr(multiarray, key))
        """
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=600, check=True
    ).stdout.split()
    assert out == ["BEFORE", "False", "AFTER", "True"], out
