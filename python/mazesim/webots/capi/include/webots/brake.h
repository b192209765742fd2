/* Webots' Brake functions (<webots/brake.h>; reference manual, Brake page). mazesim's
   robots carry no Brake: every tag is refused with Webots' message (see absent_devices.c). */
#ifndef WB_BRAKE_H
#define WB_BRAKE_H

#include <webots/types.h>

#ifdef __cplusplus
extern "C" {
#endif

void wb_brake_set_damping_constant(WbDeviceTag tag, double damping_constant);
WbJointType wb_brake_get_type(WbDeviceTag tag);
WbDeviceTag wb_brake_get_motor(WbDeviceTag tag);
WbDeviceTag wb_brake_get_position_sensor(WbDeviceTag tag);

#ifdef __cplusplus
}
#endif

#endif
