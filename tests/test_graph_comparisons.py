"""RN403 compares what it should (issue 27, cause 7).

It keeps every endpoint whose facts are certain and leaves out only the ambiguous ones
(one side of a name with two types in one code); it compares ROS 1 services by their
definition's md5sum, as roscpp and rospy do.
"""

from __future__ import annotations

import hashlib
from pathlib import Path
from typing import Any

import pytest
from conftest import AMENT_PACKAGE, CATKIN_PACKAGE, write

from roslint_names.model import Generation, Kind, Span
from roslint_names.rule import RuleContext
from roslint_names.rules import message_type_mismatch
from roslint_names.workspace.graph import EdgeKind, Endpoint, Graph, Location, Reach
from roslint_names.workspace.interfaces import WELL_KNOWN, parse_service


def findings(run_cli: Any, root: Path, select: str, *options: str) -> list[dict[str, Any]]:
    result = run_cli(["check", "--format", "json", "--select", select, *options, "."], root)
    assert result.exit_code in (0, 1), result.stderr
    found: list[dict[str, Any]] = result.findings()
    return found


def places(found: list[dict[str, Any]]) -> list[tuple[str, str, int]]:
    return sorted((f["code"], f["path"], f["line"]) for f in found)


# ---------------------------------------------------------------------------------------
# 1. One topic with two types in one file: its certain endpoints are compared

# ros2/examples' rclcpp/wait_set/src/wait_set_topics_and_timer.cpp, with the third
# publisher's type changed: the wait loop then waits for a message that never comes.
WAIT_SET_TOPICS_AND_TIMER_CPP = """\
#include <chrono>
#include <memory>

#include "rclcpp/rclcpp.hpp"
#include "std_msgs/msg/int32.hpp"
#include "std_msgs/msg/string.hpp"

using namespace std::chrono_literals;

int32_t main(const int32_t argc, char ** const argv)
{
  rclcpp::init(argc, argv);

  auto node = std::make_shared<rclcpp::Node>("wait_set_listener");
  auto do_nothing = [](std_msgs::msg::String::UniquePtr) {assert(false);};

  auto sub1 = node->create_subscription<std_msgs::msg::String>("topicA", 1, do_nothing);
  auto sub2 = node->create_subscription<std_msgs::msg::String>("topicB", 1, do_nothing);
  auto sub3 = node->create_subscription<std_msgs::msg::String>("topicC", 1, do_nothing);

  std_msgs::msg::String msg1, msg2;
  std_msgs::msg::Int32 msg3;
  msg1.data = "Hello, world!";
  msg2.data = "Hello, world!";
  msg3.data = 3;

  const auto pub1 =
    node->create_publisher<std_msgs::msg::String>("topicA", 1);
  const auto pub2 =
    node->create_publisher<std_msgs::msg::String>("topicB", 1);
  const auto pub3 =
    node->create_publisher<std_msgs::msg::Int32>("topicC", 1);

  rclcpp::TimerBase::SharedPtr one_off_timer;
  auto timer_callback = [&]() {
      pub1->publish(msg1);
      pub2->publish(msg2);
      pub3->publish(msg3);
      one_off_timer->cancel();
    };
  one_off_timer = node->create_wall_timer(1s, timer_callback);

  rclcpp::WaitSet wait_set({{{sub1}, {sub2}, {sub3}}}, {}, {one_off_timer});
  auto num_recv = std::size_t();
  while (num_recv < 3U) {
    const auto wait_result = wait_set.wait(2s);
    if (wait_result.kind() == rclcpp::WaitResultKind::Ready) {
      ++num_recv;
    }
  }
  return 0;
}
"""

WAIT_SET_CMAKE = """\
cmake_minimum_required(VERSION 3.5)
project(examples_rclcpp_wait_set)
find_package(ament_cmake REQUIRED)
find_package(rclcpp REQUIRED)
find_package(std_msgs REQUIRED)
add_executable(wait_set_topics_and_timer src/wait_set_topics_and_timer.cpp)
ament_target_dependencies(wait_set_topics_and_timer rclcpp std_msgs)
ament_package()
"""


