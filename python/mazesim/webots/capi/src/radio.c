/* Webots' Emitter and Receiver functions (reference manual, Emitter and Receiver pages), served
   by mazesim's Python radio devices over the link so that channels, ranges, buffers and queues
   behave as for a Python controller. Enabling a receiver is a command of the next step (as
   for any sensor, see devices.c); the rest are calls. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <webots/emitter.h>
#include <webots/receiver.h>

#include "call.h"
#include "link.h"

int wb_emitter_send(WbDeviceTag tag, const void *data, int size) {
  if (!data) {
    link_error("wb_emitter_send", "(): invalid argument: data = NULL.");
    return 0;
  }
  if (size < 1) {
    link_error("wb_emitter_send", "(): invalid size=%d argument.", size);
    return 0;
  }
  if (!link_device(tag, "wb_emitter_send"))
    return 0;
  call_begin("wb_emitter_send");
  call_int(tag);
  call_bytes(data, size);
  call_end();
  return answer_int(0);
}

int wb_emitter_get_buffer_size(WbDeviceTag tag) {
  return link_device(tag, "wb_emitter_get_buffer_size")
           ? call_device_int("wb_emitter_get_buffer_size", tag)
           : -1;
}

int wb_emitter_get_channel(WbDeviceTag tag) {
  return link_device(tag, "wb_emitter_get_channel") ? call_device_int("wb_emitter_get_channel", tag)
                                                    : -1;
}

void wb_emitter_set_channel(WbDeviceTag tag, int channel) {
  if (link_device(tag, "wb_emitter_set_channel"))
    call_device_set_int("wb_emitter_set_channel", tag, channel);
}

double wb_emitter_get_range(WbDeviceTag tag) {
  return link_device(tag, "wb_emitter_get_range") ? call_device_double("wb_emitter_get_range", tag)
                                                  : NAN;
}

void wb_emitter_set_range(WbDeviceTag tag, double range) {
  if (range < 0.0 && range != -1.0) {
    link_error("wb_emitter_set_range", "(): invalid range=%f argument.", range);
    return;
  }
  if (!link_device(tag, "wb_emitter_set_range"))
    return;
  call_begin("wb_emitter_set_range");
  call_int(tag);
  call_double(range);
  call_end();
}

void wb_receiver_set_channel(WbDeviceTag tag, int channel) {
  if (link_device(tag, "wb_receiver_set_channel"))
    call_device_set_int("wb_receiver_set_channel", tag, channel);
}

int wb_receiver_get_channel(WbDeviceTag tag) {
  return link_device(tag, "wb_receiver_get_channel")
           ? call_device_int("wb_receiver_get_channel", tag)
           : -1;
}

/* An enabled receiver's queue length comes with each step's readings; wb_receiver_next_packet
   is the only other change to it. */
int wb_receiver_get_queue_length(WbDeviceTag tag) {
  Device *device = link_device(tag, "wb_receiver_get_queue_length");
  if (!device)
    return 0;
  if (device->sampling_period > 0 && device->value_count > 0)
    return (int)device->values[0];
  return call_device_int("wb_receiver_get_queue_length", tag);
}

void wb_receiver_next_packet(WbDeviceTag tag) {
  Device *device = link_device(tag, "wb_receiver_next_packet");
  if (!device)
    return;
  call_begin("wb_receiver_next_packet");
  call_int(tag);
  call_end();
  if (device->value_count > 0 && device->values[0] > 0)
    device->values[0] -= 1;
}

int wb_receiver_get_data_size(WbDeviceTag tag) {
  return link_device(tag, "wb_receiver_get_data_size")
           ? call_device_int("wb_receiver_get_data_size", tag)
           : -1;
}

/* The head packet, kept by the device until the next read (NULL when the queue is empty). */
static const void *head_packet(WbDeviceTag tag, const char *function) {
  Device *device = link_device(tag, function);
  if (!device)
    return NULL;
  call_begin("wb_receiver_get_data");
  call_int(tag);
  call_end();
  int size;
  const void *data = answer_bytes(0, &size);
  free(device->packet);
  device->packet = NULL;
  if (!data)
    return NULL;
  device->packet = malloc((size_t)size + 1);
  if (!device->packet)
    link_failed("out of memory");
  memcpy(device->packet, data, (size_t)size);
  device->packet[size] = '\0';
  return device->packet;
}

const void *wb_receiver_get_data(WbDeviceTag tag) {
  return head_packet(tag, "wb_receiver_get_data");
}

const char *wb_receiver_get_string(WbDeviceTag tag) {
  return head_packet(tag, "wb_receiver_get_string");
}

double wb_receiver_get_signal_strength(WbDeviceTag tag) {
  return link_device(tag, "wb_receiver_get_signal_strength")
           ? call_device_double("wb_receiver_get_signal_strength", tag)
           : NAN;
}

const double *wb_receiver_get_emitter_direction(WbDeviceTag tag) {
  Device *device = link_device(tag, "wb_receiver_get_emitter_direction");
  if (!device)
    return NULL;
  call_begin("wb_receiver_get_emitter_direction");
  call_int(tag);
  call_end();
  int count;
  const double *direction = answer_doubles(0, &count);
  for (int i = 0; i < 3; i++)
    device->direction[i] = direction && i < count ? direction[i] : NAN;
  /* An empty queue has no direction (the call said so, answering NaNs): NULL, as in Webots. */
  if (isnan(device->direction[0]) && isnan(device->direction[1]) && isnan(device->direction[2]))
    return NULL;
  return device->direction;
}
