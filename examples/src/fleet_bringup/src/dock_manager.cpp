// Sends a robot of the fleet to its charging dock.
#include <memory>

#include <rclcpp/rclcpp.hpp>
#include <std_srvs/srv/trigger.hpp>

class DockManager : public rclcpp::Node
{
public:
  DockManager() : Node("dock_manager")
  {
    declare_parameter("dock_frame", "charging_dock");
    // Named after what it carries, not after what it does.
    dock_service_ = create_service<std_srvs::srv::Trigger>(
      "StartDocking",
      [this](const std::shared_ptr<std_srvs::srv::Trigger::Request>,
             std::shared_ptr<std_srvs::srv::Trigger::Response> response) {
        RCLCPP_INFO(get_logger(), "docking at %s", get_parameter("dockframe").as_string().c_str());
        response->success = true;
      });
  }

private:
  rclcpp::Service<std_srvs::srv::Trigger>::SharedPtr dock_service_;
};

int main(int argc, char** argv)
{
  rclcpp::init(argc, argv);
  rclcpp::spin(std::make_shared<DockManager>());
  rclcpp::shutdown();
  return 0;
}
