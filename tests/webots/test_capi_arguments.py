"""A C or C++ controller's bad arguments and misuses get what Webots' own controller library
gives (its message on stderr, the function's default answer) and the controller goes on, as in
Webots: never an end worded by mazesim."""

from __future__ import annotations

from pathlib import Path

import pytest

import mazesim
from mazesim.webots import ControllerRun, native_link, run_controller
from mazesim.webots.native_controller import CAPI
from native_controllers import NEEDS_COMPILERS, write_source

pytestmark = [NEEDS_COMPILERS, pytest.mark.usefixtures("own_cache")]

INCLUDES = "".join(
    f"#include <{name}.h>\n"
    for name in ("math", "stdio", "stdlib", "string", "webots/robot", "webots/device",
                 "webots/emitter", "webots/receiver", "webots/motor", "webots/distance_sensor",
                 "webots/camera", "webots/led", "webots/supervisor")
)  # fmt: skip


def run_c(
    capfd: pytest.CaptureFixture[str], folder: Path, body: str, seconds: float = 0.5
) -> tuple[ControllerRun, list[str], list[str]]:
    """Runs on the arena a C controller whose ``main`` runs ``body``; the run and the lines it
    printed on stdout and on stderr."""
    source = write_source(
        folder,
        "hostile",
        f"{INCLUDES}int main(void) {{\n  wb_robot_init();\n{body}\n"
        "  wb_robot_cleanup();\n  return 0;\n}\n",
    )
    run = run_controller(source, mazesim.load_world("arena"), seconds=seconds)
    out, err = capfd.readouterr()
    return run, out.splitlines(), err.splitlines()


