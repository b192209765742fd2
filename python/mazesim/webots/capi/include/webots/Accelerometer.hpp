// Webots' C++ Accelerometer class (<webots/Accelerometer.hpp>): defined with mazesim's other device classes.
#include <webots/Devices.hpp>
