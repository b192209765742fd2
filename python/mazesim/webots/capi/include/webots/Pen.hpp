// Webots' C++ Pen class (<webots/Pen.hpp>): defined with mazesim's other device classes.
#include <webots/Devices.hpp>
