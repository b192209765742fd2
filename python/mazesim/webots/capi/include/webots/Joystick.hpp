// Webots' C++ Joystick class (<webots/Joystick.hpp>): defined with mazesim's other device
// classes.
#include <webots/Devices.hpp>
