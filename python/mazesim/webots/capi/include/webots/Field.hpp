// Webots' C++ Field class (<webots/Field.hpp>): defined with the Node class.
#include <webots/Node.hpp>
