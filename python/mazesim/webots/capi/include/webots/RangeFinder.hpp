// Webots' C++ RangeFinder class (<webots/RangeFinder.hpp>): defined with mazesim's other device
// classes.
#include <webots/Devices.hpp>