def test_a_file_using_one_topic_with_two_types_is_compared_on_each_side(
    run_cli: Any, tmp_path: Path
) -> None:
    package = "src/examples_rclcpp_wait_set"
    write(tmp_path, f"{package}/package.xml", AMENT_PACKAGE.format(name="examples_rclcpp_wait_set"))
    write(tmp_path, f"{package}/CMakeLists.txt", WAIT_SET_CMAKE)
    source = f"{package}/src/wait_set_topics_and_timer.cpp"
    write(tmp_path, source, WAIT_SET_TOPICS_AND_TIMER_CPP)
    found = findings(run_cli, tmp_path, "RN403")
    # topicC: subscribed as String (line 19), published as Int32 (line 32); topicA and
    # topicB agree and stay quiet.
    assert places(found) == [("RN403", source, 19), ("RN403", source, 32)]
    message = next(f["message"] for f in found if f["line"] == 19)
    assert "'/topicC'" in message and "'std_msgs/Int32'" in message


def _endpoint(edge: EdgeKind, type_name: str, node: str, *, path: str, line: int) -> Endpoint:
    return Endpoint(
        resource="/chatter",
        resource_kind=Kind.TOPIC,
        edge=edge,
        node=node,
        root="src/talkers/launch/talkers.launch.py",
        type_name=type_name,
        location=Location(path, Span(line, 5, line, 14)),
        written="chatter",
        reach=Reach(Generation.ROS2, packages=("talkers",)),
    )


def test_only_the_side_with_a_run_time_choice_is_left_out() -> None:
    # relay.py picks its publisher's type at run time (String or Int32: ambiguous), and
    # subscribes /chatter as String (certain); counter.py publishes /chatter as Int64.
    relay, counter = "src/talkers/talkers/relay.py", "src/talkers/talkers/counter.py"
    graph = Graph(
        nodes=(),
        endpoints=(
            _endpoint(EdgeKind.PUBLISH, "std_msgs/String", "/relay", path=relay, line=12),
            _endpoint(EdgeKind.PUBLISH, "std_msgs/Int32", "/relay", path=relay, line=14),
            _endpoint(EdgeKind.SUBSCRIBE, "std_msgs/String", "/relay", path=relay, line=15),
            _endpoint(EdgeKind.PUBLISH, "std_msgs/Int64", "/counter", path=counter, line=9),
        ),
    )
    found = list(message_type_mismatch.check_workspace(graph, RuleContext()))
    assert sorted((f.path, f.finding.span.line) for f in found) == [(counter, 9), (relay, 15)]


# ---------------------------------------------------------------------------------------
# 2. ROS 1 services by their definition

# genmsg's md5sums of these definitions, as rosservice/rossrv print them.
MD5SUMS = [
    ("std_srvs/Empty", "---\n", "d41d8cd98f00b204e9800998ecf8427e"),
    (
        "std_srvs/Trigger",
        "---\nbool success   # indicate successful run of triggered service\n"
        "string message # informational, e.g. for error messages\n",
        "937c9679a518e3a18d831e57125ea522",
    ),
    (
        "std_srvs/SetBool",
        "bool data # e.g. for hardware enabling / disabling\n---\n"
        "bool success   # indicate successful run of triggered service\n"
        "string message # informational, e.g. for error messages\n",
        "09fb03525b03e7ea1fd3992bafd87e16",
    ),
    (
        "roscpp_tutorials/TwoInts",
        "int64 a\nint64 b\n---\nint64 sum\n",
        "6a2e34150c00229791cc89ff309fff21",
    ),
    (
        "roscpp/SetLoggerLevel",
        "string logger\nstring level\n---\n",
        "51da076440d78ca1684d36c868df61ea",
    ),
]


@pytest.mark.parametrize(("name", "text", "md5sum"), MD5SUMS)
def test_a_definition_without_nested_types_hashes_to_genmsgs_md5sum(
    name: str, text: str, md5sum: str
) -> None:
    definition = parse_service(text, name.partition("/")[0])
    assert definition is not None
    assert hashlib.md5(definition.text.encode()).hexdigest() == md5sum
    if name in WELL_KNOWN:
        assert WELL_KNOWN[name] == definition


