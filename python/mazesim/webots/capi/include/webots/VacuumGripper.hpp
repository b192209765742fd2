// Webots' C++ VacuumGripper class (<webots/VacuumGripper.hpp>): defined with mazesim's other device
// classes.
#include <webots/Devices.hpp>
