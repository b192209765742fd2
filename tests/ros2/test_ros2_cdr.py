"""mazesim's CDR encoding of ROS 2 messages equals rosbags' independent serializer, byte for
byte, in each distribution's layout; the decoders read what rosbags writes; bad bytes are refused
with a clear error."""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mazesim.errors import InvalidActionError
from mazesim.ros2 import cdr, graph, messages
from ros2_support import needs_ros2

pytestmark = needs_ros2

DISTROS = messages.DISTROS
floats32 = st.floats(width=32, allow_nan=False)
floats64 = st.floats(allow_nan=False)
frames = st.text(alphabet="abcdefghijklmnopqrstuvwxyz_0123456789", max_size=12)
stamps = st.tuples(st.integers(0, 2**31 - 1), st.integers(0, 999_999_999))


def _ros(distro: str, msgtype: str, **fields: object) -> bytes:
    store = messages.typestore(distro)
    return bytes(store.serialize_cdr(store.types[msgtype](**fields), msgtype))


def _header(distro: str, stamp: cdr.Stamp, frame: str) -> object:
    store = messages.typestore(distro)
    time = store.types["builtin_interfaces/msg/Time"](sec=stamp[0], nanosec=stamp[1])
    return store.types["std_msgs/msg/Header"](stamp=time, frame_id=frame)


def _padded(data: bytes) -> bytes:
    return data + bytes(-len(data) % 4)


@pytest.mark.parametrize("distro", DISTROS)
@settings(max_examples=15, deadline=None)
@given(stamp=stamps, frame=frames, values=st.lists(floats32, min_size=5, max_size=5))
def test_range_as_each_distro_lays_it_out(
    distro: str, stamp: cdr.Stamp, frame: str, values: list[float]
) -> None:
    fov, near, far, distance, variance = values
    fields = dict(
        header=_header(distro, stamp, frame), radiation_type=1, field_of_view=fov,
        min_range=near, max_range=far, range=distance,
    )  # fmt: skip
    if distro == "humble":
        encoded = cdr.encode_range(stamp, frame, 1, fov, near, far, distance, None)
    else:
        fields["variance"] = variance
        encoded = cdr.encode_range(stamp, frame, 1, fov, near, far, distance, variance)
    assert encoded == _padded(_ros(distro, "sensor_msgs/msg/Range", **fields))


@pytest.mark.parametrize("distro", DISTROS)
@settings(max_examples=10, deadline=None)
@given(
    stamp=stamps,
    frame=frames,
    child=frames,
    pose=st.lists(floats64, min_size=7, max_size=7),
    twist=st.lists(floats64, min_size=6, max_size=6),
)
def test_odometry_and_tf(
    distro: str, stamp: cdr.Stamp, frame: str, child: str, pose: list[float], twist: list[float]
) -> None:
    store = messages.typestore(distro)
    types = store.types
    zeros = __import__("numpy").zeros(36)
    point = types["geometry_msgs/msg/Point"](x=pose[0], y=pose[1], z=pose[2])
    vector = types["geometry_msgs/msg/Vector3"]
    rotation = types["geometry_msgs/msg/Quaternion"](x=pose[3], y=pose[4], z=pose[5], w=pose[6])
    expected = _ros(
        distro,
        "nav_msgs/msg/Odometry",
        header=_header(distro, stamp, frame),
        child_frame_id=child,
        pose=types["geometry_msgs/msg/PoseWithCovariance"](
            pose=types["geometry_msgs/msg/Pose"](position=point, orientation=rotation),
            covariance=zeros,
        ),
        twist=types["geometry_msgs/msg/TwistWithCovariance"](
            twist=types["geometry_msgs/msg/Twist"](
                linear=vector(x=twist[0], y=twist[1], z=twist[2]),
                angular=vector(x=twist[3], y=twist[4], z=twist[5]),
            ),
            covariance=zeros,
        ),
    )
    encoded = cdr.encode_odometry(stamp, frame, child, tuple(pose), tuple(twist))  # type: ignore[arg-type]
    assert encoded == _padded(expected)
    transform = types["geometry_msgs/msg/TransformStamped"](
        header=_header(distro, stamp, frame),
        child_frame_id=child,
        transform=types["geometry_msgs/msg/Transform"](
            translation=vector(x=pose[0], y=pose[1], z=pose[2]), rotation=rotation
        ),
    )
    for count in (1, 3):
        expected = _ros(distro, "tf2_msgs/msg/TFMessage", transforms=[transform] * count)
        one = (stamp, frame, child, tuple(pose[:3]), tuple(pose[3:]))
        assert cdr.encode_tf_message([one] * count) == _padded(expected)  # type: ignore[list-item]


