/* Webots' device functions (<webots/device.h>). */
#ifndef WB_DEVICE_H
#define WB_DEVICE_H

#include <webots/nodes.h>
#include <webots/types.h>

#ifdef __cplusplus
extern "C" {
#endif

const char *wb_device_get_name(WbDeviceTag tag);
const char *wb_device_get_model(WbDeviceTag tag);
WbNodeType wb_device_get_node_type(WbDeviceTag tag);
/* The name older Webots versions gave wb_device_get_node_type. */
WbNodeType wb_device_get_type(WbDeviceTag tag);

#ifdef __cplusplus
}
#endif

#endif
