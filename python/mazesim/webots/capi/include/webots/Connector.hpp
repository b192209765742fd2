// Webots' C++ Connector class (<webots/Connector.hpp>): defined with mazesim's other device
// classes.
#include <webots/Devices.hpp>
