"""Hostile inputs of kinds the other hostile tests do not try: odd Unicode in names and paths,
symbolic-link loops, files that change or never end while read, very deep TOML, huge counts in
Webots world fields, signals during writes, NaN in robot profiles, negative sizes, mazesim's
environment variables set to garbage, no ``HOME``, a read-only working folder. Each runs in a
fresh process under the caps of ``hostile.py`` and must end in a result or a MazesimError (a
command: an exit status of 0, 1 or 2 with no traceback), never another exception, a crash, a
hang or a file left half written."""

from __future__ import annotations

import pytest

from hostile import run_hostile

#: Text of a robot profile with one number replaced (``{}``): the e-puck's, from the core.
PROFILE = "text = mazesim.RobotProfile.builtin('e-puck').to_toml()\n"

#: Runs ``mazesim ARGS`` in a child with ``ENV`` changes (None removes a variable) and ``CWD``,
#: and raises unless it ends as a command should: exit 0, 1 or 2 and no traceback.
COMMAND = """
import os, subprocess
def command(*args, env=None, cwd=None):
    environment = dict(os.environ)
    for name, value in (env or {}).items():
        if value is None:
            environment.pop(name, None)
        else:
            environment[name] = value
    done = subprocess.run([sys.executable, "-m", "mazesim", *args], env=environment, cwd=cwd,
                          capture_output=True, text=True, timeout=100)
    print("EXIT", done.returncode, done.stderr.strip()[-160:])
    if done.returncode not in (0, 1, 2) or "Traceback" in done.stderr:
        raise AssertionError(f"exit {done.returncode}: {done.stderr[-600:]}")
"""

