/* Webots' gps functions (<webots/gps.h>): three values per reading. */
#ifndef WB_GPS_H
#define WB_GPS_H

#include <webots/types.h>

#ifdef __cplusplus
extern "C" {
#endif

void wb_gps_enable(WbDeviceTag tag, int sampling_period);
void wb_gps_disable(WbDeviceTag tag);
int wb_gps_get_sampling_period(WbDeviceTag tag);
const double *wb_gps_get_values(WbDeviceTag tag);

#ifdef __cplusplus
}
#endif

#endif
