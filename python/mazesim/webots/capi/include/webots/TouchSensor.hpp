// Webots' C++ TouchSensor class (<webots/TouchSensor.hpp>): defined with mazesim's other device classes.
#include <webots/Devices.hpp>
