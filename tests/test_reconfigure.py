"""dynamic_reconfigure ``.cfg`` files (issue 28, part 2): the parameters a config
generates, the nodes whose servers read them, and the names the per-name rules judge.

A ``.cfg`` is a Python script catkin runs (dynamic_reconfigure's
``parameter_generator_catkin.py``): ``gen.add(name, type, level, description, ...)`` adds
a parameter, ``add_group`` groups add to the same namespace, ``gen.generate(PACKAGE,
node, "Name")`` generates ``pkg::NameConfig``. A node serving that config reads every one
of its names, so its parameter set is complete again when the ``.cfg`` is in the
workspace.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from conftest import AMENT_PACKAGE, CATKIN_PACKAGE, write

from roslint_names.discover import classify
from roslint_names.extract.build import reconfigure
from roslint_names.extract.parameter_traits import reconfigure_servers
from roslint_names.model import Generation, Kind, Language, Span

ROS1, ROS2 = Generation.ROS1, Generation.ROS2

# A config as navigation's planners write them: a module constant for the package, a
# group, an enum, and the generate call wrapped in exit().
PLANNER_CFG = (Path(__file__).parent / "fixtures" / "reconfigure" / "SlowPlanner.cfg").read_text(
    encoding="utf-8"
)
PLANNER_NAMES = [
    "max_vel_x",
    "min_vel_x",
    "sim_time",
    "vx_samples",
    "drive_mode",
    "restore_defaults",
]

PLANNER_CMAKE = """\
cmake_minimum_required(VERSION 3.0.2)
project(slow_planner)
find_package(catkin REQUIRED COMPONENTS roscpp geometry_msgs dynamic_reconfigure)
generate_dynamic_reconfigure_options(cfg/SlowPlanner.cfg)
catkin_package()
include_directories(${catkin_INCLUDE_DIRS})
add_executable(slow_planner_node src/slow_planner_node.cpp)
add_dependencies(slow_planner_node ${PROJECT_NAME}_gencfg)
target_link_libraries(slow_planner_node ${catkin_LIBRARIES})
"""

PLANNER_NODE = """\
#include <ros/ros.h>
#include <geometry_msgs/Twist.h>
#include <dynamic_reconfigure/server.h>
#include <slow_planner/SlowPlannerConfig.h>

class SlowPlanner
{
public:
  SlowPlanner() : private_nh_("~")
  {
    private_nh_.param("controller_frequency", controller_frequency_, 20.0);
    cmd_pub_ = nh_.advertise<geometry_msgs::Twist>("cmd_vel", 1);
    dsrv_ = new dynamic_reconfigure::Server<slow_planner::SlowPlannerConfig>(ros::NodeHandle("~"));
    dynamic_reconfigure::Server<slow_planner::SlowPlannerConfig>::CallbackType cb =
        boost::bind(&SlowPlanner::reconfigure, this, _1, _2);
    dsrv_->setCallback(cb);
  }

private:
  void reconfigure(slow_planner::SlowPlannerConfig& config, uint32_t level)
  {
    max_vel_x_ = config.max_vel_x;
  }
  ros::NodeHandle nh_, private_nh_;
  ros::Publisher cmd_pub_;
  double controller_frequency_, max_vel_x_;
  dynamic_reconfigure::Server<slow_planner::SlowPlannerConfig>* dsrv_;
};

int main(int argc, char** argv)
{
  ros::init(argc, argv, "slow_planner");
  SlowPlanner planner;
  ros::spin();
  return 0;
}
"""

PLANNER_LAUNCH = """\
<launch>
  <node pkg="slow_planner" type="slow_planner_node" name="slow_planner" output="screen">
    <param name="max_vel_x" value="0.4"/>
    <rosparam file="$(find slow_planner)/config/planner.yaml" command="load"/>
  </node>