CASES: dict[str, str] = {
    # Odd Unicode in world names and paths.
    "zero_width_name": "mazesim.load_world('seed\\u200b-maze')",
    "fullwidth_name": "mazesim.load_world('\\uff53eed-maze')",
    "nul_in_name": "mazesim.load_world('seed-maze\\x00.toml')",
    "lone_surrogate_name": "mazesim.load_world('seed-\\udcffmaze')",
    "right_to_left_override_path": "mazesim.load_world('/tmp/\\u202elmot.toml')",
    "surrogate_in_save_path": (
        "mazesim.load_world('seed-maze').save('/tmp/h\\udcff-' + str(__import__('os').getpid()))"
    ),
    "decomposed_file_name": """
import os, tempfile, unicodedata
d = tempfile.mkdtemp()
name = unicodedata.normalize('NFD', 'caf\\u00e9.toml')
mazesim.load_world('seed-maze').save(os.path.join(d, name))
mazesim.load_world(os.path.join(d, name))
mazesim.load_world(os.path.join(d, unicodedata.normalize('NFC', 'caf\\u00e9.toml')))
""",
    "newline_in_path": "mazesim.load_world('/tmp/a\\nb.toml')",
    "emoji_robot_name": "mazesim.Simulator(mazesim.load_world('seed-maze'), robot='e-\\U0001f916')",
    "bidi_profile_name": "mazesim.RobotProfile.builtin('\\u202ee-puck')",
    # Symbolic-link loops.
    "link_loop_read": """
import os, tempfile
d = tempfile.mkdtemp(); a, b = os.path.join(d, 'a.toml'), os.path.join(d, 'b.toml')
os.symlink(b, a); os.symlink(a, b)
mazesim.load_world(a)
""",
    "link_loop_save": """
import os, tempfile
d = tempfile.mkdtemp(); a, b = os.path.join(d, 'a.toml'), os.path.join(d, 'b.toml')
os.symlink(b, a); os.symlink(a, b)
mazesim.load_world('seed-maze').save(a)
""",
    "link_loop_atomic": """
import os, tempfile
from mazesim._atomic import atomic_file
d = tempfile.mkdtemp(); a = os.path.join(d, 'self.json')
os.symlink(a, a)
with atomic_file(a) as out:
    out.write(b'{}')
""",
    "link_loop_folder_profile": """
import os, tempfile
d = tempfile.mkdtemp(); loop = os.path.join(d, 'loop')
os.symlink(loop, loop)
mazesim.RobotProfile.load(os.path.join(loop, 'p.toml'))
""",
    "link_loop_policy": """
import os, tempfile
from mazesim.learn import load_policy
d = tempfile.mkdtemp(); loop = os.path.join(d, 'policy')
os.symlink(loop, loop)
load_policy(loop)
""",
    # Files that change while read, or never end.
    "dev_zero_world": "mazesim.load_world('/dev/zero')",
    "dev_urandom_profile": "mazesim.RobotProfile.load('/dev/urandom')",
    "proc_status_world": "mazesim.load_world('/proc/self/status')",
    "growing_world_file": """
import os, tempfile, threading
d = tempfile.mkdtemp(); path = os.path.join(d, 'grow.toml')
mazesim.load_world('seed-maze').save(path)
stop = threading.Event()
def grow():
    with open(path, 'a') as out:
        while not stop.is_set():
            out.write('# more\\n' * 1000); out.flush()
t = threading.Thread(target=grow); t.start()
try:
    for _ in range(20):
        mazesim.load_world(path)
finally:
    stop.set(); t.join()
""",
    "truncated_while_read": """
import os, tempfile, threading
d = tempfile.mkdtemp(); path = os.path.join(d, 'cut.toml')
text = mazesim.load_world('seed-maze').to_toml()
stop = threading.Event()
def churn():
    while not stop.is_set():
        with open(path, 'w') as out:
            out.write(text[: len(text) // 2])
        with open(path, 'w') as out:
            out.write(text)
open(path, 'w').write(text)
t = threading.Thread(target=churn); t.start()
try:
    for _ in range(50):
        try:
            mazesim.load_world(path)
        except mazesim.MazesimError:
            pass
finally:
    stop.set(); t.join()
""",
    "wbt_import_dev_zero": "_core.import_wbt('/dev/zero')",
    # Very deep TOML.
    "deep_arrays_world": "mazesim.World.from_toml(HEADER + 'x = ' + '[' * 100000 + ']' * 100000)",
    "deep_inline_tables_world": (
        "mazesim.World.from_toml(HEADER + 'x = ' + '{a = ' * 50000 + '1' + '}' * 50000)"
    ),
    "deep_dotted_key_world": "mazesim.World.from_toml(HEADER + '.'.join(['a'] * 200000) + ' = 1')",
    "deep_table_header_profile": (
        "mazesim.RobotProfile.from_toml('[' + '.'.join(['a'] * 200000) + ']\\n')"
    ),
    "deep_arrays_settings": """
from mazesim._toml import load_toml
load_toml('x = ' + '[' * 100000 + ']' * 100000, 'deep.toml')
""",
    "deep_arrays_policy_meta": """
import os, tempfile
from mazesim.learn import load_policy
d = tempfile.mkdtemp()
open(os.path.join(d, 'policy.toml'), 'w').write('x = ' + '[' * 100000 + ']' * 100000)
load_policy(d)
""",
    # Huge counts in Webots world fields.
    "wbt_huge_coord_count": """
text = ('#VRML_SIM R2023b utf8\\nWorldInfo { basicTimeStep 32 }\\n'
        'Solid { children [ Shape { geometry IndexedFaceSet { coord Coordinate { point [ '
        + '0 0 0, ' * 2000000 + '] } coordIndex [ ' + '0, ' * 2000000 + '] } } ] }\\n')
_core.import_wbt_text(text)
""",
    "wbt_huge_basic_time_step": (
        "_core.import_wbt_text('#VRML_SIM R2023b utf8\\nWorldInfo { basicTimeStep 1e308 }\\n')"
    ),
    "wbt_huge_subdivision": (
        "_core.import_wbt_text('#VRML_SIM R2023b utf8\\nWorldInfo { basicTimeStep 32 }\\n"
        "Solid { children [ Shape { geometry Cylinder { subdivision 2000000000 } } ] }\\n')"
    ),
    "wbt_huge_floor_tiles": (
        "_core.import_wbt_text('#VRML_SIM R2023b utf8\\nWorldInfo { basicTimeStep 32 }\\n"
        "RectangleArena { floorSize 1e9 1e9 floorTileSize 1e-9 1e-9 }\\n')"
    ),
    "wbt_huge_mf_strings": """
text = ('#VRML_SIM R2023b utf8\\nWorldInfo { basicTimeStep 32 info [ '
        + '"x" ' * 3000000 + '] }\\n')
_core.import_wbt_text(text)
""",
    "wbt_huge_camera": """
text = ('#VRML_SIM R2023b utf8\\nWorldInfo { basicTimeStep 32 }\\n'
        'E-puck { camera_width 2000000000 camera_height 2000000000 }\\n')
_core.import_wbt_text(text)
""",
    # Signals during writes.
    "sigint_during_atomic_write": """
import os, signal, tempfile
from mazesim._atomic import atomic_file
d = tempfile.mkdtemp(); path = os.path.join(d, 'out.bin')
open(path, 'wb').write(b'old')
try:
    with atomic_file(path) as out:
        out.write(b'new' * 1000)
        os.kill(os.getpid(), signal.SIGINT)
        time.sleep(1)
except KeyboardInterrupt:
    pass
assert open(path, 'rb').read() == b'old'
assert sorted(os.listdir(d)) == ['out.bin'], os.listdir(d)
""",
    "sigalrm_during_save": """
import os, signal, tempfile
d = tempfile.mkdtemp(); path = os.path.join(d, 'w.toml')
world = mazesim.load_world('seed-maze')
def tick(*_):
    pass
signal.signal(signal.SIGALRM, tick)
signal.setitimer(signal.ITIMER_REAL, 0.0001, 0.0001)
for _ in range(200):
    world.save(path)
signal.setitimer(signal.ITIMER_REAL, 0)
assert mazesim.load_world(path).to_toml() == world.to_toml()
assert sorted(os.listdir(d)) == ['w.toml'], os.listdir(d)
""",
    "signal_handler_saves_during_save": """
import os, signal, tempfile
d = tempfile.mkdtemp(); path = os.path.join(d, 'w.toml')
world = mazesim.load_world('seed-maze')
busy = []
def save_again(*_):
    # A handler that does not nest: on a loaded machine a save outlasts the 0.5 ms interval,
    # and a handler re-entered by each tick would recurse without end.
    if busy:
        return
    busy.append(True)
    try:
        world.save(path)
    finally:
        busy.pop()
signal.signal(signal.SIGALRM, save_again)
signal.setitimer(signal.ITIMER_REAL, 0.0005, 0.0005)
for _ in range(100):
    world.save(path)
signal.setitimer(signal.ITIMER_REAL, 0)
assert sorted(os.listdir(d)) == ['w.toml'], os.listdir(d)
""",
    # NaN and other absurd numbers in robot profiles.
    "profile_nan_axle": PROFILE + "mazesim.RobotProfile.from_toml(text.replace("
    "'axle_length = ', 'axle_length = nan #', 1))",
    "profile_inf_wheel": PROFILE + "mazesim.RobotProfile.from_toml(text.replace("
    "'wheel_radius = ', 'wheel_radius = inf #', 1))",
    "profile_negative_speed": PROFILE + "mazesim.RobotProfile.from_toml(text.replace("
    "'max_wheel_speed = ', 'max_wheel_speed = -6.28 #', 1))",
    "profile_nan_everywhere": """
import re
text = mazesim.RobotProfile.builtin('e-puck').to_toml()
mazesim.RobotProfile.from_toml(re.sub(r'= [-0-9.e]+', '= nan', text))
""",
    "profile_huge_sensor_count": PROFILE + "mazesim.RobotProfile.from_toml(text + "
    "''.join(f'\\n[[distance_sensors]]\\nname = \"s{i}\"\\n' for i in range(200000)))",
    # Negative sizes.
    "negative_maze": "_core.generate_maze(width=-3, height=5)",
    "negative_num_envs": "mazesim.BatchSimulator(mazesim.load_world('seed-maze'), num_envs=-1)",
    "negative_cell_size": "mazesim.MazeLayout(cell_size=-0.3)",
    "negative_steps_run": "mazesim.EpisodeLimits(max_steps=-5)",
    "negative_render_size": """
from mazesim.render.topdown import TopDownRenderer
TopDownRenderer(mazesim.load_world('seed-maze'), mazesim.RobotProfile.builtin('e-puck'),
                size=(-640, -480))
""",
    "negative_env_maze_size": """
import gymnasium
gymnasium.make('mazesim/UnseenMazeExplore-v0', maze_size=(-5, 5))
""",
    # mazesim's environment variables set to garbage, HOME unset, a read-only working folder.
    "cache_variable_garbage": COMMAND
    + "command('worlds', env={'MAZESIM_CACHE': '\\x01\\udcff' * 3000})",
    "proto_cache_is_a_file": COMMAND
    + "command('import-wbt', '/nonexistent.wbt', env={'MAZESIM_PROTO_CACHE': '/etc/passwd'})",
    "offline_garbage": COMMAND + "command('worlds', env={'MAZESIM_OFFLINE': '\\udcff' * 10})",
    "controller_fd_garbage": COMMAND
    + "command('worlds', env={'MAZESIM_CONTROLLER_FD': '-99999999999999999999'})",
    "ros_graph_garbage": COMMAND + "command('worlds', env={'MAZESIM_ROS_GRAPH': '{{{'})",
    "home_unset_demo": COMMAND
    + "import tempfile\ncommand('demo', '--seconds', '1', '--no-progress', env={'HOME': None}, "
    "cwd=tempfile.mkdtemp())",
    "home_unset_cache": """
import os
os.environ.pop('HOME', None); os.environ.pop('XDG_CACHE_HOME', None)
from mazesim.webots import native_controller
native_controller.cache_folder() if hasattr(native_controller, 'cache_folder') else None
""",
    "home_is_a_file": COMMAND
    + "command('worlds', '--export', 'seed-maze', '-o', '/nonexistent/x.toml', "
    "env={'HOME': '/etc/passwd'})",
    "read_only_cwd_demo": COMMAND
    + """
# (/proc: read-only even for root, who may write into a folder of mode 0o555)
command('demo', '--seconds', '1', '--no-progress', cwd='/proc')
""",
    "read_only_cwd_export": COMMAND
    + """
command('worlds', '--export', 'seed-maze', cwd='/proc')
""",
    "deleted_cwd": COMMAND
    + """
import tempfile
d = tempfile.mkdtemp()
child = subprocess.Popen([sys.executable, '-c', 'import os,sys,time; time.sleep(1);'
    'from mazesim.cli import main; sys.exit(main(["worlds"]))'], cwd=d, stderr=subprocess.PIPE,
    text=True)
os.rmdir(d)
err = child.communicate(timeout=100)[1]
if child.returncode not in (0, 1, 2) or 'Traceback' in err:
    raise AssertionError(err[-600:])
""",
    # Threads of one process writing one file, through the Python writer and the core's: every
    # write ends (a write refused because another thread wrote is a harm too).
    "two_writers_one_file_threads": """
import os, tempfile, threading
from mazesim._atomic import atomic_file
d = tempfile.mkdtemp(); path = os.path.join(d, 'shared.toml')
world = mazesim.load_world('seed-maze')
failed = []
def python_writer():
    for _ in range(30):
        try:
            with atomic_file(path) as out:
                out.write(world.to_toml().encode())
        except mazesim.MazesimError as error:
            failed.append(error)
def core_writer():
    for _ in range(30):
        try:
            world.save(path)
        except mazesim.MazesimError as error:
            failed.append(error)
threads = [threading.Thread(target=f) for f in (python_writer, core_writer) * 3]
[t.start() for t in threads]; [t.join() for t in threads]
assert not failed, f'{len(failed)} of 180 writes failed: {failed[0]}'
assert sorted(os.listdir(d)) == ['shared.toml'], os.listdir(d)
""",
    # Text that is a world file in another dress.
    "byte_order_mark_world": (
        "mazesim.World.from_toml('\\ufeff' + mazesim.load_world('seed-maze').to_toml())"
    ),
    "utf16_world_file": """
import os, tempfile
d = tempfile.mkdtemp(); path = os.path.join(d, 'w.toml')
open(path, 'w', encoding='utf-16').write(mazesim.load_world('seed-maze').to_toml())
mazesim.load_world(path)
""",
    "huge_integer_in_world": (
        "mazesim.World.from_toml(HEADER + 'basic_time_step_ms = ' + '9' * 5000)"
    ),
    # Others: names at and past the file system's limit, a world path that is a folder.
    "name_past_limit": "mazesim.load_world('/tmp/' + 'x' * 300 + '.toml')",
    "save_name_past_limit": "mazesim.load_world('seed-maze').save('/tmp/' + 'y' * 300 + '.toml')",
    "world_path_is_folder": "mazesim.load_world('/tmp/')",
    "profile_path_is_folder": "mazesim.RobotProfile.load('/tmp')",
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_a_fresh_hostile_input_ends_in_a_result_or_a_mazesim_error(case: str) -> None:
    outcome = run_hostile(CASES[case])
    assert outcome.ok, outcome.describe()