@pytest.mark.parametrize("distro", DISTROS)
@settings(max_examples=10, deadline=None)
@given(
    stamp=stamps,
    frame=frames,
    ranges=st.lists(floats32, max_size=25),
    head=st.lists(floats32, min_size=7, max_size=7),
)
def test_laser_scan(
    distro: str, stamp: cdr.Stamp, frame: str, ranges: list[float], head: list[float]
) -> None:
    numpy = pytest.importorskip("numpy")
    expected = _ros(
        distro, "sensor_msgs/msg/LaserScan", header=_header(distro, stamp, frame),
        angle_min=head[0], angle_max=head[1], angle_increment=head[2], time_increment=head[3],
        scan_time=head[4], range_min=head[5], range_max=head[6],
        ranges=numpy.asarray(ranges, dtype=numpy.float32),
        intensities=numpy.zeros(0, numpy.float32),
    )  # fmt: skip
    encoded = cdr.encode_laser_scan(
        stamp,
        frame,
        tuple(head[:3]),
        tuple(head[3:5]),
        tuple(head[5:]),
        ranges,  # type: ignore[arg-type]
    )
    assert encoded == _padded(expected)


@pytest.mark.parametrize("distro", DISTROS)
@settings(max_examples=10, deadline=None)
@given(labels=st.lists(frames, max_size=4), data=st.lists(floats64, max_size=12), text=st.text())
def test_arrays_strings_clock_and_commands(
    distro: str, labels: list[str], data: list[float], text: str
) -> None:
    numpy = pytest.importorskip("numpy")
    types = messages.typestore(distro).types
    label = ",".join(labels)
    dimensions = (
        [types["std_msgs/msg/MultiArrayDimension"](label=label, size=len(data), stride=len(data))]
        if labels
        else []
    )
    expected = _ros(
        distro,
        "std_msgs/msg/Float64MultiArray",
        layout=types["std_msgs/msg/MultiArrayLayout"](dim=dimensions, data_offset=0),
        data=numpy.asarray(data, dtype=numpy.float64),
    )
    assert cdr.encode_float64_multi_array(labels, data) == _padded(expected)
    assert cdr.decode_float64_array(expected) == data
    assert cdr.encode_string(text) == _padded(_ros(distro, "std_msgs/msg/String", data=text))
    assert cdr.decode_string(_ros(distro, "std_msgs/msg/String", data=text)) == text
    time = types["builtin_interfaces/msg/Time"](sec=12, nanosec=34)
    clock = _ros(distro, "rosgraph_msgs/msg/Clock", clock=time)
    assert cdr.encode_clock((12, 34)) == clock
    assert cdr.decode_clock(clock) == 12_000_000_034
    vector = types["geometry_msgs/msg/Vector3"]
    twist = types["geometry_msgs/msg/Twist"](
        linear=vector(x=0.1, y=0.0, z=0.0), angular=vector(x=0.0, y=0.0, z=-0.5)
    )
    twist_bytes = _ros(
        distro, "geometry_msgs/msg/Twist", linear=twist.linear, angular=twist.angular
    )
    assert cdr.decode_twist(twist_bytes) == (0.1, -0.5)
    assert cdr.encode_twist((0.1, 0.0, 0.0), (0.0, 0.0, -0.5)) == twist_bytes
    stamped = _ros(
        distro, "geometry_msgs/msg/TwistStamped", header=_header(distro, (1, 2), "base_link"),
        twist=twist,
    )  # fmt: skip
    assert cdr.decode_twist_stamped(stamped) == (0.1, -0.5)
    encoded = cdr.encode_twist_stamped((1, 2), "base_link", (0.1, 0.0, 0.0), (0.0, 0.0, -0.5))
    assert encoded == _padded(stamped)


@pytest.mark.parametrize("distro", DISTROS)
@settings(max_examples=10, deadline=None)
@given(
    stamp=stamps,
    names=st.lists(st.text(max_size=20), max_size=3),
    values=st.lists(floats64, min_size=6, max_size=6),
)
def test_joint_state(distro: str, stamp: cdr.Stamp, names: list[str], values: list[float]) -> None:
    numpy = pytest.importorskip("numpy")
    positions, velocities = values[: len(names)], values[3 : 3 + len(names)]
    expected = _ros(
        distro, "sensor_msgs/msg/JointState", header=_header(distro, stamp, ""), name=names,
        position=numpy.asarray(positions, dtype=numpy.float64),
        velocity=numpy.asarray(velocities, dtype=numpy.float64),
        effort=numpy.asarray([], dtype=numpy.float64),
    )  # fmt: skip
    assert cdr.encode_joint_state(stamp, names, positions, velocities) == _padded(expected)


def test_big_endian_commands_are_read_too() -> None:
    import struct

    data = b"\x00\x00\x00\x00" + struct.pack(">6d", 0.2, 0, 0, 0, 0, 1.5)
    assert cdr.decode_twist(data) == (0.2, 1.5)


