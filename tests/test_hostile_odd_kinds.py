"""Hostile inputs of kinds the other hostile tests do not try: numbers of other types where an
int or a float goes (numpy scalars and 0-d arrays, bool, Fraction, Decimal, huge ints), path
objects that raise or give bytes, bytes paths, NUL in paths, folders, FIFOs and /proc files
where a file goes, a full disk (``/dev/full``, a file-size limit), few file descriptors, a
million-cell world, grid maps with tabs, CRLF and a byte-order mark, interrupts and raising or
re-entering callbacks, pickling and copying every public class, threads sharing one
environment, wrappers closed twice and objects used after ``fork``. Each runs in a fresh process
under the caps of ``hostile.py`` and must end in a result or a MazesimError, never another
exception, a crash, a hang or a file left half written; a caller's own exception or interrupt
comes back as it was raised."""

from __future__ import annotations

from pathlib import Path

import pytest

from hostile import run_hostile

#: The tests' folder, whose training settings the training cases import.
TESTS = str(Path(__file__).resolve().parent)

#: A seed-maze simulator, the caller's own exception, a scratch folder and the tests' helpers.
SETUP = f"""
import os, sys, tempfile
sys.path.insert(0, {TESTS!r})
world = mazesim.load_world('seed-maze')
sim = mazesim.Simulator(world, seed=0)
class Mine(Exception):
    pass
folder = tempfile.mkdtemp()
"""

#: A world file with a grid map, its map's lines joined by ``{eol}``.
GRID = (
    SETUP
    + """
rows = ['+--+--+', '|S    |', '+  +--+', '|    G|', '+--+--+']
def grid_world(eol='\\n', prefix='', cell_row=None):
    lines = list(rows) if cell_row is None else [*rows[:1], cell_row, *rows[2:]]
    text = (prefix + 'format = "mazesim-world"' + eol + 'version = 1' + eol + '[grid]' + eol
            + 'map = ' + chr(34) * 3 + eol + eol.join(lines) + eol + chr(34) * 3 + eol)
    return mazesim.World.from_toml(text)
"""
)

#: An env of the suite, and a vector env of two.
ENVS = (
    SETUP
    + """
import gymnasium
from mazesim.envs import EPuckMazeEnv, EPuckMazeVectorEnv
"""
)

#: ENVS, and ``from_threads(step, calls)``: four threads each calling ``step`` ``calls`` times;
#: raises unless each call ended in a result or a MazesimError.
THREADS = (
    ENVS
    + """
import threading
def from_threads(step, calls):
    errors = []
    def drive():
        for _ in range(calls):
            try:
                step()
            except mazesim.MazesimError:
                pass
            except BaseException as e:
                errors.append(e)
    threads = [threading.Thread(target=drive) for _ in range(4)]
    [t.start() for t in threads]; [t.join() for t in threads]
    assert not errors, errors[0]
"""
)

#: One class of each public kind, made, for pickling and copying.
EVERY_CLASS = (
    SETUP
    + """
import copy, pickle
made = [world, sim, mazesim.BatchSimulator(world, num_envs=2),
        mazesim.RobotProfile.builtin('e-puck'),
        mazesim.EpisodeLimits(max_steps=5), mazesim.AvoidCollisionSettings(threshold=70.0),
        mazesim.MazeLayout(cell_size=0.3), mazesim.DrivePerturbation(wheel_radius_scale=1.05),
        mazesim.SensingPerturbation(noise_scale=2.0),
        mazesim.RunSettings(mazesim.EpisodeLimits(), seeds=2),
        mazesim.TabularSettings(np.zeros((4096, 12)), epsilon=0.1)]
def each(how):
    for obj in made:
        try:
            how(obj)
        except mazesim.MazesimError:
            pass
"""
)

#: Runs ``code`` in a child process after setting ``limit`` (a resource) to ``value``.
LIMITED = """
import resource, subprocess, textwrap
def limited(limit, value, code):
    def cap():
        resource.setrlimit(limit, (value, value))
    code = 'import mazesim, os, sys, tempfile\\n' + textwrap.dedent(code)
    done = subprocess.run([sys.executable, '-c', code],
                          preexec_fn=cap, capture_output=True, text=True, timeout=100)
    print('EXIT', done.returncode, done.stderr[-300:])
    if done.returncode != 0 or 'Traceback' in done.stderr and 'MazesimError' not in done.stderr:
        raise AssertionError(f'exit {done.returncode}: {done.stderr[-800:]}')
"""

