// Webots' C++ PositionSensor class (<webots/PositionSensor.hpp>): defined with mazesim's other device classes.
#include <webots/Devices.hpp>
