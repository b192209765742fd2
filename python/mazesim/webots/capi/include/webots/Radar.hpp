// Webots' C++ Radar class (<webots/Radar.hpp>): defined with mazesim's other device
// classes.
#include <webots/Devices.hpp>
