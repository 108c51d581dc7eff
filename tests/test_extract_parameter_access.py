"""What code does with each parameter name: declare, read (throwing or not), check,
write, read another node's; names under a run-time prefix; node options and libraries that
leave a node's parameters open; the classes a file defines with their bases."""

from __future__ import annotations

from roslint_names.extract.cpp import extract as cpp
from roslint_names.extract.parameter_traits import cpp_class_bases, python_class_bases
from roslint_names.extract.python import extract as python
from roslint_names.model import FileFacts, Generation, Kind, ParameterAccess, ParameterTrait

D, R, Q = ParameterAccess.DECLARE, ParameterAccess.READ, ParameterAccess.READ_QUIETLY
P, C, X = ParameterAccess.READ_PREFIX, ParameterAccess.CHECK, ParameterAccess.REMOTE


def _cpp(text: str) -> FileFacts:
    return cpp.extract("src/node.cpp", text.encode(), Generation.ROS2, Generation.ROS2)


def _python(text: str) -> FileFacts:
    return python.extract("node.py", text.encode(), Generation.ROS2, Generation.ROS2)


def _parameters(facts: FileFacts) -> list[tuple[str, ParameterAccess | None, str | None]]:
    return [
        (use.value, use.access, use.suffix) for use in facts.names if use.kind is Kind.PARAMETER
    ]


CONTROLLER = """
#include "nav2_util/node_utils.hpp"
#include "rclcpp/rclcpp.hpp"

namespace dwb_core
{
void DWBLocalPlanner::configure(const rclcpp_lifecycle::LifecycleNode::WeakPtr & parent)
{
  auto node = parent.lock();
  nav2_util::declare_parameter_if_not_declared(
    node, plugin_name_ + ".max_vel_x", rclcpp::ParameterValue(0.26));
  node->get_parameter(plugin_name_ + ".max_vel_x", max_vel_x_);
  std::string critic_prefix = plugin_name_ + ".critics";
  auto rate = node->declare_or_get_parameter(plugin_name_ + ".rate", 10.0);
  double tolerance = nav2::declare_or_get_parameter(node, "tolerance", 0.1);
  std::string type = nav2::get_plugin_type_param(node, plugin_name_);
}
}  // namespace dwb_core
"""


def test_nav2_plugin_parameters_sit_under_a_run_time_prefix() -> None:
    assert _parameters(_cpp(CONTROLLER)) == [
        ('plugin_name_ + ".max_vel_x"', D, ".max_vel_x"),
        ('plugin_name_ + ".max_vel_x"', Q, ".max_vel_x"),
        ('plugin_name_ + ".rate"', D, ".rate"),
        ("tolerance", D, None),
        ("plugin_name_", D, ".plugin"),
    ]


NODE = """
#include "rclcpp/rclcpp.hpp"

class Driver : public rclcpp::Node
{
public:
  Driver()
  : Node("driver")
  {
    declare_parameter("rate", 10.0);
    double rate;
    get_parameter("rate", rate);
    double gain = get_parameter("gain").as_double();
    bool sim = this->get_parameter_or("sim", false);
    declare_parameters("limits", {{"min", 0.0}, {"max", 1.0}});
    auto both = get_parameters({"a", "b"});
    std::map<std::string, rclcpp::Parameter> filters;
    get_parameters("filters", filters);
    if (!has_parameter("port")) {}
    auto client = std::make_shared<rclcpp::SyncParametersClient>(this, "camera");
    auto remote = client->get_parameters({"exposure"});
  }
};
"""


def test_rclcpp_reads_that_throw_and_reads_that_do_not() -> None:
    assert _parameters(_cpp(NODE)) == [
        ("rate", D, None),
        ("rate", Q, None),  # get_parameter(name, value): false when undeclared
        ("gain", R, None),  # get_parameter(name): throws when undeclared
        ("sim", Q, None),
        ("limits.min", D, None),
        ("limits.max", D, None),
        ("a", R, None),
        ("b", R, None),
        ("filters", P, None),
        ("port", C, None),
        ("exposure", X, None),  # a parameter client asks another node
    ]


def test_ros2_control_auto_declare_declares() -> None:
    text = 'void C::on_init() { auto_declare<int>("update_rate", 100); }\n'
    assert _parameters(_cpp(text)) == [("update_rate", D, None)]


RCLPY = """
import rclpy
from rclpy.node import Node


class Driver(Node):
    def __init__(self):
        super().__init__('driver')
        self.declare_parameter('rate', 10.0)
        self.get_parameter('gain')
        self.get_parameter_or('sim')
        self.declare_parameters('limits', [('min', 0.0), ('max', 1.0)])
        self.get_parameter(f'{self.prefix}.max_vel')
        self.get_parameters_by_prefix('filters')
        self.get_parameters_by_prefix('')
        self.camera_client.get_parameters(['exposure'])
"""


