/* Webots' touch sensor functions (<webots/touch_sensor.h>). */
#ifndef WB_TOUCH_SENSOR_H
#define WB_TOUCH_SENSOR_H

#include <webots/types.h>

#ifdef __cplusplus
extern "C" {
#endif

void wb_touch_sensor_enable(WbDeviceTag tag, int sampling_period);
void wb_touch_sensor_disable(WbDeviceTag tag);
int wb_touch_sensor_get_sampling_period(WbDeviceTag tag);
double wb_touch_sensor_get_value(WbDeviceTag tag);

#ifdef __cplusplus
}
#endif

#endif