def test_definitions_agree_by_md5_text_not_by_spelling() -> None:
    spaced = parse_service("# adds\nint64  a   # first\nint64 b\n---\nint64 sum\n", "mine")
    plain = parse_service("int64 a\nint64 b\n---\nint64 sum", "theirs")
    narrower = parse_service("int64 a\nint32 b\n---\nint32 sum\n", "mine")
    assert spaced is not None and plain is not None and narrower is not None
    assert spaced.same_md5(plain) is True
    assert spaced.same_md5(narrower) is False
    # genmsg hashes the request's text then the response's into one md5: a lone field on
    # either side of the separator hashes alike
    asked, answered = parse_service("int64 a\n---\n", "x"), parse_service("---\nint64 a\n", "y")
    assert asked is not None and answered is not None and asked.same_md5(answered) is True
    # nested types: the same full name agrees; two names of one shape may or may not
    mine = parse_service("Header header\nPose target\n---\nbool ok\n", "nav_tools")
    same = parse_service("std_msgs/Header header\nnav_tools/Pose target\n---\nbool ok\n", "x")
    other = parse_service("Header header\ngeometry_msgs/Pose target\n---\nbool ok\n", "y")
    assert mine is not None and same is not None and other is not None
    assert mine.same_md5(same) is True
    assert mine.same_md5(other) is None
    # what genmsg refuses is no definition
    assert parse_service("int64 a b\n---\n", "broken") is None


TWO_INTS_SERVER_CPP = """\
#include "ros/ros.h"
#include "roscpp_tutorials/TwoInts.h"

bool add(roscpp_tutorials::TwoInts::Request  &req,
         roscpp_tutorials::TwoInts::Response &res )
{
  res.sum = req.a + req.b;
  return true;
}

int main(int argc, char **argv)
{
  ros::init(argc, argv, "add_two_ints_server");
  ros::NodeHandle n;
  ros::ServiceServer service = n.advertiseService("add_two_ints", add);
  ros::spin();
  return 0;
}
"""

ADD_TWO_INTS_CLIENT_PY = """\
#!/usr/bin/env python
import sys

import rospy
from rospy_tutorials.srv import {type}


def add_two_ints_client(x, y):
    rospy.wait_for_service("add_two_ints")
    add_two_ints = rospy.ServiceProxy("add_two_ints", {type})
    return add_two_ints(x, y).sum


if __name__ == "__main__":
    print(add_two_ints_client(int(sys.argv[1]), int(sys.argv[2])))
"""

CPP_TUTORIALS_CMAKE = """\
cmake_minimum_required(VERSION 3.0.2)
project(roscpp_tutorials)
find_package(catkin REQUIRED COMPONENTS message_generation roscpp)
add_service_files(DIRECTORY srv FILES TwoInts.srv)
generate_messages()
catkin_package()
add_executable(add_two_ints_server add_two_ints_server/add_two_ints_server.cpp)
target_link_libraries(add_two_ints_server ${catkin_LIBRARIES})
"""

TUTORIALS_LAUNCH = """\
<launch>
  <node name="a2i_server" pkg="roscpp_tutorials" type="add_two_ints_server"/>
  <node name="a2i_client" pkg="rospy_tutorials" type="add_two_ints_client" args="1 2"/>
</launch>
"""


def ros_tutorials(root: Path, client_type: str) -> None:
    """ros_tutorials reduced: roscpp's server of TwoInts, rospy's client of ``client_type``."""
    cpp, py = "src/roscpp_tutorials", "src/rospy_tutorials"
    write(root, f"{cpp}/package.xml", CATKIN_PACKAGE.format(name="roscpp_tutorials"))
    write(root, f"{cpp}/CMakeLists.txt", CPP_TUTORIALS_CMAKE)
    write(root, f"{cpp}/srv/TwoInts.srv", "int64 a\nint64 b\n---\nint64 sum\n")
    write(root, f"{cpp}/add_two_ints_server/add_two_ints_server.cpp", TWO_INTS_SERVER_CPP)
    write(root, f"{py}/package.xml", CATKIN_PACKAGE.format(name="rospy_tutorials"))
    write(root, f"{py}/srv/AddTwoInts.srv", "int64 a\nint64 b\n---\nint64 sum\n")
    write(
        root,
        f"{py}/srv/BadTwoInts.srv",
        "# Bad version of AddTwoInts for unit testing\nint64 a\nint32 b\n---\nint32 sum\n",
    )
    write(
        root,
        f"{py}/005_add_two_ints/add_two_ints_client",
        ADD_TWO_INTS_CLIENT_PY.format(type=client_type),
    )
    write(root, f"{py}/launch/add_two_ints.launch", TUTORIALS_LAUNCH)


