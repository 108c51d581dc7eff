"""C++ names held in constants of a header of the package (``symbols``), end to end.

The layout follows moveit's move_group: a header of name constants with no ROS code in it,
capabilities in ``src/`` that include it, and a client in another package that uses the
same constants (that package did not choose them).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from conftest import AMENT_PACKAGE, write

CAPABILITY_NAMES_HPP = """\
#pragma once

#include <string>

namespace arm_server
{
static const std::string PLAN_SERVICE_NAME = "plan_path";  // within the node's namespace
static const std::string RECOGNITION_ACTION =
    "/recognize_objects";  // the perception server's
#define STATUS_TOPIC "arm_status"
}  // namespace arm_server
"""

CAPABILITY_HPP = """\
#pragma once

#include <rclcpp/rclcpp.hpp>
#include "arm_server/capability_names.hpp"
"""

PLAN_CAPABILITY_CPP = """\
#include "arm_server/capability.hpp"

#include <arm_msgs/srv/plan_path.hpp>
#include <std_msgs/msg/string.hpp>

namespace arm_server
{
class PlanCapability : public rclcpp::Node
{
public:
  PlanCapability() : Node("plan_capability")
  {
    service_ = create_service<arm_msgs::srv::PlanPath>(
        PLAN_SERVICE_NAME, [](const auto&, auto) {});
    status_pub_ = create_publisher<std_msgs::msg::String>(STATUS_TOPIC, 10);
    recognition_ = rclcpp_action::create_client<arm_msgs::action::Recognize>(
        this, RECOGNITION_ACTION);
  }

private:
  rclcpp::Service<arm_msgs::srv::PlanPath>::SharedPtr service_;
  rclcpp::Publisher<std_msgs::msg::String>::SharedPtr status_pub_;
  rclcpp_action::Client<arm_msgs::action::Recognize>::SharedPtr recognition_;
};
}  // namespace arm_server
"""

CLIENT_CPP = """\
#include <arm_server/capability_names.hpp>
#include <arm_msgs/action/recognize.hpp>
#include <rclcpp/rclcpp.hpp>
#include <rclcpp_action/rclcpp_action.hpp>

int main(int argc, char** argv)
{
  rclcpp::init(argc, argv);
  auto node = rclcpp::Node::make_shared("arm_client");
  auto client = rclcpp_action::create_client<arm_msgs::action::Recognize>(
      node, arm_server::RECOGNITION_ACTION);
  rclcpp::spin(node);
}
"""


def workspace(root: Path) -> None:
    write(root, "src/arm_server/package.xml", AMENT_PACKAGE.format(name="arm_server"))
    write(root, "src/arm_server/include/arm_server/capability_names.hpp", CAPABILITY_NAMES_HPP)
    write(root, "src/arm_server/include/arm_server/capability.hpp", CAPABILITY_HPP)
    write(root, "src/arm_server/src/plan_capability.cpp", PLAN_CAPABILITY_CPP)
    write(root, "src/arm_client/package.xml", AMENT_PACKAGE.format(name="arm_client"))
    write(root, "src/arm_client/src/client.cpp", CLIENT_CPP)


def test_a_constant_of_an_included_header_of_the_package_names_the_endpoint(
    run_cli: Any, tmp_path: Path
) -> None:
    workspace(tmp_path)
    result = run_cli(["check", "--format", "json", "--no-cache", "."], tmp_path)
    found = [(f["code"], f["path"], f["line"]) for f in result.findings()]
    # Through capability.hpp: the absolute action name is the package's own choice. The
    # client in arm_client uses the same constant, chosen by arm_server: not reported.
    assert found == [("RN202", "src/arm_server/src/plan_capability.cpp", 17)]
    graph = json.loads(run_cli(["graph", "--format", "json", "--no-cache", "."], tmp_path).stdout)
    names = {service["name"] for service in graph["services"]}
    assert "/plan_path" in names
    assert "/arm_status" in {topic["name"] for topic in graph["topics"]}


def test_the_same_findings_for_a_run_of_the_file_alone_and_with_workers(
    run_cli: Any, tmp_path: Path
) -> None:
    workspace(tmp_path)
    whole = run_cli(["check", "--no-cache", "--jobs", "2", "."], tmp_path).stdout
    alone = run_cli(
        ["check", "--no-cache", "src/arm_server/src/plan_capability.cpp"], tmp_path
    ).stdout
    assert "RN202" in whole
    assert alone == whole
    assert "plan_capability.cpp:17" in alone


def test_a_constant_two_headers_define_differently_stays_unknown(
    run_cli: Any, tmp_path: Path
) -> None:
    workspace(tmp_path)
    write(
        tmp_path,
        "src/arm_server/include/arm_server/capability.hpp",
        CAPABILITY_HPP + '#include "arm_server/legacy_names.hpp"\n',
    )
    write(
        tmp_path,
        "src/arm_server/include/arm_server/legacy_names.hpp",
        'static const std::string RECOGNITION_ACTION = "recognize";\n',
    )
    result = run_cli(["check", "--format", "json", "--no-cache", "."], tmp_path)
    assert result.findings() == []


def test_the_language_server_resolves_an_edited_buffer_as_the_cli_does(tmp_path: Path) -> None:
    from roslint_names.config import load_settings
    from roslint_names.registry import load_registry
    from roslint_names.session import Session

    workspace(tmp_path)
    registry = load_registry()
    session = Session(tmp_path, load_settings(None, tmp_path, registry), registry, None)
    session.load()
    path = tmp_path / "src/arm_server/src/plan_capability.cpp"
    edited = PLAN_CAPABILITY_CPP.replace("this, RECOGNITION_ACTION", "this, RECOGNITION_ACTION ")
    found = session.check(path, edited) or []
    assert [(d.code, d.span.line) for d in found] == [("RN202", 17)]
    assert "'/recognize_objects'" in found[0].message
