"""Fuzzing what covmap parses of a ROS bag itself: rosbags reads the bag,
covmap turns the messages' fields into a log (``covmap/_bag.py``). Bags of
hostile field values (stamps in any order, ranges and fans of any float,
poses that are not finite, frames that do not match, transforms in loops),
in both formats, give a log or a covmap error, never another exception.
The hostile bags themselves (truncated, of the wrong message type, of
sizes claimed past the data, ...) are cases of the bad-input corpus
(``bags.hostile``)."""

from __future__ import annotations

import math
import tempfile
from pathlib import Path
from typing import Any

import pytest

import covmap
from bags import FORMATS, BagWriter, need_rosbags

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

#: Any float a message field may hold.
floats = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True, width=32),
    st.sampled_from([0.0, -0.0, 1e30, -1e30, math.nan, math.inf, -math.inf]),
    st.floats(-5.0, 5.0),
)
#: Stamps, seconds: in order, out of order, equal, huge.
stamps = st.lists(st.one_of(st.floats(0.0, 1e9), st.sampled_from([0.0, 2.0**31 - 1.0, 1.5])), min_size=1, max_size=4)
frames = st.sampled_from(["laser", "base_link", "/laser", "", "odom", "x" * 300])
#: A planar pose: any position, a heading of any finite angle (the bags'
#: writer makes a quaternion of it).
poses = st.tuples(floats, floats, st.floats(-1e6, 1e6))


@st.composite
def hostile_messages(draw: st.DrawFn) -> dict[str, Any]:
    """What the messages of one bag hold."""
    times = draw(stamps)
    return {
        "stamps": times,
        "frames": [draw(frames) for _ in times],
        "beams": draw(st.integers(0, 4)),
        "ranges": draw(st.lists(floats, min_size=0, max_size=4)),
        "fan": (draw(floats), draw(floats), draw(floats)),
        "odometry": draw(st.lists(poses, min_size=0, max_size=3)),
        "tf": draw(st.lists(st.tuples(frames, frames, poses), max_size=3)),
        "range_topic": draw(st.booleans()),
    }


def _write(directory: Path, bag_format: str, m: dict[str, Any]) -> Path:
    with BagWriter(directory, "hostile", bag_format) as w:
        for i, (t, frame) in enumerate(zip(m["stamps"], m["frames"])):
            record_t = 0.01 * (i + 1)
            if m["range_topic"]:
                reading = (m["ranges"] or [1.0])[0]
                w.write("/scan", w.range(t, frame, reading, max_range=m["fan"][2]), record_t)
            else:
                ranges = (m["ranges"] + [1.0] * m["beams"])[: max(m["beams"], len(m["ranges"]))]
                angle_min, increment, range_max = m["fan"]
                w.write("/scan", w.laser_scan(t, frame, ranges, angle_min=angle_min, angle_increment=increment, range_max=range_max), record_t)
        for i, pose in enumerate(m["odometry"]):
            w.write("/odom", w.odometry(0.01 * i, pose), 0.01 * (i + 1))
        if m["tf"]:
            w.write("/tf", w.tf(0.0, *m["tf"]), 0.005)
        w.write("/tf_static", w.tf(0.0, ("base_link", "laser", (0.1, 0.0, 0.0))), 0.001)
    return w.path


@pytest.mark.parametrize("bag_format", FORMATS)
@settings(max_examples=40, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow])
@given(messages=hostile_messages(), use_odometry=st.booleans())
def test_hostile_messages_give_a_log_or_a_covmap_error(bag_format: str, messages: dict[str, Any], use_odometry: bool) -> None:
    need_rosbags()
    with tempfile.TemporaryDirectory() as tmp:
        bag = _write(Path(tmp), bag_format, messages)
        odom = "/odom" if use_odometry and messages["odometry"] else None
        try:
            log = covmap.Log.from_bag(bag, odom_topic=odom)
        except covmap.CovmapError:
            return
        assert len(log) == len(messages["stamps"])
        assert (log.timestamps[1:] >= log.timestamps[:-1]).all()
