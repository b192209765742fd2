// Webots' C++ Lidar class (<webots/Lidar.hpp>): defined with mazesim's other device classes.
#include <webots/Devices.hpp>
