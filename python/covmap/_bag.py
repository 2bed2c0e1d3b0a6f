"""ROS 1 and ROS 2 bags into a :class:`~covmap.Log`, read by the ``rosbags``
package (the ``rosbags`` extra: ``pip install 'covmap[rosbags]'``).
``covmap.Log.from_bag`` calls :func:`read_bag`.

A log is one sensor's scans, so one topic is read a call:

===========================  ==================================================
in the bag                   in the log
===========================  ==================================================
``sensor_msgs/LaserScan``    a scan a message, beam ``k`` at ``angle_min + k
on ``topic``                 angle_increment``, REP 117 converted as
                             ``Log.from_laser_scans`` does (``+inf`` and
                             readings above ``range_max``: no echo; NaN,
                             ``-inf`` and readings below ``range_min``:
                             dropped); the maximum range ``range_max``
``sensor_msgs/Range``        a scan of one beam along the sensor's x axis a
on ``topic``                 message, ``min_range`` and ``max_range`` as a
                             LaserScan's ``range_min`` and ``range_max``
each message's               the scan's timestamp, seconds
``header.stamp``
``nav_msgs/Odometry`` on     the robot's poses: ``pose.pose`` at each scan's
``odom_topic``               stamp; ``base_frame`` is its ``child_frame_id``
else ``/tf``                 the robot's poses: ``base_frame`` in
                             ``fixed_frame`` (default: the root of the tree
                             above ``base_frame``), composed along the tree at
                             each scan's stamp
``/tf_static``               the sensor's mounting: its frame (the messages'
                             ``header.frame_id``) in ``base_frame``, applied
                             when the log is integrated
===========================  ==================================================

Poses between two samples are interpolated as the CARMEN reader's ``ODOM``
poses are: linearly by timestamp, the heading the short way round; a scan
before the first sample or after the last takes the nearest. Every message
on ``topic`` must have the same frame, fan (LaserScan) or limits (Range),
and a stamp no earlier than the message's before it (a log is a drive in
time order: stamps that go back, a clock reset, are refused).
The robot is planar: heights, roll and pitch are dropped. A sonar ring
published as one ``Range`` topic a sonar is one log a topic, each with its
own mounting.

A bag that cannot be read (truncated, not a bag, a message that is not of
its topic's type, a size that runs past the data), a topic that is missing
or holds other messages, a frame without transforms, transforms that form
a loop: ``FileFormatError`` naming the file (``filename``), where
(``place``: the bag, a topic, a message, ``/tf``) and why (``reason``). A
missing path: ``FileIOError``. A ROS 2 bag's ``metadata.yaml`` is read by
rosbags' YAML parser, whose time grows with the square of how deeply flow
collections nest: it is refused first if it is no small regular file or
holds more than :data:`MAX_FLOW_COLLECTIONS` flow collections that hold
something (the rule of covmap's map_server reader).

What covmap parses itself here (the messages' fields into a log) is held
to that by ``python/tests/test_bag_hostile.py``, a property test over
bags of hostile field values.
"""

from __future__ import annotations

import errno
import math
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from covmap._errors import FileFormatError, FileIOError, MissingDependencyError
from covmap._native import MAX_FLOW_COLLECTIONS, Log, flow_collections

if TYPE_CHECKING:
    from collections.abc import Iterator

    import numpy.typing as npt

LASER_SCAN = "sensor_msgs/msg/LaserScan"
RANGE = "sensor_msgs/msg/Range"
ODOMETRY = "nav_msgs/msg/Odometry"
TF_MESSAGE = "tf2_msgs/msg/TFMessage"
TF_TOPIC = "/tf"
TF_STATIC_TOPIC = "/tf_static"
SCAN_TYPES = (LASER_SCAN, RANGE)
"""The message types a log is read from."""

DEFAULT_BASE_FRAME = "base_link"
"""The robot's frame (REP 105) where the bag does not name it."""

Poses = tuple["npt.NDArray[np.float64]", "npt.NDArray[np.float64]", "npt.NDArray[np.float64]"]
"""x, y and theta arrays of one length."""


