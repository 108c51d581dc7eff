"""What real code writes (issue 27, cause 6): names the extractors read through option
objects, absolute prefixes joined at run time, values followed through lambdas, repeated
assignments, members and constants, and remapping arguments of one node."""

from __future__ import annotations

from pathlib import Path

from roslint_names.extract.cpp import extract as cpp
from roslint_names.model import FileFacts, Generation, Kind, NameUse, Role

FIXTURES = Path(__file__).parent / "fixtures"
ROS1, ROS2 = Generation.ROS1, Generation.ROS2
TOPIC, SERVICE = Kind.TOPIC, Kind.SERVICE


def cpp_fixture(name: str) -> FileFacts:
    return cpp.extract(name, (FIXTURES / "cpp" / name).read_bytes(), None, ROS2)


def known(facts: FileFacts) -> list[NameUse]:
    return [use for use in facts.names if not use.dynamic]


# ---------------------------------------------------------------------------------------
# roscpp's option objects


def test_roscpp_option_objects_name_their_endpoints() -> None:
    facts = cpp_fixture("cloud_relay_options.cpp")
    found = [
        (u.kind, u.role, u.value, u.type_name, u.namespace, u.api, u.span.line)
        for u in known(facts)
    ]
    assert found == [
        (
            TOPIC,
            Role.SUBSCRIBE,
            "/velodyne_points",
            "sensor_msgs::PointCloud2",
            "",
            "ros::SubscribeOptions::create",
            17,
        ),
        # advertised through the private handle: the name is under ~
        (
            TOPIC,
            Role.PUBLISH,
            "status",
            "std_msgs::String",
            "~",
            "ros::AdvertiseOptions::create",
            23,
        ),
        (
            TOPIC,
            Role.SUBSCRIBE,
            "/planning/mode",
            "std_msgs::String",
            "",
            "ros::SubscribeOptions::init",
            29,
        ),
        (
            SERVICE,
            Role.SERVE,
            "reset",
            "std_srvs::Trigger",
            "~",
            "ros::AdvertiseServiceOptions::create",
            34,
        ),
    ]
    # `nh_.subscribe(ops)` hands over the object: no unknown name is made of `ops`
    assert [u.value for u in facts.names if u.dynamic] == []