</launch>
"""


def planner_package(root: Path, cfg: str = PLANNER_CFG) -> Path:
    directory = root / "src" / "slow_planner"
    write(directory, "package.xml", CATKIN_PACKAGE.format(name="slow_planner"))
    write(directory, "CMakeLists.txt", PLANNER_CMAKE)
    write(directory, "cfg/SlowPlanner.cfg", cfg)
    write(directory, "src/slow_planner_node.cpp", PLANNER_NODE)
    write(directory, "launch/planner.launch", PLANNER_LAUNCH)
    write(directory, "config/planner.yaml", "sim_time: 2.0\nvx_samples: 6\n")
    return directory


def extract(text: str, generation: Generation | None = ROS1) -> Any:
    return reconfigure.extract("cfg/SlowPlanner.cfg", text.encode(), generation, ROS2)


def graph_node(run_cli: Any, root: Path, name: str) -> dict[str, Any]:
    result = run_cli(["graph", "--format", "json", "--no-cache", "."], root)
    assert result.exit_code == 0, result.stderr
    (node,) = [node for node in json.loads(result.stdout)["nodes"] if node["name"] == name]
    found: dict[str, Any] = node
    return found


# --- reading a .cfg ----------------------------------------------------------------------


def test_config_names_groups_and_generated_class() -> None:
    facts = extract(PLANNER_CFG)
    config = facts.reconfigure
    assert facts.language is Language.RECONFIGURE and facts.generation is ROS1
    assert (config.package, config.name, config.complete) == ("slow_planner", "SlowPlanner", True)
    assert [name for name, _ in config.parameters] == PLANNER_NAMES
    # The enum's constants are no parameters; every name is one judged where it is chosen.
    assert [(use.kind, use.value) for use in facts.names] == [
        (Kind.PARAMETER, name) for name in PLANNER_NAMES
    ]
    # The span is the name's literal, quotes included, as in code.
    assert config.parameters[0][1] == Span(8, 9, 8, 20)
    assert config.parameters[2][1] == Span(12, 16, 12, 26)


def test_spans_count_code_points_and_python2_is_read() -> None:
    text = (
        "# -*- coding: utf-8 -*-\n"
        "from dynamic_reconfigure.parameter_generator_catkin import *\n"
        "gen = ParameterGenerator()\n"
        'print "Génération"\n'
        'gen.add("é_rate", double_t, 0, "Débit", 1.0); gen.add("rate", double_t, 0, "x", 1.0)\n'
        'exit(gen.generate("demo", "demo", "Demo"))\n'
    )
    facts = extract(text)
    assert facts.parse_errors == ()
    assert facts.reconfigure.parameters == (
        ("é_rate", Span(5, 9, 5, 17)),
        ("rate", Span(5, 55, 5, 61)),
    )


def test_generator_handed_to_a_helper_leaves_the_config_open() -> None:
    """navigation's DWAPlanner.cfg: ``add_generic_localplanner_params(gen)`` adds the
    parameters of base_local_planner's Python module."""
    text = PLANNER_CFG.replace(
        "gen = ParameterGenerator()\n",
        "gen = ParameterGenerator()\nadd_generic_localplanner_params(gen)\n",
    )
    config = extract(text).reconfigure
    assert config.complete is False
    assert [name for name, _ in config.parameters] == PLANNER_NAMES


def test_names_built_at_run_time_leave_the_config_open() -> None:
    text = PLANNER_CFG.replace(
        'gen.add("restore_defaults"',
        'for axis in ("x", "y"):\n    gen.add("acc_lim_" + axis, double_t, 0, "a", 2.5)\n'
        'gen.add("restore_defaults"',
    )
    config = extract(text).reconfigure
    assert config.complete is False


