// Webots' C++ Speaker class (<webots/Speaker.hpp>): defined with mazesim's other device classes.
#include <webots/Devices.hpp>
