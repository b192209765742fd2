/* Webots' receiver functions (<webots/receiver.h>), as the reference manual's Receiver page
   describes them (https://cyberbotics.com/doc/reference/receiver): the queue is the one of
   mazesim's Python Receiver (mazesim/webots/radio_devices.py). The data of the head packet
   stay valid until wb_receiver_next_packet. */
#ifndef WB_RECEIVER_H
#define WB_RECEIVER_H

#include <webots/types.h>

#ifdef __cplusplus
extern "C" {
#endif

#ifndef WB_CHANNEL_BROADCAST
#define WB_CHANNEL_BROADCAST -1
#endif

void wb_receiver_enable(WbDeviceTag tag, int sampling_period);
void wb_receiver_disable(WbDeviceTag tag);
int wb_receiver_get_sampling_period(WbDeviceTag tag);
void wb_receiver_set_channel(WbDeviceTag tag, int channel);
int wb_receiver_get_channel(WbDeviceTag tag);
int wb_receiver_get_queue_length(WbDeviceTag tag);
void wb_receiver_next_packet(WbDeviceTag tag);
int wb_receiver_get_data_size(WbDeviceTag tag);
const void *wb_receiver_get_data(WbDeviceTag tag);
/* The head packet as a text (R2023b and later). */
const char *wb_receiver_get_string(WbDeviceTag tag);
double wb_receiver_get_signal_strength(WbDeviceTag tag);
const double *wb_receiver_get_emitter_direction(WbDeviceTag tag);

#ifdef __cplusplus
}
#endif

#endif
