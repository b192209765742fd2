// Webots' C++ Skin class (<webots/Skin.hpp>): defined with mazesim's other device
// classes.
#include <webots/Devices.hpp>
