// Webots' C++ Compass class (<webots/Compass.hpp>): defined with mazesim's other device classes.
#include <webots/Devices.hpp>
