// Webots' C++ Display class (<webots/Display.hpp>): defined with mazesim's other device classes.
#include <webots/Devices.hpp>
