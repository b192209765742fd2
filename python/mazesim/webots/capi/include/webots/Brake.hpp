// Webots' C++ Brake class (<webots/Brake.hpp>): defined with mazesim's other device
// classes.
#include <webots/Devices.hpp>
