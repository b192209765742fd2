// Webots' C++ LightSensor class (<webots/LightSensor.hpp>): defined with mazesim's other device classes.
#include <webots/Devices.hpp>
