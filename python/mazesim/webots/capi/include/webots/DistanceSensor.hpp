// Webots' C++ DistanceSensor class (<webots/DistanceSensor.hpp>): defined with mazesim's other device classes.
#include <webots/Devices.hpp>
