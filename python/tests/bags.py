"""ROS bags written with rosbags' own writers, for the tests of
``covmap.Log.from_bag``: one ``BagWriter`` for both formats (ROS 1: a
``.bag`` file; ROS 2: a directory), messages built from plain numbers."""

from __future__ import annotations

import math
from pathlib import Path
from types import TracebackType
from typing import Any

import numpy as np

from extras import need_extra

FORMATS = ("ros1", "ros2")
"""The bag formats every test writes."""


def need_rosbags() -> None:
    """Skip with a message when rosbags is missing (a failure under
    ``CI=true``: CI installs the extra)."""
    need_extra("rosbags", "rosbags", "the bag tests")


def ns(t_s: float) -> int:
    """Seconds as integer nanoseconds, rounded."""
    return round(t_s * 1e9)


class BagWriter:
    """A bag of format ``ros1`` or ``ros2`` at ``path`` (``.bag`` is added
    for ROS 1), written as a context manager."""

    def __init__(self, directory: Path, name: str, bag_format: str) -> None:
        from rosbags.typesys import Stores, get_typestore

        self.ros1 = bag_format == "ros1"
        if self.ros1:
            from rosbags.rosbag1 import Writer as Writer1

            self.path = directory / f"{name}.bag"
            self.store = get_typestore(Stores.ROS1_NOETIC)
            # Noetic's store lacks tf2_msgs, which every ROS 1 /tf uses.
            from rosbags.typesys import get_types_from_msg

            tf_message = get_types_from_msg("geometry_msgs/TransformStamped[] transforms", "tf2_msgs/msg/TFMessage")
            self.store.register(tf_message)
            self.writer: Any = Writer1(self.path)
        else:
            from rosbags.rosbag2 import Writer as Writer2

            self.path = directory / name
            self.store = get_typestore(Stores.ROS2_HUMBLE)
            self.writer = Writer2(self.path, version=9)
        self.connections: dict[str, Any] = {}

    def __enter__(self) -> BagWriter:
        self.writer.open()
        return self

    def __exit__(self, kind: type[BaseException] | None, value: BaseException | None, tb: TracebackType | None) -> None:
        self.writer.close()

    def write(self, topic: str, message: Any, t_s: float) -> None:
        """``message`` on ``topic``, recorded at ``t_s``."""
        msgtype = message.__msgtype__
        if topic not in self.connections:
            self.connections[topic] = self.writer.add_connection(topic, msgtype, typestore=self.store)
        data = self.store.serialize_ros1(message, msgtype) if self.ros1 else self.store.serialize_cdr(message, msgtype)
        self.writer.write(self.connections[topic], ns(t_s), data)

    def _type(self, name: str) -> Any:
        return self.store.types[name]

    def header(self, t_s: float, frame: str) -> Any:
        stamp = self._type("builtin_interfaces/msg/Time")(sec=ns(t_s) // 10**9, nanosec=ns(t_s) % 10**9)
        if self.ros1:
            return self._type("std_msgs/msg/Header")(seq=0, stamp=stamp, frame_id=frame)
        return self._type("std_msgs/msg/Header")(stamp=stamp, frame_id=frame)

    def _pose_parts(self, pose: tuple[float, float, float]) -> tuple[Any, Any]:
        x, y, theta = pose
        position = self._type("geometry_msgs/msg/Vector3")(x=x, y=y, z=0.0)
        q = self._type("geometry_msgs/msg/Quaternion")(x=0.0, y=0.0, z=math.sin(theta / 2), w=math.cos(theta / 2))
        return position, q

    def laser_scan(
        self, t_s: float, frame: str, ranges: Any, *, angle_min: float, angle_increment: float, range_max: float
    ) -> Any:
        ranges = np.asarray(ranges, dtype=np.float32)
        return self._type("sensor_msgs/msg/LaserScan")(
            header=self.header(t_s, frame),
            angle_min=angle_min,
            angle_max=angle_min + angle_increment * (len(ranges) - 1),
            angle_increment=angle_increment,
            time_increment=0.0,
            scan_time=0.1,
            range_min=0.05,
            range_max=range_max,
            ranges=ranges,
            intensities=np.zeros(0, dtype=np.float32),
        )

    def range(self, t_s: float, frame: str, reading: float, *, max_range: float = 5.0) -> Any:
        return self._type("sensor_msgs/msg/Range")(
            header=self.header(t_s, frame),
            radiation_type=0,
            field_of_view=0.4,
            min_range=0.1,
            max_range=max_range,
            range=reading,
        )

    def odometry(self, t_s: float, pose: tuple[float, float, float], *, child: str = "base_link") -> Any:
        position, q = self._pose_parts(pose)
        point = self._type("geometry_msgs/msg/Point")(x=position.x, y=position.y, z=0.0)
        covariance = np.zeros(36, dtype=np.float64)
        with_cov = self._type("geometry_msgs/msg/PoseWithCovariance")(
            pose=self._type("geometry_msgs/msg/Pose")(position=point, orientation=q), covariance=covariance
        )
        zero = self._type("geometry_msgs/msg/Vector3")(x=0.0, y=0.0, z=0.0)
        twist = self._type("geometry_msgs/msg/TwistWithCovariance")(
            twist=self._type("geometry_msgs/msg/Twist")(linear=zero, angular=zero), covariance=covariance
        )
        return self._type("nav_msgs/msg/Odometry")(
            header=self.header(t_s, "odom"), child_frame_id=child, pose=with_cov, twist=twist
        )

    def tf(self, t_s: float, *edges: tuple[str, str, tuple[float, float, float]]) -> Any:
        """A ``TFMessage`` of ``(parent, child, (x, y, theta))`` transforms."""
        transforms = []
        for parent, child, pose in edges:
            translation, q = self._pose_parts(pose)
            transforms.append(
                self._type("geometry_msgs/msg/TransformStamped")(
                    header=self.header(t_s, parent),
                    child_frame_id=child,
                    transform=self._type("geometry_msgs/msg/Transform")(translation=translation, rotation=q),
                )
            )
        return self._type("tf2_msgs/msg/TFMessage")(transforms=transforms)


#: The hostile bags :func:`hostile` writes, each of both formats.
HOSTILE = ("truncated", "wrong type", "huge size", "stamps back", "tf loop", "deep metadata")


def hostile(directory: Path, kind: str, bag_format: str) -> Path:
    """A bag of ``bag_format`` made hostile as ``kind`` says (one of
    :data:`HOSTILE`), in ``directory``: three LaserScans on ``/scan`` with
    odometry on ``/odom`` and the laser's static mounting, then

    - ``truncated``: cut in half (a ROS 2 bag: its database);
    - ``wrong type``: a Range message on the LaserScan topic;
    - ``huge size``: a size claiming 2**31 bytes (ROS 1: the first record's
      header length; ROS 2: the scans' ``ranges`` length);
    - ``stamps back``: the scans' header stamps going back in time;
    - ``tf loop``: no odometry, the ``/tf`` transforms forming a loop;
    - ``deep metadata`` (ROS 2; ROS 1 is truncated): ``metadata.yaml``
      nested 100,000 deep under a key it ignores.

    Read it with ``odom_topic="/odom"`` (``tf loop``: without)."""
    import sqlite3

    name = f"{kind.replace(' ', '-')}-{bag_format}"
    with BagWriter(directory, name, bag_format) as w:
        w.write("/tf_static", w.tf(0.0, ("base_link", "laser", (0.1, 0.0, 0.0))), 0.0)
        for i in range(3):
            t = 0.1 * (i + 1)
            stamp = 0.3 - 0.1 * i if kind == "stamps back" else t
            if kind == "wrong type" and i == 1:
                message = w.range(stamp, "laser", 1.0)
                connection = w.connections["/scan"]
                data = w.store.serialize_ros1(message, message.__msgtype__) if w.ros1 else w.store.serialize_cdr(message, message.__msgtype__)
                w.writer.write(connection, ns(t), data)
            else:
                w.write("/scan", w.laser_scan(stamp, "laser", [1.0, 2.0, 3.0], angle_min=-0.5, angle_increment=0.5, range_max=5.0), t)
            if kind == "tf loop":
                w.write("/tf", w.tf(t, ("odom", "base_link", (0.1 * i, 0.0, 0.0)), ("base_link", "odom", (0.0, 0.0, 0.0))), t)
            else:
                w.write("/odom", w.odometry(t, (0.1 * i, 0.0, 0.0)), t)
    path = w.path
    database = next(iter(path.glob("*.db3")), None) if not w.ros1 else None
    if kind == "truncated" or (kind == "deep metadata" and w.ros1):
        target = path if w.ros1 else database
        assert target is not None
        data = target.read_bytes()
        target.write_bytes(data[: len(data) // 2])
    elif kind == "huge size" and w.ros1:
        data = bytearray(path.read_bytes())
        data[13:17] = (2**31).to_bytes(4, "little")  # after the 13-byte magic line
        path.write_bytes(bytes(data))
    elif kind == "huge size":
        with sqlite3.connect(database) as connection:
            rows = connection.execute("SELECT id, data FROM messages").fetchall()
            for row_id, data in rows:
                # The ranges' length, 3, after the header and the fan's five floats.
                at = bytes(data).find((3).to_bytes(4, "little"), 8)
                if at > 0:
                    patched = data[:at] + (2**31 - 1).to_bytes(4, "little") + data[at + 4 :]
                    connection.execute("UPDATE messages SET data = ? WHERE id = ?", (patched, row_id))
        connection.close()
    elif kind == "deep metadata":
        metadata = path / "metadata.yaml"
        metadata.write_text(metadata.read_text() + "ignored: " + "[" * 100_000 + "]" * 100_000 + "\n")
    return path
