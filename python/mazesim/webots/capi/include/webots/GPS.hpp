// Webots' C++ GPS class (<webots/GPS.hpp>): defined with mazesim's other device classes.
#include <webots/Devices.hpp>
