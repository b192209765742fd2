// Webots' C++ CameraRecognitionObject (<webots/CameraRecognitionObject.hpp>): defined with
// mazesim's other device classes.
#include <webots/Devices.hpp>