@pytest.mark.parametrize(
    "data", [b"", b"\x00\x01\x00\x00", b"\x07\x01\x00\x00" + bytes(48), b"\x00\x01\x00\x00\xff"]
)
def test_bytes_that_are_not_a_command_are_refused(data: bytes) -> None:
    with pytest.raises(InvalidActionError, match="expected"):
        cdr.decode_twist(data)
    with pytest.raises(InvalidActionError, match="expected"):
        cdr.decode_float64_array(data)


def test_type_hashes_and_graph_gids_per_distro() -> None:
    import uuid

    assert graph.endpoint_user_data("humble", "sensor_msgs/msg/Range") is None
    jazzy = graph.endpoint_user_data("jazzy", "sensor_msgs/msg/Range")
    assert jazzy is not None and jazzy.startswith(b"typehash=RIHS01_") and jazzy.endswith(b";")
    assert len(jazzy) == len("typehash=RIHS01_;") + 64
    # Range gained a field after Humble: its hash differs; Twist's did not change.
    assert messages.type_hash("humble", "sensor_msgs/msg/Range") != messages.type_hash(
        "jazzy", "sensor_msgs/msg/Range"
    )
    guid = uuid.UUID(int=0x0110_1234_5678_9ABC_DEF0_0000_0000_01C1)
    assert len(graph.gid("humble", guid).data) == 24
    assert bytes(graph.gid("jazzy", guid).data) == guid.bytes
    info = graph.participant_entities_info("jazzy", guid, [("/", "mazesim_bridge", [guid], [])])
    assert info.node_entities_info_seq[0].node_name == "mazesim_bridge"
    assert messages.dds_type_name("sensor_msgs/msg/Range") == "sensor_msgs::msg::dds_::Range_"
    assert math.isfinite(len(messages.DISTROS))


def test_a_string_keeps_its_own_nul_characters() -> None:
    for text in ("\x00", "a\x00", "a\x00\x00b", ""):
        assert cdr.decode_string(cdr.encode_string(text)) == text


@pytest.mark.parametrize("distro", DISTROS)
@settings(max_examples=10, deadline=None)
@given(stamp=stamps, frame=frames, values=st.lists(floats64, min_size=10, max_size=10))
def test_imu(distro: str, stamp: cdr.Stamp, frame: str, values: list[float]) -> None:
    types = messages.typestore(distro).types
    zeros = __import__("numpy").zeros(9)
    vector = types["geometry_msgs/msg/Vector3"]
    expected = _ros(
        distro,
        "sensor_msgs/msg/Imu",
        header=_header(distro, stamp, frame),
        orientation=types["geometry_msgs/msg/Quaternion"](
            x=values[0], y=values[1], z=values[2], w=values[3]
        ),
        orientation_covariance=zeros,
        angular_velocity=vector(x=values[4], y=values[5], z=values[6]),
        angular_velocity_covariance=zeros,
        linear_acceleration=vector(x=values[7], y=values[8], z=values[9]),
        linear_acceleration_covariance=zeros,
    )
    encoded = cdr.encode_imu(
        stamp,
        frame,
        tuple(values[:4]),  # type: ignore[arg-type]
        tuple(values[4:7]),  # type: ignore[arg-type]
        tuple(values[7:]),  # type: ignore[arg-type]
    )
    assert encoded == _padded(expected)


@pytest.mark.parametrize("distro", DISTROS)
@settings(max_examples=10, deadline=None)
@given(
    stamp=stamps,
    frame=frames,
    resolution=floats32,
    origin=st.lists(floats64, min_size=7, max_size=7),
    cells=st.lists(st.sampled_from([-1, 0, 100]), max_size=40),
)
def test_occupancy_grid(
    distro: str,
    stamp: cdr.Stamp,
    frame: str,
    resolution: float,
    origin: list[float],
    cells: list[int],
) -> None:
    np = __import__("numpy")
    types = messages.typestore(distro).types
    time = types["builtin_interfaces/msg/Time"](sec=stamp[0], nanosec=stamp[1])
    pose = types["geometry_msgs/msg/Pose"](
        position=types["geometry_msgs/msg/Point"](x=origin[0], y=origin[1], z=origin[2]),
        orientation=types["geometry_msgs/msg/Quaternion"](
            x=origin[3], y=origin[4], z=origin[5], w=origin[6]
        ),
    )
    width = max(len(cells), 1)
    expected = _ros(
        distro,
        "nav_msgs/msg/OccupancyGrid",
        header=_header(distro, stamp, frame),
        info=types["nav_msgs/msg/MapMetaData"](
            map_load_time=time, resolution=resolution, width=width, height=1, origin=pose
        ),
        data=np.array(cells, dtype=np.int8),
    )
    data = np.array(cells, dtype=np.int8).tobytes()
    encoded = cdr.encode_occupancy_grid(
        stamp,
        frame,
        resolution,
        (width, 1),
        tuple(origin),
        data,  # type: ignore[arg-type]
    )
    assert encoded == _padded(expected)
