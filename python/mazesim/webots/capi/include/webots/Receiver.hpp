// Webots' C++ Receiver class (<webots/Receiver.hpp>): defined with mazesim's other device classes.
#include <webots/Devices.hpp>
