// Webots' C++ Device class (<webots/Device.hpp>), over mazesim's C library.
#ifndef WB_DEVICE_HPP
#define WB_DEVICE_HPP

#include <string>

#include <webots/device.h>
#include <webots/robot.h>

namespace webots {
  class Device {
  public:
    explicit Device(WbDeviceTag tag) : tag(tag) {}
    explicit Device(const std::string &name) : tag(wb_robot_get_device(name.c_str())) {}
    virtual ~Device() {}
    std::string getName() const { return text(wb_device_get_name(tag)); }
    std::string getModel() const { return text(wb_device_get_model(tag)); }
    int getNodeType() const { return wb_device_get_node_type(tag); }
    WbDeviceTag getTag() const { return tag; }

  protected:
    static std::string text(const char *value) { return value ? value : ""; }
    WbDeviceTag tag;
  };
}  // namespace webots

#endif