def test_other_spellings_of_the_generator() -> None:
    """velodyne's ``import ... as pgc``, an unqualified name for the config's package,
    keyword arguments."""
    text = (
        "import dynamic_reconfigure.parameter_generator_catkin as pgc\n"
        "gen = pgc.ParameterGenerator()\n"
        'gen.add(name="view_width", paramtype=pgc.double_t, level=0, description="w")\n'
        'exit(gen.generate(pkgname="velodyne_pointcloud", nodename="n", name="TransformNode"))\n'
    )
    config = extract(text).reconfigure
    assert (config.package, config.name) == ("velodyne_pointcloud", "TransformNode")
    assert [name for name, _ in config.parameters] == ["view_width"]


def test_not_a_config() -> None:
    # A ROS 2 package's leftover .cfg (moveit2): nothing generates it.
    assert extract(PLANNER_CFG, ROS2).names == ()
    assert extract(PLANNER_CFG, ROS2).reconfigure is None
    # navigation's LocalPlannerLimits.cfg: all of it commented out.
    commented = "# gen = ParameterGenerator()\n# exit(gen.generate(PACKAGE, 'a', 'B'))\n"
    assert extract(commented).reconfigure is None
    broken = extract("gen = ParameterGenerator(\n")
    assert broken.parse_errors and broken.parse_errors[0].message.startswith("not valid Python")


def test_discovery_tells_a_config_from_other_cfg_files(tmp_path: Path) -> None:
    config = write(tmp_path, "cfg/SlowPlanner.cfg", PLANNER_CFG)
    lint = write(tmp_path, "CPPLINT.cfg", "set noparent\nlinelength=100\n")
    setup = write(tmp_path, "setup.cfg", "[develop]\nscript_dir=$base/lib/demo\n")
    assert classify(config) is Language.RECONFIGURE
    assert classify(lint) is None
    assert classify(setup) is Language.SETUP_CFG


def test_servers_the_code_shows() -> None:
    assert reconfigure_servers(PLANNER_NODE.encode(), python=False) == (
        "slow_planner::SlowPlannerConfig",
    )
    # velodyne_driver's, broken over two lines; dwa_local_planner's, in its own namespace.
    split = (
        b"srv_ = boost::make_shared <dynamic_reconfigure::Server<velodyne_driver::\n"
        b"    VelodyneNodeConfig> > (private_nh);"
    )
    assert reconfigure_servers(split, python=False) == ("velodyne_driver::VelodyneNodeConfig",)
    own = b"dsrv_ = new dynamic_reconfigure::Server<DWAPlannerConfig>(private_nh);"
    assert reconfigure_servers(own, python=False) == ("DWAPlannerConfig",)
    rospy = (
        b"from dynamic_reconfigure.server import Server\n"
        b"from slow_planner.cfg import SlowPlannerConfig\n"
        b"srv = Server(SlowPlannerConfig, callback)\n"
    )
    assert reconfigure_servers(rospy, python=True) == ("slow_planner::SlowPlannerConfig",)
    # A client needs no config class and serves nothing.
    assert reconfigure_servers(b"import dynamic_reconfigure.client\n", python=True) == ()


# --- the node serving it -----------------------------------------------------------------


def test_node_serving_a_config_reads_its_names(run_cli: Any, tmp_path: Path) -> None:
    planner_package(tmp_path)
    node = graph_node(run_cli, tmp_path, "/slow_planner")
    parameters = node["code_parameters"]
    assert parameters["reconfigure"] == ["src/slow_planner/cfg/SlowPlanner.cfg"]
    assert parameters["read"] == sorted([*PLANNER_NAMES, "controller_frequency"])
    assert parameters["complete"] is True and parameters["incomplete"] == []


