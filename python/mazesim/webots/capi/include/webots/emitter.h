/* Webots' emitter functions (<webots/emitter.h>), as the reference manual's Emitter page
   describes them (https://cyberbotics.com/doc/reference/emitter): packets go over mazesim's
   radio (mazesim/webots/radio.py), with the channel, range and buffer rules of Python
   controllers. */
#ifndef WB_EMITTER_H
#define WB_EMITTER_H

#include <webots/types.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The channel of an emitter that sends on every channel. */
#define WB_CHANNEL_BROADCAST -1

int wb_emitter_send(WbDeviceTag tag, const void *data, int size);
int wb_emitter_get_buffer_size(WbDeviceTag tag);
int wb_emitter_get_channel(WbDeviceTag tag);
void wb_emitter_set_channel(WbDeviceTag tag, int channel);
double wb_emitter_get_range(WbDeviceTag tag);
void wb_emitter_set_range(WbDeviceTag tag, double range);

#ifdef __cplusplus
}
#endif

#endif