def test_emitter_send_refuses_null_data_and_sizes_as_webots_and_goes_on(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    run, out, err = run_c(
        capfd,
        tmp_path,
        '  WbDeviceTag emitter = wb_robot_get_device("emitter");\n'
        '  printf("null %d\\n", wb_emitter_send(emitter, NULL, 10));\n'
        '  printf("negative %d\\n", wb_emitter_send(emitter, "abc", -5));\n'
        '  printf("empty %d\\n", wb_emitter_send(emitter, "abc", 0));\n'
        "  char *big = calloc(1, 100000000);\n"
        '  printf("huge %d\\n", wb_emitter_send(emitter, big, 100000000));\n'
        '  printf("large %d\\n", wb_emitter_send(emitter, big, 20000000));\n'
        '  printf("sent %d\\n", wb_emitter_send(emitter, "abc", 3));\n'
        '  printf("step %d\\n", wb_robot_step(32));',
    )
    assert (run.exit_status, run.error, run.steps) == (0, "", 1)
    assert out == ["null 0", "negative 0", "empty 0", "huge 0", "large 0", "sent 1", "step 0"]
    # Webots' emitter.c checks data, then size, before the tag.
    assert err[:3] == [
        "Error: wb_emitter_send(): invalid argument: data = NULL.",
        "Error: wb_emitter_send(): invalid size=-5 argument.",
        "Error: wb_emitter_send(): invalid size=0 argument.",
    ]
    # Webots queues any packet an unlimited buffer holds; mazesim bounds them (the link's
    # bound, then the emitter's of an unlimited buffer), refused in Webots' form.
    assert err[3].startswith("Error: wb_emitter_send(): invalid size=100000000 argument: ")
    assert err[4].startswith("Error: wb_emitter_send(): Emitter.send: packet refused: ")
    assert len(err) == 5


def test_a_negative_step_is_an_unsigned_duration_that_lasts_to_the_runs_end(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    # Webots' library sends the duration as an unsigned 32-bit count of ms, without a message:
    # -5 asks for 2^32 - 5 ms, a step that outlasts the run.
    run, out, err = run_c(
        capfd,
        tmp_path,
        '  printf("first %d\\n", wb_robot_step(32));\n'
        "  int negative = wb_robot_step(-5);\n"
        '  printf("negative %d at %.3f\\n", negative, wb_robot_get_time());\n'
        '  printf("after %d\\n", wb_robot_step(32));',
        seconds=0.5,
    )
    assert (run.exit_status, run.error, run.steps) == (0, "", 16)
    # The step after the one that returned -1 ends the controller, as in Webots.
    assert out == ["first 0", "negative -1 at 0.512"]
    assert err == []


def test_a_second_cpp_robot_ends_the_controller_with_webots_message(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    source = write_source(
        tmp_path,
        "twice",
        "#include <cstdio>\n#include <webots/Robot.hpp>\n#include <webots/Supervisor.hpp>\n"
        "int main() {\n  webots::Robot *robot = new webots::Robot();\n"
        '  printf("step %d\\n", robot->step(32));\n'
        "  webots::Supervisor *other = new webots::Supervisor();\n"
        '  printf("second %d\\n", other != 0);\n  delete robot;\n  return 0;\n}\n',
        ".cpp",
    )
    run = run_controller(source, mazesim.load_world("arena"), seconds=0.5)
    out, err = capfd.readouterr()
    # Webots' Robot.cpp prints its message and exits with -1: status 255.
    assert (run.exit_status, run.error, run.steps) == (255, "", 1)
    assert out == "step 0\n"
    assert err.splitlines() == ["Only one instance of the Robot class should be created"]


def test_tags_of_other_kinds_null_names_and_indexes_get_webots_messages(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    run, out, err = run_c(
        capfd,
        tmp_path,
        '  printf("null %d empty %d\\n", wb_robot_get_device(NULL), wb_robot_get_device(""));\n'
        '  printf("missing %d\\n", wb_robot_get_device("nothing"));\n'
        '  printf("index %d\\n", wb_robot_get_device_by_index(-1));\n'
        '  WbDeviceTag motor = wb_robot_get_device("left wheel motor");\n'
        '  WbDeviceTag sensor = wb_robot_get_device("ps0");\n'
        '  printf("value %g\\n", wb_distance_sensor_get_value(motor));\n'
        '  printf("velocity %g\\n", wb_motor_get_max_velocity(sensor));\n'
        '  printf("width %d\\n", wb_camera_get_width(motor));\n'
        "  wb_motor_set_velocity(sensor, 1.0);\n  wb_distance_sensor_enable(motor, 32);\n"
        '  printf("far %g\\n", wb_distance_sensor_get_value(999));\n'
        '  const char *none = wb_device_get_name(999) ? "?" : "none";\n'
        '  printf("names %s %s\\n", wb_device_get_name(0), none);\n'
        '  WbDeviceTag emitter = wb_robot_get_device("emitter");\n'
        "  wb_emitter_set_range(emitter, -3.0);\n"
        '  printf("range %g\\n", wb_emitter_get_range(emitter));\n'
        '  WbDeviceTag receiver = wb_robot_get_device("receiver");\n'
        '  printf("direction %p\\n", (void *)wb_receiver_get_emitter_direction(receiver));\n'
        "  WbNodeRef self = wb_supervisor_node_get_self();\n"
        '  printf("field %p\\n", (void *)wb_supervisor_node_get_field(self, NULL));\n'
        '  WbFieldRef name = wb_supervisor_node_get_field(self, "name");\n'
        "  wb_supervisor_field_set_sf_string(name, NULL);\n"
        '  printf("name %s\\n", wb_supervisor_field_get_sf_string(name));\n'
        '  printf("step %d\\n", wb_robot_step(32));',
    )
    assert (run.exit_status, run.error, run.steps) == (0, "", 1)
    assert out == [
        "null 0 empty 0",
        "missing 0",
        "index 0",
        "value nan",
        "velocity nan",
        "width 0",
        "far nan",
        "names e-puck none",
        "range -1",
        "direction (nil)",
        "field (nil)",
        "name e-puck",
        "step 0",
    ]
    assert err == [
        "Error: wb_robot_get_device() called with NULL or empty argument.",
        "Error: wb_robot_get_device() called with NULL or empty argument.",
        'Warning: "nothing" device not found.',
        "Error: The index of wb_robot_get_device_by_index() is out of the bounds.",
        # Webots' functions of a kind of device refuse the other kinds' tags.
        "Error: wb_distance_sensor_get_value(): invalid device tag.",
        "Error: wb_motor_get_max_velocity(): invalid device tag.",
        "Error: wb_camera_get_width(): invalid device tag.",
        "Error: wb_motor_set_velocity(): invalid device tag.",
        "Error: wb_distance_sensor_enable(): invalid device tag.",
        "Error: device with tag=999 not found.",
        "Error: wb_distance_sensor_get_value(): invalid device tag.",
        # wb_device_get_name says nothing: tag 0 is the robot, 999 none.
        "Error: wb_emitter_set_range(): invalid range=-3.000000 argument.",
        "Error: wb_receiver_get_emitter_direction(): the receiver queue is empty.",
        "Error: wb_supervisor_node_get_field() called with a NULL or empty 'field_name' argument.",
        "Error: wb_supervisor_field_set_sf_string() called with a NULL string argument.",
    ]


def test_the_library_knows_the_most_bytes_a_call_carries() -> None:
    # A larger value is refused in the controller, before it reaches the link.
    header = (CAPI / "src" / "link.h").read_text()
    assert "#define LINK_MAX_VALUE_BYTES (1 << 26)" in header
    assert native_link.MAX_VALUE_BYTES == 1 << 26


def test_a_step_after_the_one_that_returned_minus_1_ends_the_controller(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    # Webots' robot.c: once Webots quits the controller, wb_robot_step returns -1, and the
    # next call exits (EXIT_SUCCESS). A controller looping on without looking at -1 (an
    # evolutionary supervisor that reloads the world from its loop) stops there, rather than
    # calling on into the world for a second of wall-clock time.
    run, out, err = run_c(
        capfd,
        tmp_path,
        "  for (int count = 1;; count++)\n"
        '    if (wb_robot_step(32) == -1) printf("over at call %d\\n", count);',
        seconds=0.5,
    )
    assert out == ["over at call 17"], "16 steps of 32 ms in 0.5 s, then -1 once"
    assert (run.exit_status, run.error, run.stopped) == (0, "", False)
    assert err == []


def test_a_device_name_is_quoted_short_and_on_one_line(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    # A 10 MB name holding a newline was written whole, over two lines.
    run, _, err = run_c(
        capfd,
        tmp_path,
        "  char *name = malloc(1000001);\n  memset(name, 'a', 1000000);\n  name[10] = '\\n';\n"
        "  name[1000000] = 0;\n  wb_robot_get_device(name);\n  free(name);\n"
        "  wb_robot_step(32);",
    )
    assert run.exit_status == 0, run.error
    (line,) = [line for line in err if "device not found" in line]
    assert line == 'Warning: "' + "a" * 10 + "?" + "a" * 189 + '..." device not found.'