def read_bag(
    path: str | os.PathLike[str],
    *,
    topic: str | None = None,
    odom_topic: str | None = None,
    base_frame: str | None = None,
    fixed_frame: str | None = None,
    max_range_m: float | None = None,
) -> Log:
    """The log of the ``sensor_msgs/LaserScan`` or ``sensor_msgs/Range``
    messages on ``topic`` of the bag at ``path`` (a ROS 1 ``.bag`` file or a
    ROS 2 bag directory), as the module documentation says; ``topic=None``
    takes the bag's only such topic, ``max_range_m`` overrides the
    message's maximum range."""
    try:
        from rosbags.highlevel import AnyReader
        from rosbags.typesys import Stores, get_typestore
    except ImportError:
        raise MissingDependencyError(
            "rosbags is not installed: pip install 'covmap[rosbags]' (ROS bags)"
        ) from None
    bag = Path(path)
    if not bag.exists():
        raise FileIOError(errno.ENOENT, os.strerror(errno.ENOENT), str(bag))
    _check_metadata(bag)
    try:
        # rosbags raises many kinds of exception for a damaged bag (its own,
        # sqlite3's, struct's, the decompressors'): all are "not a readable
        # bag" here, and no covmap code runs inside this block.
        with AnyReader([bag], default_typestore=get_typestore(Stores.ROS2_HUMBLE)) as reader:
            contents = _Contents.read(reader, bag, topic, odom_topic)
    except FileFormatError:
        raise
    except Exception as err:  # noqa: BLE001 (see above)
        raise _format_error(bag, "the bag", f"not a readable bag: {err}") from err
    return contents.log(base_frame=base_frame, fixed_frame=fixed_frame, max_range_m=max_range_m)


def _check_metadata(bag: Path) -> None:
    """Refuse a ROS 2 bag whose ``metadata.yaml`` is no small regular file
    or would take the YAML parser long (see the module's documentation)."""
    metadata = bag / "metadata.yaml"
    if not bag.is_dir() or not os.path.lexists(metadata):
        return  # a ROS 1 bag, or none: rosbags says what is wrong
    from covmap._read import read_small_file

    text = read_small_file(metadata).decode("utf-8", errors="replace")
    collections = flow_collections(text)
    if collections > MAX_FLOW_COLLECTIONS:
        reason = (
            f"{collections} flow collections (`[` or `{{`), more than the {MAX_FLOW_COLLECTIONS} a YAML file "
            "covmap reads may hold (a bound on their nesting)"
        )
        raise _format_error(bag, "metadata.yaml", reason)


def _format_error(bag: Path, place: str, reason: str) -> FileFormatError:
    error = FileFormatError(f"{bag}: {place}: {reason}")
    error.filename, error.place, error.reason = str(bag), place, reason
    return error


def _stamp_s(header: Any) -> float:
    return float(header.stamp.sec) + 1e-9 * float(header.stamp.nanosec)


def _frame(name: str) -> str:
    # ROS 1 bags may write frames as "/base_link"; tf2 names them without.
    return name.lstrip("/")


def _yaw(q: Any) -> float:
    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