#: Runs ``mazesim ARGS`` in a child; raises unless it ends as a command should (0, 1 or 2).
COMMAND_LINE = """
import subprocess
def command(*args):
    done = subprocess.run([sys.executable, '-m', 'mazesim', *args], capture_output=True,
                          text=True, timeout=100)
    print('EXIT', done.returncode, done.stderr.strip()[-200:])
    if done.returncode not in (0, 1, 2) or 'Traceback' in done.stderr:
        raise AssertionError(f'exit {done.returncode}: {done.stderr[-600:]}')
"""

#: Runs ``code`` in a forked child; raises unless it ended with status 0 within 60 s.
FORKED = """
import signal, textwrap, time
def forked(code):
    pid = os.fork()
    if pid == 0:
        status = 0
        try:
            exec(textwrap.dedent(code), globals())
        except mazesim.MazesimError:
            pass
        except BaseException:
            import traceback; traceback.print_exc(); status = 3
        os._exit(status)
    for _ in range(600):
        done, status = os.waitpid(pid, os.WNOHANG)
        if done:
            assert status == 0, f'child status {status}'
            return
        time.sleep(0.1)
    os.kill(pid, signal.SIGKILL)
    raise AssertionError('the forked child hung')
"""

CASES: dict[str, str] = {
    # Numbers of other types where an int or a float goes.
    "numpy_int_num_envs": (
        "mazesim.BatchSimulator(mazesim.load_world('seed-maze'), num_envs=np.int64(2))"
    ),
    "zero_d_array_num_envs": (
        "mazesim.BatchSimulator(mazesim.load_world('seed-maze'), num_envs=np.array(2))"
    ),
    "one_item_array_num_envs": (
        "mazesim.BatchSimulator(mazesim.load_world('seed-maze'), num_envs=np.array([2]))"
    ),
    "bool_num_envs": "mazesim.BatchSimulator(mazesim.load_world('seed-maze'), num_envs=True)",
    "fraction_speed": SETUP + "from fractions import Fraction\nsim.step(Fraction(1, 2), 1)",
    "decimal_speed": SETUP + "from decimal import Decimal\nsim.step(Decimal('1.5'), 1)",
    "decimal_nan_speed": SETUP + "from decimal import Decimal\nsim.step(Decimal('sNaN'), 1)",
    "huge_int_seed": SETUP + "mazesim.Simulator(world, seed=10**100)",
    "huge_int_speed": SETUP + "sim.step(10**400, 0)",
    "float16_speed": SETUP + "sim.step(np.float16(1.0), np.float16('inf'))",
    "numpy_bool_seed": SETUP + "sim.reset(seed=np.bool_(True))",
    "fraction_cell_size": (
        "from fractions import Fraction\nmazesim.MazeLayout(cell_size=Fraction(3, 10))"
    ),
    "numpy_negative_max_steps": "mazesim.EpisodeLimits(max_steps=np.int64(-1))",
    "huge_maze_width": "_core.generate_maze(width=2**40, height=2)",
    "zero_d_array_maze": "_core.generate_maze(width=np.array(3), height=np.uint8(3))",
    # Path objects, bytes and NUL where a path goes.
    "path_object_raising": SETUP
    + """
class Raising:
    def __fspath__(self):
        raise Mine('no path')
try:
    mazesim.load_world(Raising())
except Mine:
    pass
""",
    "path_object_giving_int": SETUP
    + """
class Number:
    def __fspath__(self):
        return 5
mazesim.load_world(Number())
""",
    "path_object_giving_bytes": SETUP
    + """
class Bytes:
    def __fspath__(self):
        return os.path.join(folder, 'w.toml').encode()
world.save(Bytes())
mazesim.load_world(Bytes())
""",
    "bytes_world_name": "mazesim.load_world(b'seed-maze')",
    "bytes_save_path": SETUP + "world.save(os.path.join(folder, 'w.toml').encode())",
    "nul_in_save_path": SETUP + "world.save(os.path.join(folder, 'a\\x00b.toml'))",
    "nul_in_profile_path": "mazesim.RobotProfile.load('/tmp/\\x00e-puck.toml')",
    "folder_as_save_target": SETUP + "os.mkdir(os.path.join(folder, 'w.toml'))\n"
    "world.save(os.path.join(folder, 'w.toml'))",
    # Special files where a file goes.
    "fifo_as_world": SETUP + "fifo = os.path.join(folder, 'w.toml'); os.mkfifo(fifo)\n"
    "mazesim.load_world(fifo)",
    "fifo_as_text_world": SETUP + "fifo = os.path.join(folder, 'w.txt'); os.mkfifo(fifo)\n"
    "mazesim.load_world(fifo)",
    "fifo_as_profile": SETUP + "fifo = os.path.join(folder, 'p.toml'); os.mkfifo(fifo)\n"
    "mazesim.RobotProfile.load(fifo)",
    "proc_self_mem_world": "mazesim.load_world('/proc/self/mem')",
    "proc_environ_profile": "mazesim.RobotProfile.load('/proc/self/environ')",
    "dev_null_world": "mazesim.load_world('/dev/null')",
    # A full disk, a file-size limit, few file descriptors.
    "dev_full_save": SETUP + "world.save('/dev/full')",
    "file_size_limit_save": LIMITED
    + """
limited(resource.RLIMIT_FSIZE, 200, '''
try:
    mazesim.load_world('seed-maze').save(os.path.join(tempfile.mkdtemp(), 'w.toml'))
except mazesim.MazesimError as e:
    print('REFUSED', e)
''')
""",
    "file_size_limit_python_writer": LIMITED
    + """
limited(resource.RLIMIT_FSIZE, 200, '''
from mazesim._atomic import atomic_file
path = os.path.join(tempfile.mkdtemp(), 'big.json')
try:
    with atomic_file(path) as out:
        out.write(b'x' * 10000)
except mazesim.MazesimError as e:
    print('REFUSED', e)
left = os.listdir(os.path.dirname(path))
assert not os.path.exists(path) and left == [], left
''')
""",
    "file_size_limit_export_command": LIMITED
    + """
limited(resource.RLIMIT_FSIZE, 100, '''
from mazesim.cli import main
code = main(['worlds', '--export', 'seed-maze', '-o', os.path.join(tempfile.mkdtemp(), 'w.toml')])
assert code in (0, 1, 2), code
''')
""",
    "few_file_descriptors_load": LIMITED
    + """
limited(resource.RLIMIT_NOFILE, 12, '''
try:
    w = mazesim.load_world('seed-maze')
    w.save(os.path.join(tempfile.mkdtemp(), 'w.toml'))
except mazesim.MazesimError as e:
    print('REFUSED', e)
''')
""",
    "few_file_descriptors_threads": LIMITED
    + """
limited(resource.RLIMIT_NOFILE, 12, '''
try:
    b = mazesim.BatchSimulator(mazesim.load_world('seed-maze'), num_envs=64, threads=8)
    b.reset(*b.output_buffers())
except mazesim.MazesimError as e:
    print('REFUSED', e)
''')
""",
    # A world of a million cells.
    "million_cell_maze": "_core.generate_maze(width=1000, height=1000)",
    "million_cell_grid_map": """
row = '+' + '--+' * 1000
cells = '|' + '   ' * 999 + '  |'
text = 'format = "mazesim-world"\\nversion = 1\\n[grid]\\nmap = \\"\\"\\"\\n' + '\\n'.join(
    [row] + [cells, row] * 1000) + '\\n\\"\\"\\"\\n'
mazesim.World.from_toml(text)
""",
    # Grid maps in another dress.
    "grid_map_crlf": GRID + "grid_world('\\r\\n')",
    "grid_map_byte_order_mark": GRID + "grid_world(prefix='\\ufeff')",
    "grid_map_tab_in_row": GRID + "grid_world(cell_row='|S\\t   |')",
    "grid_map_lone_cr": GRID + "grid_world('\\r')",
    "grid_map_nbsp_in_row": GRID + "grid_world(cell_row='|S\\u00a0   |')",
    # Interrupts and callbacks.
    "keyboard_interrupt_in_progress": SETUP
    + """
from mazesim.learn.train import run_training
from training_settings import TINY
def progress(stage, done, total):
    raise KeyboardInterrupt
try:
    run_training(TINY.lower(), TINY.higher(), world, progress=progress)
except KeyboardInterrupt:
    pass
""",
    "curve_callback_raising_own": SETUP
    + """
from mazesim.learn.train import run_training
from training_settings import TINY
def curve(stage, point):
    raise Mine('mine')
try:
    run_training(TINY.lower(), TINY.higher(), world, curve=curve)
    raise AssertionError('the curve was never drawn')
except Mine:
    pass
""",
    "sigint_while_stepping_batch": SETUP
    + """
import signal, threading
batch = mazesim.BatchSimulator(world, num_envs=256)
threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
try:
    for _ in range(200):
        batch.run(50, 'braitenberg', *buffers(batch))
except KeyboardInterrupt:
    pass
batch.reset(*buffers(batch))
""",
    "sigterm_while_saving": SETUP
    + """
import signal, subprocess
path = os.path.join(folder, 'w.toml')
world.save(path)
code = f'''import mazesim
w = mazesim.load_world('seed-maze')
while True:
    w.save({path!r})
'''
child = subprocess.Popen([sys.executable, '-c', code])
import time; time.sleep(2.0)
child.send_signal(signal.SIGTERM); child.wait(timeout=60)
assert mazesim.load_world(path) == world
world.save(path)
assert sorted(os.listdir(folder)) == ['w.toml'], os.listdir(folder)
""",
    "progress_reenters_simulator": SETUP
    + """
from mazesim.learn.train import run_training
from training_settings import TINY
calls = []
def progress(stage, done, total):
    sim.step(1.0, 1.0)
    calls.append(stage)
run_training(TINY.lower(), TINY.higher(), world, progress=progress)
assert calls
""",
    "index_reenters_batch": SETUP
    + """
class Sneaky:
    def __index__(self):
        sim.reset()
        return 0
sim.reset(seed=Sneaky())
""",
    # Pickling and copying every public class.
    "pickle_every_class": EVERY_CLASS + "each(lambda o: pickle.loads(pickle.dumps(o)))",
    "copy_every_class": EVERY_CLASS + "each(copy.copy)",
    "deepcopy_every_class": EVERY_CLASS + "each(copy.deepcopy)",
    "pickle_env": ENVS
    + """
import pickle
env = EPuckMazeEnv(); env.reset(seed=0)
try:
    pickle.loads(pickle.dumps(env)).step(env.action_space.sample())
except mazesim.MazesimError:
    pass
""",
    "deepcopy_vector_env": ENVS
    + """
import copy
envs = EPuckMazeVectorEnv(num_envs=2); envs.reset(seed=0)
try:
    copy.deepcopy(envs).step(envs.action_space.sample())
except mazesim.MazesimError:
    pass
""",
    # Threads sharing one environment.
    "threads_share_env": THREADS
    + """
env = EPuckMazeEnv(); env.reset(seed=0)
def step():
    _, _, ended, cut, _ = env.step(env.action_space.sample())
    if ended or cut:
        env.reset()
from_threads(step, 200)
""",
    "threads_share_vector_env": THREADS
    + """
envs = EPuckMazeVectorEnv(num_envs=3); envs.reset(seed=0)
from_threads(lambda: envs.step(envs.action_space.sample()), 100)
""",
    # Wrappers closed twice, used after closing.
    "wrapper_closed_twice": ENVS
    + """
env = gymnasium.make('mazesim/EPuckMaze-v0'); env.reset(seed=0)
env.close(); env.close()
env.step(env.action_space.sample())
""",
    "vector_wrapper_closed_twice": ENVS
    + """
envs = gymnasium.make_vec('mazesim/EPuckMaze-v0', 2, vectorization_mode='vector_entry_point')
envs.reset(seed=0); envs.close(); envs.close()
envs.step(envs.action_space.sample())
""",
    "record_statistics_closed_twice": ENVS
    + """
from gymnasium.wrappers import RecordEpisodeStatistics, TimeLimit
env = RecordEpisodeStatistics(TimeLimit(EPuckMazeEnv(), 10)); env.reset(seed=0)
env.close(); env.close()
env.reset(seed=1)
""",
    # Objects used after fork.
    "env_after_fork": ENVS
    + FORKED
    + """
env = EPuckMazeEnv(); env.reset(seed=0)
forked('env.step(env.action_space.sample()); env.reset(seed=1)')
env.step(env.action_space.sample())
""",
    "threaded_batch_after_fork": SETUP
    + FORKED
    + """
batch = mazesim.BatchSimulator(world, num_envs=64, threads=2)
batch.reset(*buffers(batch)); batch.run(20, 'braitenberg', *buffers(batch))
forked('''
batch.reset(*buffers(batch)); batch.run(20, "braitenberg", *buffers(batch))
fresh = mazesim.BatchSimulator(world, num_envs=64, threads=2)
fresh.run(20, "braitenberg", *buffers(fresh))
''')
batch.run(20, 'braitenberg', *buffers(batch))
""",
    "vector_env_after_fork": ENVS
    + FORKED
    + """
envs = EPuckMazeVectorEnv(num_envs=4, threads=2); envs.reset(seed=0)
forked('envs.step(envs.action_space.sample()); envs.reset(seed=1)')
""",
    # Values of other types for a registered name.
    "list_for_autoreset_mode": ENVS + "EPuckMazeVectorEnv(num_envs=2, autoreset_mode=['NextStep'])",
    "dict_for_action_mode": ENVS + "EPuckMazeEnv(action_mode={'continuous': 1})",
    "list_for_events": SETUP
    + "from mazesim.episodes import EpisodeBatch\nEpisodeBatch([world], events=['truth'])",
    "list_for_trainer": (
        "from mazesim.distributed.tasks import resolve_trainer\nresolve_trainer(['q'])"
    ),
    "list_for_ros_distro": (
        "from mazesim.ros2.messages import check_distro\ncheck_distro(['humble'])"
    ),
    "list_for_random_stream": "from mazesim._seeding import stream\nstream(0, ['lower/round'], 0)",
    # More numbers, strings and paths of other types.
    "numpy_str_world_name": "mazesim.World.builtin(np.str_('arena'))",
    "numpy_str_robot": SETUP + "mazesim.Simulator(world, robot=np.str_('e-puck'))",
    "zero_d_array_speeds": SETUP + "sim.step(np.array(1.0), np.array([1.0]))",
    "bool_robot_index": SETUP + "sim.distance_sensors(True)",
    "float_maze_width": "_core.generate_maze(width=3.0, height=3)",
    "float_max_steps": "mazesim.EpisodeLimits(max_steps=1e3)",
    "env_seed_numpy_uint64_max": ENVS + "EPuckMazeEnv().reset(seed=np.uint64(2**64 - 1))",
    "env_seed_bool": ENVS + "EPuckMazeEnv().reset(seed=True)",
    "path_object_giving_nul": SETUP
    + """
class Nul:
    def __fspath__(self):
        return os.path.join(folder, 'a\\x00.toml')
world.save(Nul())
""",
    "parent_is_a_file_load": "mazesim.load_world('/etc/passwd/w.toml')",
    "parent_is_a_file_save": SETUP + "world.save('/etc/passwd/w.toml')",
    "save_into_proc": SETUP + "world.save('/proc/self/w.toml')",
    "socket_as_world": SETUP
    + """
import socket
path = os.path.join(folder, 's.toml')
server = socket.socket(socket.AF_UNIX); server.bind(path)
mazesim.load_world(path)
""",
    "export_to_dev_full_command": COMMAND_LINE
    + "command('worlds', '--export', 'seed-maze', '-o', '/dev/full')",
    "long_line_world": "mazesim.World.from_toml(HEADER + 'name = \"' + 'x' * 10_000_000 + '\"')",
    "little_memory_million_cells": LIMITED
    + """
limited(resource.RLIMIT_AS, 700 << 20, '''
row = '+' + '--+' * 1000
cells = '|S' + '   ' * 999 + ' |'
quotes = chr(34) * 3
text = ('format = "mazesim-world"' + chr(10) + 'version = 1' + chr(10) + '[grid]' + chr(10)
        + 'map = ' + quotes + chr(10) + chr(10).join([row] + [cells, row] * 1000) + chr(10)
        + quotes + chr(10))
try:
    mazesim.Simulator(mazesim.World.from_toml(text)).step(1.0, 1.0)
except mazesim.MazesimError as e:
    print('REFUSED', e)
''')
""",
    "list_for_axis_level": """
from mazesim.transfer.axes import AXES
axis = next(a for a in AXES if a.names)
axis.check([axis.names[0]])
""",
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_an_odd_kind_of_hostile_input_ends_in_a_result_or_a_mazesim_error(case: str) -> None:
    outcome = run_hostile(CASES[case])
    assert outcome.ok, outcome.describe()
