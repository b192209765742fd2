// Webots' C++ InertialUnit class (<webots/InertialUnit.hpp>): defined with mazesim's other device classes.
#include <webots/Devices.hpp>
