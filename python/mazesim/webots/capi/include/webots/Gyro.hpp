// Webots' C++ Gyro class (<webots/Gyro.hpp>): defined with mazesim's other device classes.
#include <webots/Devices.hpp>