def test_two_ros1_service_types_of_one_definition_connect(run_cli: Any, tmp_path: Path) -> None:
    ros_tutorials(tmp_path, "AddTwoInts")
    assert findings(run_cli, tmp_path, "RN403") == []


def test_two_ros1_service_definitions_that_differ_never_connect(
    run_cli: Any, tmp_path: Path
) -> None:
    ros_tutorials(tmp_path, "BadTwoInts")
    found = findings(run_cli, tmp_path, "RN403")
    assert places(found) == [
        ("RN403", "src/roscpp_tutorials/add_two_ints_server/add_two_ints_server.cpp", 15),
        ("RN403", "src/rospy_tutorials/005_add_two_ints/add_two_ints_client", 10),
    ]
    message = next(f["message"] for f in found if f["line"] == 10)
    assert "'rospy_tutorials/BadTwoInts'" in message
    assert "'roscpp_tutorials/TwoInts'" in message and "md5sum" in message


def test_a_well_known_definition_is_compared_without_its_srv_file(
    run_cli: Any, tmp_path: Path
) -> None:
    # turtlesim serves /reset as std_srvs/Empty; a client calling it as Trigger waits for
    # a response roscpp never lets through. Neither .srv is in the workspace.
    write(tmp_path, "src/turtle_tools/package.xml", CATKIN_PACKAGE.format(name="turtle_tools"))
    write(
        tmp_path,
        "src/turtle_tools/src/sim.cpp",
        "#include <ros/ros.h>\n#include <std_srvs/Empty.h>\n\n"
        "bool reset(std_srvs::Empty::Request&, std_srvs::Empty::Response&) { return true; }\n\n"
        "int main(int argc, char** argv)\n{\n"
        '  ros::init(argc, argv, "sim");\n  ros::NodeHandle nh;\n'
        '  ros::ServiceServer server = nh.advertiseService("reset", reset);\n'
        "  ros::spin();\n}\n",
    )
    write(
        tmp_path,
        "src/turtle_tools/src/resetter.cpp",
        "#include <ros/ros.h>\n#include <std_srvs/Trigger.h>\n\n"
        "int main(int argc, char** argv)\n{\n"
        '  ros::init(argc, argv, "resetter");\n  ros::NodeHandle nh;\n'
        '  ros::ServiceClient client = nh.serviceClient<std_srvs::Trigger>("reset");\n'
        "  std_srvs::Trigger srv;\n  client.call(srv);\n}\n",
    )
    found = findings(run_cli, tmp_path, "RN403")
    assert places(found) == [
        ("RN403", "src/turtle_tools/src/resetter.cpp", 8),
        ("RN403", "src/turtle_tools/src/sim.cpp", 10),
    ]


def test_an_edited_definition_is_not_served_from_a_stored_run(run_cli: Any, tmp_path: Path) -> None:
    ros_tutorials(tmp_path, "BadTwoInts")
    assert len(findings(run_cli, tmp_path, "RN403")) == 2
    bad = tmp_path / "src/rospy_tutorials/srv/BadTwoInts.srv"
    bad.write_text("int64 a\nint64 b\n---\nint64 sum\n")  # now AddTwoInts' definition
    assert findings(run_cli, tmp_path, "RN403") == []


def test_ros1_topics_of_shape_shifter_connect_to_any_type(run_cli: Any, tmp_path: Path) -> None:
    # ros_comm's topic_tools test: a ShapeShifter subscriber hears a std_msgs/String.
    write(tmp_path, "src/topic_tools/package.xml", CATKIN_PACKAGE.format(name="topic_tools"))
    write(
        tmp_path,
        "src/topic_tools/src/relay_check.cpp",
        "#include <ros/ros.h>\n#include <std_msgs/String.h>\n"
        '#include "topic_tools/shape_shifter.h"\n\n'
        "void morph(const topic_tools::ShapeShifter::ConstPtr& msg) {}\n\n"
        "int main(int argc, char** argv)\n{\n"
        '  ros::init(argc, argv, "relay_check");\n  ros::NodeHandle nh;\n'
        '  ros::Subscriber sub = nh.subscribe<topic_tools::ShapeShifter>("loopback", 10, morph);\n'
        '  ros::Publisher pub = nh.advertise<std_msgs::String>("loopback", 10);\n'
        "  ros::spin();\n}\n",
    )
    assert findings(run_cli, tmp_path, "RN403") == []