def test_config_not_in_the_workspace_or_open_keeps_the_node_incomplete(
    run_cli: Any, tmp_path: Path
) -> None:
    directory = planner_package(tmp_path)
    (directory / "cfg" / "SlowPlanner.cfg").unlink()
    parameters = graph_node(run_cli, tmp_path, "/slow_planner")["code_parameters"]
    assert parameters["reconfigure"] == []
    assert parameters["incomplete"] == ["dynamic-reconfigure"]
    helper = PLANNER_CFG.replace(
        "gen = ParameterGenerator()\n",
        "gen = ParameterGenerator()\nadd_generic_localplanner_params(gen)\n",
    )
    write(directory, "cfg/SlowPlanner.cfg", helper)
    parameters = graph_node(run_cli, tmp_path, "/slow_planner")["code_parameters"]
    assert parameters["reconfigure"] == ["src/slow_planner/cfg/SlowPlanner.cfg"]
    assert "max_vel_x" in parameters["read"]
    assert parameters["incomplete"] == ["dynamic-reconfigure"]


def test_config_of_the_package_namespace_and_of_rospy(run_cli: Any, tmp_path: Path) -> None:
    directory = planner_package(tmp_path)
    unqualified = PLANNER_NODE.replace("slow_planner::SlowPlannerConfig", "SlowPlannerConfig")
    write(directory, "src/slow_planner_node.cpp", "namespace slow_planner {}\n" + unqualified)
    parameters = graph_node(run_cli, tmp_path, "/slow_planner")["code_parameters"]
    assert parameters["complete"] is True and "vx_samples" in parameters["read"]
    write(
        directory,
        "scripts/speed_limiter",
        "#!/usr/bin/env python\n"
        "import rospy\n"
        "from geometry_msgs.msg import Twist\n"
        "from dynamic_reconfigure.server import Server\n"
        "from slow_planner.cfg import SlowPlannerConfig\n\n\n"
        "def callback(config, level):\n"
        "    return config\n\n\n"
        'if __name__ == "__main__":\n'
        '    rospy.init_node("speed_limiter")\n'
        "    server = Server(SlowPlannerConfig, callback)\n"
        '    pub = rospy.Publisher("cmd_vel_limited", Twist, queue_size=1)\n'
        "    rospy.spin()\n",
    )
    parameters = graph_node(run_cli, tmp_path, "/speed_limiter")["code_parameters"]
    assert parameters["reconfigure"] == ["src/slow_planner/cfg/SlowPlanner.cfg"]
    assert parameters["read"] == sorted(PLANNER_NAMES)
    assert parameters["complete"] is True


# --- the names the per-name rules judge ----------------------------------------------------


def test_cfg_names_are_judged_where_chosen_and_never_renamed_alone(
    run_cli: Any, tmp_path: Path
) -> None:
    """A ``.cfg``'s name is also a field of the generated class (``config.maxVelX``):
    RN203 reports it in the ``.cfg``, and offers no rename, even with --unsafe-fixes."""
    camel = PLANNER_CFG.replace('"max_vel_x"', '"maxVelX"')
    planner_package(tmp_path, camel)
    result = run_cli(
        ["check", "--format", "json", "--select", "RN203", "--unsafe-fixes", "--no-cache", "."],
        tmp_path,
    )
    (finding,) = result.findings()
    assert (finding["path"], finding["line"]) == ("src/slow_planner/cfg/SlowPlanner.cfg", 8)
    assert "maxVelX" in finding["message"] and finding.get("fix") is None
    suppressed = camel.replace(", 0.55, 0, 20)", ", 0.55, 0, 20)  # noqa: RN203")
    write(tmp_path, "src/slow_planner/cfg/SlowPlanner.cfg", suppressed)
    result = run_cli(["check", "--format", "json", "--select", "RN203", "."], tmp_path)
    assert result.findings() == []


def test_a_ros2_package_cfg_is_not_judged(run_cli: Any, tmp_path: Path) -> None:
    directory = tmp_path / "src" / "moveit_ros_planning"
    write(directory, "package.xml", AMENT_PACKAGE.format(name="moveit_ros_planning"))
    write(directory, "cfg/SlowPlanner.cfg", PLANNER_CFG.replace('"max_vel_x"', '"maxVelX"'))
    result = run_cli(["check", "--format", "json", "--select", "RN203", "."], tmp_path)
    assert result.findings() == []
