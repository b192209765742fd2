// Webots' C++ Keyboard class (<webots/Keyboard.hpp>): defined with mazesim's other device classes.
#include <webots/Devices.hpp>
