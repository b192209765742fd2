// Webots' C++ Emitter class (<webots/Emitter.hpp>): defined with mazesim's other device classes.
#include <webots/Devices.hpp>
