// Webots' C++ LED class (<webots/LED.hpp>): defined with mazesim's other device classes.
#include <webots/Devices.hpp>
