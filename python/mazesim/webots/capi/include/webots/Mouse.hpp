// Webots' C++ Mouse class (<webots/Mouse.hpp>): defined with mazesim's other device
// classes.
#include <webots/Devices.hpp>
