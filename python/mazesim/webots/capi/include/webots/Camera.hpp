// Webots' C++ Camera class (<webots/Camera.hpp>): defined with mazesim's other device classes.
#include <webots/Devices.hpp>
