"""Hostile inputs of kinds the other hostile tests do not try: arrays in other dresses (big-endian,
structured, read-only, reversed, memory-mapped, of objects, complex numbers, dates or text),
number-likes whose conversion raises an interrupt or lies about their length, text subclasses,
gymnasium envs misused (before reset, after close, actions of other shapes and dtypes), threads
sharing one simulator, world and Webots files in other encodings and line ends, with duplicate
keys and look-alike characters, outputs past a dangling link or with a trailing slash, standard
input and files renamed while read, and the command line with junk flags, junk environment
variables and a standard output that is full, closed or a broken pipe. Each runs in a fresh
process under the caps of ``hostile.py`` and must end in a result or a MazesimError (a command:
an exit status of 0, 1 or 2 with no traceback), never another exception, a crash, a hang or a
file lost or left half written; an accepted value must give the result its plain equivalent
gives, and a caller's own interrupt comes back as it was raised."""

from __future__ import annotations

import pytest

from hostile import run_hostile

#: A seed-maze world and simulator, a batch of four and a twin, each with its reset buffers.
BATCH = """
import os, tempfile
world = mazesim.load_world('seed-maze')
sim = mazesim.Simulator(world, seed=0)
folder = tempfile.mkdtemp()
batch = mazesim.BatchSimulator(world, num_envs=4, seeds=0)
twin = mazesim.BatchSimulator(world, num_envs=4, seeds=0)
out, twin_out = buffers(batch), buffers(twin)
batch.reset(*out); twin.reset(*twin_out)
actions = np.array([[3.0, 2.0], [1.0, -1.0], [0.5, 6.0], [-2.0, -2.0]], np.float32)
def same():
    assert all(np.array_equal(a, b) for a, b in zip(out, twin_out)), 'another result'
"""

#: An env of the suite, made through gymnasium, and a vector env of two.
ENVS = """
import gymnasium
import mazesim.envs
env = gymnasium.make('mazesim/EPuckMaze-v0')
def vector():
    return gymnasium.make_vec('mazesim/EPuckMaze-v0', num_envs=2,
                              vectorization_mode='vector_entry_point')
"""

#: A small Webots world (an e-puck and one wall) and its text with another line end.
WBT = '''
from mazesim._core import import_wbt_text
WBT = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 16 }
E-puck { translation -0.3 0 0 controller "x" }
Solid {
  translation 0 0 0.05
  children [ Shape { geometry DEF W Box { size 0.05 0.6 0.1 } } ]
  boundingObject USE W
}
"""
plain, _ = import_wbt_text(WBT)
'''

#: Runs ``mazesim ARGS`` in a child with ``env`` changes, ``stdout`` and ``preexec``; raises
#: unless it ends as a command should (0, 1 or 2, no traceback); returns its stderr.
COMMAND = """
import os, subprocess, tempfile
folder = tempfile.mkdtemp()
def command(*args, env=None, stdout=subprocess.PIPE, preexec=None, codes=(0, 1, 2)):
    environment = dict(os.environ)
    environment.update(env or {})
    done = subprocess.run([sys.executable, '-m', 'mazesim', *args], env=environment,
                          stdout=stdout, stderr=subprocess.PIPE, preexec_fn=preexec,
                          stdin=subprocess.DEVNULL, timeout=100)
    err = done.stderr.decode('utf-8', 'replace')
    print('EXIT', done.returncode, err.strip()[-200:])
    if done.returncode not in codes or 'Traceback' in err:
        raise AssertionError(f'exit {done.returncode}: {err[-600:]}')
    return err
"""

