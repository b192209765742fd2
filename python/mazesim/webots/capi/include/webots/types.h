/* Types shared by the Webots C API functions mazesim implements. */
#ifndef WB_TYPES_H
#define WB_TYPES_H

#ifndef __cplusplus
#include <stdbool.h>
#endif
/* Controllers pass INFINITY to wb_motor_set_position without including <math.h> themselves. */
#include <math.h>

/* A device of the robot: 1, 2... in the robot's device order; 0 is no device. */
typedef unsigned short WbDeviceTag;

/* A motor's or a position sensor's joint. */
typedef enum { WB_ROTATIONAL = 0, WB_LINEAR } WbJointType;

#endif
