// Webots' C++ Motor class (<webots/Motor.hpp>): defined with mazesim's other device classes.
#include <webots/Devices.hpp>
