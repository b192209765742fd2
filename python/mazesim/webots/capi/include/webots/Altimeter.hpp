// Webots' C++ Altimeter class (<webots/Altimeter.hpp>): defined with mazesim's other device classes.
#include <webots/Devices.hpp>
