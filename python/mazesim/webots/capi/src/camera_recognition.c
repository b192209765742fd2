/* Webots' camera recognition functions (<webots/camera.h>): calls over the link to the
   camera's Python object (see mazesim/webots/native_calls.py), whose recognised objects come
   back as one list of numbers (per object: id, position, orientation, size, position and size
   on the image, number of colours, then the colours) and their models, each ending with a
   NUL. */
#include <stdlib.h>
#include <string.h>

#include <webots/camera.h>

#include "call.h"
#include "link.h"

/* The numbers of an object before its colours. */
#define OBJECT_NUMBERS 15

bool wb_camera_has_recognition(WbDeviceTag tag) {
  return call_device_int("wb_camera_has_recognition", tag) != 0;
}

void wb_camera_recognition_enable(WbDeviceTag tag, int sampling_period) {
  call_device_set_int("wb_camera_recognition_enable", tag, sampling_period);
}

void wb_camera_recognition_disable(WbDeviceTag tag) {
  call_device_int("wb_camera_recognition_disable", tag);
}

int wb_camera_recognition_get_sampling_period(WbDeviceTag tag) {
  return call_device_int("wb_camera_recognition_get_sampling_period", tag);
}

int wb_camera_recognition_get_number_of_objects(WbDeviceTag tag) {
  return call_device_int("wb_camera_recognition_get_number_of_objects", tag);
}

static void forget_objects(Device *device) {
  for (int i = 0; i < device->object_count; i++) {
    free(device->objects[i].colors);
    free(device->objects[i].model);
  }
  free(device->objects);
  device->objects = NULL;
  device->object_count = 0;
}

static char *copy_text(const char *text, size_t size) {
  char *copy = malloc(size + 1);
  if (!copy)
    link_failed("out of memory");
  memcpy(copy, text, size);
  copy[size] = '\0';
  return copy;
}

/* Reads the objects of an answer into `device`; returns 0 when the answer is malformed. */
static int read_objects(Device *device) {
  int count, size;
  const double *numbers = answer_doubles(0, &count);
  const char *models = answer_bytes(1, &size);
  int capacity = count / OBJECT_NUMBERS;
  device->objects = calloc((size_t)(capacity ? capacity : 1), sizeof(WbCameraRecognitionObject));
  if (!device->objects)
    link_failed("out of memory");
  int at = 0, model_at = 0;
  while (at < count) {
    if (count - at < OBJECT_NUMBERS)
      return 0;
    const double *n = numbers + at;
    int colors = (int)n[14];
    if (colors < 0 || count - at - OBJECT_NUMBERS < 3 * colors)
      return 0;
    WbCameraRecognitionObject *object = &device->objects[device->object_count++];
    object->id = (int)n[0];
    memcpy(object->position, n + 1, sizeof object->position);
    memcpy(object->orientation, n + 4, sizeof object->orientation);
    memcpy(object->size, n + 8, sizeof object->size);
    for (int i = 0; i < 2; i++) {
      object->position_on_image[i] = (int)n[10 + i];
      object->size_on_image[i] = (int)n[12 + i];
    }
    object->number_of_colors = colors;
    object->colors = malloc(sizeof(double) * (size_t)(3 * colors + 1));
    if (!object->colors)
      link_failed("out of memory");
    memcpy(object->colors, n + OBJECT_NUMBERS, sizeof(double) * (size_t)(3 * colors));
    const char *model = models && model_at < size ? models + model_at : "";
    const char *end = models && model_at < size ? memchr(model, '\0', (size_t)(size - model_at)) : NULL;
    size_t length = end ? (size_t)(end - model) : 0;
    object->model = copy_text(model, length);
    model_at += (int)length + 1;
    at += OBJECT_NUMBERS + 3 * colors;
  }
  return 1;
}

const WbCameraRecognitionObject *wb_camera_recognition_get_objects(WbDeviceTag tag) {
  Device *device = link_device(tag, "wb_camera_recognition_get_objects");
  if (!device)
    return NULL;
  /* As in Webots, the array stays valid until the next step. */
  if (device->objects && device->objects_time == link_robot.time)
    return device->objects;
  forget_objects(device);
  call_begin("wb_camera_recognition_get_objects");
  call_int(tag);
  call_end();
  if (answer_type(0) != VALUE_DOUBLES)
    return NULL;
  if (!read_objects(device))
    link_failed("mazesim sent a malformed answer");
  device->objects_time = link_robot.time;
  return device->objects;
}

bool wb_camera_recognition_has_segmentation(WbDeviceTag tag) {
  return call_device_int("wb_camera_recognition_has_segmentation", tag) != 0;
}

void wb_camera_recognition_enable_segmentation(WbDeviceTag tag) {
  call_device_int("wb_camera_recognition_enable_segmentation", tag);
}

void wb_camera_recognition_disable_segmentation(WbDeviceTag tag) {
  call_device_int("wb_camera_recognition_disable_segmentation", tag);
}

bool wb_camera_recognition_is_segmentation_enabled(WbDeviceTag tag) {
  return call_device_int("wb_camera_recognition_is_segmentation_enabled", tag) != 0;
}

const unsigned char *wb_camera_recognition_get_segmentation_image(WbDeviceTag tag) {
  call_device_int("wb_camera_recognition_get_segmentation_image", tag);
  return NULL;
}