CASES: dict[str, str] = {
    # Arrays in other dresses, through the batch API: refused, or read as their plain twin.
    "big_endian_actions": BATCH
    + "twin.step(actions, *twin_out)\nbatch.step(actions.astype('>f4'), *out)\nsame()",
    "big_endian_observations": BATCH
    + """
twin.step(actions, *twin_out)
swapped = out[0].astype('>f4')
batch.step(actions, swapped, *out[1:])
out = (swapped.astype('<f4'), *out[1:])
same()
""",
    "structured_actions": BATCH + "batch.step(np.zeros(4, dtype=[('l', 'f4'), ('r', 'f4')]), *out)",
    "read_only_actions": BATCH
    + "twin.step(actions, *twin_out)\nactions.setflags(write=False)\nbatch.step(actions, *out)\n"
    "same()",
    "reversed_view_actions": BATCH
    + """
backwards = actions[::-1].copy()
twin.step(actions, *twin_out)
batch.step(backwards[::-1], *out)
same()
""",
    "memory_mapped_actions": BATCH
    + """
mapped = np.memmap(os.path.join(folder, 'a.bin'), np.float32, 'w+', shape=(4, 2))
mapped[:] = actions
twin.step(actions, *twin_out)
batch.step(mapped, *out)
same()
""",
    "object_actions": BATCH + "batch.step(actions.astype(object), *out)",
    "complex_actions": BATCH + "batch.step(actions.astype(np.complex64), *out)",
    "datetime_actions": BATCH + "batch.step(np.zeros((4, 2), 'datetime64[s]'), *out)",
    "text_actions": BATCH + "batch.step(np.full((4, 2), '1.0'), *out)",
    "zero_d_actions": BATCH + "batch.step(np.array(1.0, np.float32), *out)",
    "nested_list_actions": BATCH
    + "twin.step(actions, *twin_out)\nbatch.step(actions.tolist(), *out)\nsame()",
    "int_mask_reset": BATCH
    + """
twin.step(actions, *twin_out); batch.step(actions, *out)
twin.reset(*twin_out, mask=np.array([True, False, True, False]))
batch.reset(*out, mask=np.array([1, 0, 1, 0]))
same()
""",
    "negative_seeds_reset": BATCH + "batch.reset(*out, seeds=np.array([-1, -2, -3, -4]))",
    "float_seeds_reset": BATCH + "batch.reset(*out, seeds=np.array([0.5, 1.5, 2.5, 3.5]))",
    "duplicate_env_indices": BATCH
    + """
start = np.array(world.start, np.float64)
batch.set_starts_at(np.array([1, 1]), np.stack([start, start + [0.01, 0, 0]]))
""",
    "largest_uint64_env_index": BATCH
    + "batch.set_starts_at(np.array([2**64 - 1], np.uint64), np.array([world.start]))",
    "int_starts": BATCH + "batch.set_starts(np.zeros((4, 3), np.int64))",
    "no_robot_commands": BATCH + "sim.step_robots(np.zeros((0, 2)))",
    "long_double_speeds": BATCH
    + """
other = mazesim.Simulator(world, seed=0)
other.step(1.5, 2.5)
sim.step(np.longdouble(1.5), np.longdouble(2.5))
assert sim.pose == other.pose, (sim.pose, other.pose)
""",
    "snapshot_as_memoryview": BATCH
    + "sim.step(1.0, 1.0)\nsnap = sim.snapshot()\nsim.step(2.0, 1.0)\n"
    "sim.restore(memoryview(snap))\nassert sim.snapshot() == snap",
    "snapshot_of_another_world": BATCH
    + "sim.restore(mazesim.Simulator(mazesim.load_world('arena'), seed=0).snapshot())",
    # Number-likes and text subclasses.
    "int_enum_num_envs": """
import enum
class Size(enum.IntEnum):
    TWO = 2
assert mazesim.BatchSimulator(mazesim.load_world('arena'), num_envs=Size.TWO).num_envs == 2
""",
    "interrupt_from_index": BATCH
    + """
class Interrupting:
    def __index__(self):
        raise KeyboardInterrupt
try:
    sim.reset(seed=Interrupting())
    raise AssertionError('the interrupt was lost')
except KeyboardInterrupt:
    pass
""",
    "interrupt_from_float": BATCH
    + """
class Interrupting:
    def __float__(self):
        raise KeyboardInterrupt
try:
    sim.step(Interrupting(), 0.0)
    raise AssertionError('the interrupt was lost')
except KeyboardInterrupt:
    pass
""",
    "float_giving_text": BATCH
    + """
class Texty:
    def __float__(self):
        return 'fast'
sim.step(Texty(), 0.0)
""",
    "seeds_lying_about_length": BATCH
    + """
class Liar(list):
    def __len__(self):
        return 10**12
mazesim.BatchSimulator(world, num_envs=2, seeds=Liar([1, 2]))
""",
    "generator_seeds": BATCH
    + "mazesim.BatchSimulator(world, num_envs=2, seeds=(s for s in range(2)))",
    "view_of_worlds": BATCH
    + "mazesim.BatchSimulator({0: world, 1: mazesim.load_world('arena')}.values(), num_envs=2)",
    "dict_of_robots": BATCH + "mazesim.BatchSimulator(world, num_envs=2, robot={'e-puck': 1})",
    "text_subclass_name": """
class Named(str):
    def __str__(self):
        return 'arena'
assert mazesim.load_world(Named('seed-maze')).name == 'seed-maze'
""",
    "text_subclass_equal_to_all": """
class Equal(str):
    def __eq__(self, other):
        return True
    __hash__ = str.__hash__
mazesim.load_world(Equal('no-such-world'))
raise AssertionError('a world that does not exist was loaded')
""",
    # Gymnasium envs misused.
    "env_step_before_reset": ENVS
    + "from mazesim.envs import EPuckMazeEnv\nEPuckMazeEnv().step(env.action_space.sample())",
    "env_action_of_another_shape": ENVS + "env.reset(seed=0)\nenv.step(np.zeros((7, 3)))",
    "env_action_of_text": ENVS + "env.reset(seed=0)\nenv.step('forward')",
    "env_step_after_close": ENVS
    + "env.reset(seed=0)\nenv.close()\nenv.step(env.action_space.sample())",
    "env_seed_float": ENVS + "env.reset(seed=3.0)",
    "env_unknown_option": ENVS + "env.reset(seed=0, options={'no_such_option': 1})",
    "make_unknown_keyword": ENVS + "gymnasium.make('mazesim/EPuckMaze-v0', no_such_keyword=1)",
    "make_junk_render_mode": ENVS + "gymnasium.make('mazesim/EPuckMaze-v0', render_mode='holo')",
    "vector_actions_for_three": ENVS
    + """
vec = vector()
vec.reset(seed=0)
vec.step(np.stack([vec.single_action_space.sample() for _ in range(3)]))
""",
    "vector_step_after_close": ENVS
    + "vec = vector()\nvec.reset(seed=0)\nvec.close()\nvec.step(vec.action_space.sample())",
    "vector_big_endian_actions": ENVS
    + """
vec, other = vector(), vector()
vec.reset(seed=0); other.reset(seed=0)
action = np.asarray(vec.action_space.sample())
if action.dtype.kind == 'f':
    expected = other.step(action)[0]
    got = vec.step(action.astype(action.dtype.newbyteorder('>')))[0]
    assert np.array_equal(got, expected)
""",
    "observation_written_by_the_caller": ENVS
    + """
other = gymnasium.make('mazesim/EPuckMaze-v0')
first, _ = env.reset(seed=0)
other.reset(seed=0)
first[...] = 1e9
action = env.action_space.sample()
assert np.array_equal(env.step(action)[0], other.step(action)[0])
""",
    "world_sampler_interrupted": """
import gymnasium, mazesim.envs
def sampler(rng):
    raise KeyboardInterrupt
try:
    gymnasium.make('mazesim/EPuckMaze-v0', world=sampler).reset(seed=0)
    raise AssertionError('the interrupt was lost')
except KeyboardInterrupt:
    pass
""",
    "threads_step_and_restore_one_simulator": BATCH
    + """
import threading
snap = sim.snapshot()
errors = []
def drive(work):
    for _ in range(200):
        try:
            work()
        except mazesim.MazesimError:
            pass
        except BaseException as e:
            errors.append(e)
works = [lambda: sim.step(1.0, 2.0), lambda: sim.restore(snap), lambda: sim.snapshot(),
         lambda: sim.distance_sensors()]
threads = [threading.Thread(target=drive, args=(w,)) for w in works]
[t.start() for t in threads]; [t.join() for t in threads]
assert not errors, errors[0]
""",
    # World and Webots files in other dresses.
    "world_duplicate_key": "mazesim.World.from_toml(HEADER + 'version = 1\\n')",
    "world_duplicate_table": (
        "text = mazesim.load_world('arena').to_toml()\n"
        'mazesim.World.from_toml(text + \'\\n[robot]\\nname = "x"\\n[robot]\\nname = "y"\\n\')'
    ),
    "world_key_in_look_alike_letters": (
        "mazesim.World.from_toml(HEADER + '[[w\\u0430lls]]\\ncenter = [0, 0]\\nsize = [1, 1]\\n')"
    ),
    "world_format_in_look_alike_hyphen": (
        "mazesim.World.from_toml('format = \"mazesim\\u2010world\"\\nversion = 1\\n')"
    ),
    "world_date_for_a_number": (
        "mazesim.World.from_toml(HEADER + 'basic_time_step_ms = 1979-05-27T07:32:00Z\\n')"
    ),
    "world_in_crlf": """
world = mazesim.load_world('seed-maze')
assert mazesim.World.from_toml(world.to_toml().replace('\\n', '\\r\\n')) == world
""",
    "profile_with_mark_and_crlf": """
profile = mazesim.RobotProfile.builtin('e-puck')
text = '\\ufeff' + profile.to_toml().replace('\\n', '\\r\\n')
assert mazesim.RobotProfile.from_toml(text) == profile
""",
    "wbt_with_mark": WBT + "assert import_wbt_text('\\ufeff' + WBT)[0] == plain",
    "wbt_in_crlf": WBT + "assert import_wbt_text(WBT.replace('\\n', '\\r\\n'))[0] == plain",
    "wbt_file_in_utf16": WBT
    + """
import os, tempfile
path = os.path.join(tempfile.mkdtemp(), 'w.wbt')
open(path, 'w', encoding='utf-16').write(WBT)
_core.import_wbt(path)
""",
    "wbt_with_nul": WBT + "import_wbt_text(WBT.replace('Solid', 'So\\x00lid'))",
    "wbt_use_before_def": WBT
    + "import_wbt_text(WBT.replace('boundingObject USE W', 'boundingObject USE NOWHERE'))",
    # Outputs and inputs on odd paths.
    "save_with_trailing_slash": BATCH + "world.save(os.path.join(folder, 'w.toml') + '/')",
    "save_through_dangling_link": BATCH
    + """
link, target = os.path.join(folder, 'link.toml'), os.path.join(folder, 'target.toml')
os.symlink(target, link)
try:
    world.save(link)
except mazesim.MazesimError:
    assert os.path.islink(link) and not os.path.exists(target)
else:
    assert os.path.islink(link) and mazesim.load_world(target) == world
""",
    "world_from_silent_standard_input": """
import subprocess
code = ('import mazesim\\ntry:\\n    mazesim.load_world("/dev/stdin")\\n'
        'except mazesim.MazesimError as e:\\n    print(e)')
child = subprocess.Popen([sys.executable, '-c', code], stdin=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True)
try:
    err = child.communicate(timeout=60)[1]
except subprocess.TimeoutExpired:
    child.kill()
    raise AssertionError('reading a standard input that never ends hung')
assert child.returncode == 0 and 'Traceback' not in err, err
""",
    "world_file_renamed_over_while_read": """
import os, tempfile, threading
d = tempfile.mkdtemp(); path = os.path.join(d, 'w.toml')
worlds = [mazesim.load_world('seed-maze'), mazesim.load_world('arena')]
for i, w in enumerate(worlds):
    w.save(os.path.join(d, f'{i}.toml'))
worlds[0].save(path)
stop = threading.Event()
def swap():
    i = 0
    while not stop.is_set():
        i += 1
        os.link(os.path.join(d, f'{i % 2}.toml'), path + '.new')
        os.replace(path + '.new', path)
mover = threading.Thread(target=swap); mover.start()
try:
    for _ in range(100):
        assert mazesim.load_world(path) in worlds
finally:
    stop.set(); mover.join()
""",
    # The command line: junk flags, junk environment, odd standard outputs.
    "command_seed_in_other_digits": COMMAND
    + "command('demo', '--seconds', '1', '--seed', '\\u0661\\u0662', '--out', folder)",
    "command_argument_of_100000_characters": COMMAND
    + "err = command('show', 'x' * 100000)\nassert len(err) < 20000, len(err)",
    "command_undecodable_argument": """
import subprocess
done = subprocess.run([sys.executable, '-m', 'mazesim', 'show', b'\\xff\\xfe.toml'],
                      capture_output=True, timeout=100)
err = done.stderr.decode('utf-8', 'replace')
assert done.returncode in (1, 2) and 'Traceback' not in err, err[-600:]
""",
    "command_output_to_a_full_device": COMMAND
    + "err = command('worlds', stdout=open('/dev/full', 'w'))\n"
    "assert 'the standard output: No space left' in err, err",
    "command_output_closed": COMMAND
    + "command('worlds', stdout=subprocess.DEVNULL, preexec=lambda: os.close(1))",
    "command_output_to_a_broken_pipe": COMMAND
    + """
read, write = os.pipe()
os.close(read)
command('worlds', stdout=write, codes=(0, 141))
""",
    "command_ascii_output_unicode_path": COMMAND
    + "command('worlds', '--export', 'seed-maze', '-o', os.path.join(folder, 'w\\u00f6rld.toml'), "
    "env={'PYTHONIOENCODING': 'ascii'})",
    "command_junk_matplotlib_backend": COMMAND
    + "command('show', 'arena', '-o', os.path.join(folder, 'a.png'), "
    "env={'MPLBACKEND': 'no-such'})",
    "command_junk_rayon_threads": COMMAND
    + "command('demo', '--seconds', '1', '--out', folder, env={'RAYON_NUM_THREADS': '1e9'})",
    "command_junk_columns": COMMAND
    + "command('show', '--help', env={'COLUMNS': '-7', 'LINES': 'many'})",
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_an_input_in_another_dress_ends_in_a_result_or_a_mazesim_error(case: str) -> None:
    outcome = run_hostile(CASES[case])
    assert outcome.ok, outcome.describe()