def _wrap(theta: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
    return np.asarray((theta + math.pi) % (2.0 * math.pi) - math.pi, dtype=np.float64)


def _compose(a: Poses, b: Poses) -> Poses:
    """The pose ``b`` (in ``a``'s frame) in the frame ``a`` is in."""
    ax, ay, at = a
    bx, by, bt = b
    c, s = np.cos(at), np.sin(at)
    return ax + c * bx - s * by, ay + s * bx + c * by, _wrap(at + bt)


@dataclass
class _Track:
    """The samples of one moving pose: ``(t, x, y, theta)`` rows."""

    samples: list[tuple[float, float, float, float]] = field(default_factory=list)

    def at(self, times_s: npt.NDArray[np.float64]) -> Poses:
        """The pose at each time: linear between the samples around it, the
        heading the short way round, the nearest sample outside them."""
        rows = np.array(sorted(self.samples, key=lambda r: r[0]), dtype=np.float64)
        t, x, y = rows[:, 0], rows[:, 1], rows[:, 2]
        theta = np.unwrap(rows[:, 3])
        return (
            np.interp(times_s, t, x),
            np.interp(times_s, t, y),
            _wrap(np.interp(times_s, t, theta)),
        )


@dataclass
class _Scan:
    """One sensor message as read: stamp, frame, ranges and fan."""

    stamp_s: float
    frame: str
    ranges: npt.NDArray[np.float32]
    fan: tuple[float, float, float, float]
    """angle_min, angle_increment, range_min, range_max."""


@dataclass
class _Contents:
    """What a log is made of, read from one bag."""

    bag: Path
    topic: str
    msgtype: str
    scans: list[_Scan]
    odometry: _Track | None = None
    odom_frame: str = ""
    tf: dict[str, tuple[str, _Track]] = field(default_factory=dict)
    """child frame: (parent frame, its track)."""
    tf_static: dict[str, tuple[str, tuple[float, float, float]]] = field(default_factory=dict)

    @classmethod
    def read(cls, reader: Any, bag: Path, topic: str | None, odom_topic: str | None) -> _Contents:
        types: dict[str, set[str]] = {}
        for connection in reader.connections:
            types.setdefault(connection.topic, set()).add(connection.msgtype)
        topic = cls._scan_topic(bag, types, topic)
        msgtype = next(iter(types[topic]))
        if odom_topic is not None:
            cls._check_topic(bag, types, odom_topic, (ODOMETRY,))
        contents = cls(bag, topic, msgtype, [])
        wanted = {topic, odom_topic, TF_TOPIC, TF_STATIC_TOPIC}
        connections = [c for c in reader.connections if c.topic in wanted]
        for connection, _, raw in reader.messages(connections=connections):
            message = reader.deserialize(raw, connection.msgtype)
            contents._take(connection.topic, connection.msgtype, message, odom_topic)
        if not contents.scans:
            raise _format_error(bag, f"topic {topic}", "holds no messages")
        if odom_topic is not None and contents.odometry is None:
            raise _format_error(bag, f"topic {odom_topic}", "holds no messages")
        return contents

    @staticmethod
    def _scan_topic(bag: Path, types: dict[str, set[str]], topic: str | None) -> str:
        if topic is not None:
            _Contents._check_topic(bag, types, topic, SCAN_TYPES)
            return topic
        found = sorted(t for t, kinds in types.items() if kinds & set(SCAN_TYPES))
        if len(found) != 1:
            reason = (
                f"holds {len(found)} LaserScan or Range topics ({', '.join(found) or 'none'}): "
                "name one (topic=...)"
            )
            raise _format_error(bag, "the bag", reason)
        return found[0]

    @staticmethod
    def _check_topic(bag: Path, types: dict[str, set[str]], topic: str, expected: tuple[str, ...]) -> None:
        if topic not in types:
            shown = ", ".join(f"{t} ({', '.join(sorted(k))})" for t, k in sorted(types.items()))
            raise _format_error(bag, f"topic {topic}", f"no such topic; the bag has {shown or 'none'}")
        if not types[topic] <= set(expected):
            reason = f"holds {', '.join(sorted(types[topic]))} messages, not {' or '.join(expected)}"
            raise _format_error(bag, f"topic {topic}", reason)

    def _take(self, topic: str, msgtype: str, message: Any, odom_topic: str | None) -> None:
        if topic == self.topic:
            self.scans.append(self._scan(message))
        elif topic == odom_topic:
            if self.odometry is None:
                self.odometry, self.odom_frame = _Track(), _frame(message.child_frame_id)
            pose = message.pose.pose
            self.odometry.samples.append(
                (_stamp_s(message.header), pose.position.x, pose.position.y, _yaw(pose.orientation))
            )
        elif msgtype == TF_MESSAGE:
            for transform in message.transforms:
                parent, child = _frame(transform.header.frame_id), _frame(transform.child_frame_id)
                t, q = transform.transform.translation, transform.transform.rotation
                if topic == TF_STATIC_TOPIC:
                    self.tf_static[child] = (parent, (t.x, t.y, _yaw(q)))
                else:
                    track = self.tf.setdefault(child, (parent, _Track()))[1]
                    track.samples.append((_stamp_s(transform.header), t.x, t.y, _yaw(q)))

    def _scan(self, message: Any) -> _Scan:
        stamp, frame = _stamp_s(message.header), _frame(message.header.frame_id)
        if self.msgtype == LASER_SCAN:
            fan = (message.angle_min, message.angle_increment, message.range_min, message.range_max)
            return _Scan(stamp, frame, np.asarray(message.ranges, dtype=np.float32), fan)
        fan = (0.0, 0.0, message.min_range, message.max_range)
        return _Scan(stamp, frame, np.array([message.range], dtype=np.float32), fan)

    def log(self, *, base_frame: str | None, fixed_frame: str | None, max_range_m: float | None) -> Log:
        """The log: the scans, the robot's poses at their stamps, the mounting."""
        first = self.scans[0]
        for i, scan in enumerate(self.scans):
            for what, value, expected in (
                ("frame", scan.frame, first.frame),
                ("fan" if self.msgtype == LASER_SCAN else "limits", scan.fan, first.fan),
                ("beam count", len(scan.ranges), len(first.ranges)),
            ):
                if value != expected:
                    reason = f"its {what} {value} differs from the first message's {expected}"
                    raise _format_error(self.bag, f"topic {self.topic} message {i}", reason)
        times = np.array([s.stamp_s for s in self.scans], dtype=np.float64)
        back = np.flatnonzero(np.diff(times) < 0.0)
        if back.size:
            i = int(back[0]) + 1
            reason = (
                f"its stamp {times[i]:.9f} s is earlier than message {i - 1}'s, {times[i - 1]:.9f} s: the stamps "
                "go back (a clock reset?), and a log is read in time order"
            )
            raise _format_error(self.bag, f"topic {self.topic} message {i}", reason)
        if self.odometry is not None:
            base = self.odom_frame or base_frame or DEFAULT_BASE_FRAME
            if base_frame is not None and base_frame != base:
                reason = f"the odometry is of frame {base}, not base_frame {base_frame}"
                raise _format_error(self.bag, "the odometry", reason)
            x, y, theta = self.odometry.at(times)
        else:
            base = base_frame or DEFAULT_BASE_FRAME
            x, y, theta = self._tf_poses(base, fixed_frame, times)
        angle_min, angle_increment, range_min, range_max = first.fan
        log = Log.from_laser_scans(
            np.column_stack([x, y, theta]),
            np.stack([s.ranges for s in self.scans]),
            angle_min=angle_min,
            angle_increment=angle_increment,
            range_min=range_min,
            range_max=range_max if max_range_m is None else max_range_m,
            timestamps=times,
        )
        return log.with_sensor_offset(self._mounting(base, first.frame))

    def _parents(self, frame: str) -> Iterator[tuple[str, str, bool]]:
        """``(child, parent, static)`` up the tree from ``frame`` to its root."""
        seen = {frame}
        while True:
            if frame in self.tf:
                parent, static = self.tf[frame][0], False
            elif frame in self.tf_static:
                parent, static = self.tf_static[frame][0], True
            else:
                return
            if parent in seen:
                raise _format_error(self.bag, TF_TOPIC, f"the transforms above {frame} form a loop")
            seen.add(parent)
            yield frame, parent, static
            frame = parent

    def _tf_poses(self, base: str, fixed: str | None, times: npt.NDArray[np.float64]) -> Poses:
        zeros = np.zeros_like(times)
        pose: Poses = (zeros, zeros, zeros)
        reached = base
        for child, parent, static in self._parents(base):
            if static:
                step: Poses = tuple(zeros + v for v in self.tf_static[child][1])  # type: ignore[assignment]
            else:
                step = self.tf[child][1].at(times)
            pose = _compose(step, pose)
            reached = parent
            if parent == fixed:
                break
        if reached == base:
            reason = f"no transform of the robot's frame {base} (give odom_topic, or base_frame)"
            raise _format_error(self.bag, TF_TOPIC, reason)
        if fixed is not None and reached != fixed:
            reason = f"the transforms above {base} end at {reached}, not at fixed_frame {fixed}"
            raise _format_error(self.bag, TF_TOPIC, reason)
        return pose

    def _mounting(self, base: str, sensor: str) -> tuple[float, float, float]:
        """The sensor's frame in the robot's, from the static transforms."""
        offset: Poses = (np.zeros(1), np.zeros(1), np.zeros(1))
        reached = sensor
        for child, parent, static in self._parents(sensor):
            if reached == base:
                break
            if not static:
                reason = f"the sensor's frame {sensor} moves against {parent} (its transform is not static)"
                raise _format_error(self.bag, TF_STATIC_TOPIC, reason)
            x, y, theta = self.tf_static[child][1]
            offset = _compose((np.array([x]), np.array([y]), np.array([theta])), offset)
            reached = parent
        if reached != base:
            reason = f"no static transform from the robot's frame {base} to the sensor's frame {sensor}"
            raise _format_error(self.bag, TF_STATIC_TOPIC, reason)
        return float(offset[0][0]), float(offset[1][0]), float(offset[2][0])