def test_rclpy_parameter_access() -> None:
    assert _parameters(_python(RCLPY)) == [
        ("rate", D, None),
        ("gain", R, None),
        ("sim", Q, None),
        ("limits.min", D, None),
        ("limits.max", D, None),
        ("f'{self.prefix}.max_vel'", R, ".max_vel"),
        ("filters", P, None),
        ("exposure", X, None),
    ]


def test_node_options_that_open_a_node_parameters() -> None:
    main = """
#include "rclcpp/rclcpp.hpp"
int main(int argc, char ** argv)
{
  rclcpp::init(argc, argv);
  rclcpp::NodeOptions options;
  options.allow_undeclared_parameters(true);
  options.automatically_declare_parameters_from_overrides(true);
  rclcpp::spin(std::make_shared<Driver>(options));
}
"""
    assert _cpp(main).parameter_traits == (
        ParameterTrait.ALLOW_UNDECLARED,
        ParameterTrait.FROM_OVERRIDES,
    )
    closed = "rclcpp::NodeOptions().allow_undeclared_parameters(false);\nrclcpp::init(a, b);\n"
    assert _cpp(closed).parameter_traits == ()
    rclpy = RCLPY.replace("'driver')", "'driver', allow_undeclared_parameters=True)")
    assert _python(rclpy).parameter_traits == (ParameterTrait.ALLOW_UNDECLARED,)


def test_plugins_and_generated_parameters() -> None:
    server = """
#include "pluginlib/class_loader.hpp"
#include "rclcpp/rclcpp.hpp"
ControllerServer::ControllerServer() : nav2::LifecycleNode("controller_server") {}
void ControllerServer::load() { controller_ = lp_loader_.createUniqueInstance(type); }
"""
    assert _cpp(server).parameter_traits == (ParameterTrait.PLUGINS,)
    generated = """
#include "joint_trajectory_controller_parameters.hpp"
void C::on_init() { param_listener_ = std::make_shared<ParamListener>(get_node()); }
"""
    assert _cpp(generated).parameter_traits == (ParameterTrait.GENERATED,)


def test_class_bases() -> None:
    header = b"""
class NAV2_EXPORT ControllerServer : public nav2::LifecycleNode, private Helper<int, float>
{
  enum class Mode : uint8_t { A, B };
};
struct Options {};
"""
    assert cpp_class_bases(header) == (
        ("ControllerServer", ("nav2::LifecycleNode", "Helper")),
        ("Options", ()),
    )
    module = b"class Driver(Node):\n    pass\n\nclass Meta(Base, metaclass=M):\n    pass\n"
    assert python_class_bases(module) == (("Driver", ("Node",)), ("Meta", ("Base",)))


def test_a_descriptor_name_set_once_is_the_parameter_name() -> None:
    """image_pipeline's image_view names parameters through their descriptors."""
    text = """
void ImageViewNode::configure()
{
  rcl_interfaces::msg::ParameterDescriptor colormap_descriptor;
  colormap_descriptor.name = "colormap";
  colormap_descriptor.set__integer_range({rcl_interfaces::msg::IntegerRange()});
  colormap_ = this->declare_parameter<int>(colormap_descriptor.name, -1, colormap_descriptor);
  rcl_interfaces::msg::ParameterDescriptor other;
  if (flip) {
    other.name = "flipped";
  }
  declare_parameter(other.name, 0);
}
"""
    assert _parameters(_cpp(text)) == [("colormap", D, None), ("other.name", D, None)]


def test_a_declaring_api_own_body_declares_nothing_of_its_own() -> None:
    """nav2_ros_common's node_utils.hpp: the callers' names are what it declares."""
    header = """
template<typename NodeT>
inline void declare_parameter_if_not_declared(
  NodeT node, const std::string & parameter_name, const rclcpp::ParameterValue & value)
{
  if (!node->has_parameter(parameter_name)) {
    node->declare_parameter(parameter_name, value);
  }
}
void load_limits(rclcpp::Node * node, const std::string & name)
{
  node->declare_parameter(name, 1.0);
}
"""
    facts = cpp.extract(
        "include/a/node_utils.hpp", header.encode(), Generation.ROS2, Generation.ROS2
    )
    assert _parameters(facts) == [
        ("parameter_name", None, None),  # the API's body: checks and declares what it is given
        ("parameter_name", None, None),
        ("name", D, None),  # a project's own helper: a name declared at run time
    ]


def test_strings_the_extractor_did_not_read_for() -> None:
    from roslint_names.extract.literals import unexplained_literals

    code = b"""
// "gain" in a comment is no string
/* "offset" neither */
void f() {
  utils::declare_double(node, "trim");
  get_parameter("rate", rate_);
  RCLCPP_INFO(logger, "No 'octomap_frame' parameter defined");
  char c = 'x';
}
"""
    facts = _cpp(code.decode())
    assert unexplained_literals(code, facts.names) == ("trim",)
    python = b"# 'gain'\ndeclare(node, 'trim')\nnode.get_parameter(\"rate\")\n"
    assert unexplained_literals(python, (), python=True) == ("rate", "trim")
