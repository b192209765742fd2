/* Webots' Lidar and RangeFinder functions (reference manual, Lidar and RangeFinder pages) other
   than enable, disable and the sampling period (devices.c): calls served by the Python Lidar and
   RangeFinder, so that a C controller reads what a Python one reads. Range images and point
   clouds stay valid until the next such call on the same device. */
#include <math.h>
#include <stdlib.h>

#include <webots/lidar.h>
#include <webots/range_finder.h>

#include "call.h"
#include "link.h"

/* Numbers per point of a point cloud on the link: x, y, z, layer, time. */
#define POINT_NUMBERS 5

static void *resized(void *buffer, size_t size) {
  void *grown = realloc(buffer, size ? size : 1);
  if (!grown)
    link_failed("out of memory");
  return grown;
}

/* Calls `function` on the lidar `tag` with an optional layer (-1 for none); the numbers it
   answers, or NULL. */
static const double *numbers(WbDeviceTag tag, int layer, const char *function, int *count) {
  *count = 0;
  if (!link_device(tag, function))
    return NULL;
  call_begin(function);
  call_int(tag);
  if (layer >= 0)
    call_int(layer);
  call_end();
  return answer_doubles(0, count);
}

static const float *range_image(WbDeviceTag tag, int layer, const char *function) {
  int count;
  const double *ranges = numbers(tag, layer, function, &count);
  if (!ranges)
    return NULL;
  Device *device = link_device(tag, function);
  device->ranges = resized(device->ranges, sizeof(float) * (size_t)count);
  device->range_count = count;
  for (int i = 0; i < count; i++)
    device->ranges[i] = (float)ranges[i];
  return device->ranges;
}

static const WbLidarPoint *point_cloud(WbDeviceTag tag, int layer, const char *function) {
  int count;
  const double *points = numbers(tag, layer, function, &count);
  if (!points)
    return NULL;
  Device *device = link_device(tag, function);
  int point_count = count / POINT_NUMBERS;
  device->points = resized(device->points, sizeof(WbLidarPoint) * (size_t)point_count);
  device->point_count = point_count;
  for (int i = 0; i < point_count; i++) {
    const double *point = points + POINT_NUMBERS * i;
    WbLidarPoint *made = &device->points[i];
    made->x = (float)point[0];
    made->y = (float)point[1];
    made->z = (float)point[2];
    made->layer_id = (int)point[3];
    made->time = (float)point[4];
  }
  return device->points;
}

const float *wb_lidar_get_range_image(WbDeviceTag tag) {
  return range_image(tag, -1, "wb_lidar_get_range_image");
}

const float *wb_lidar_get_layer_range_image(WbDeviceTag tag, int layer) {
  return range_image(tag, layer, "wb_lidar_get_layer_range_image");
}

const WbLidarPoint *wb_lidar_get_point_cloud(WbDeviceTag tag) {
  return point_cloud(tag, -1, "wb_lidar_get_point_cloud");
}

const WbLidarPoint *wb_lidar_get_layer_point_cloud(WbDeviceTag tag, int layer) {
  return point_cloud(tag, layer, "wb_lidar_get_layer_point_cloud");
}

/* A call on the lidar `tag` answered by nothing. */
static void command(WbDeviceTag tag, const char *function) {
  if (!link_device(tag, function))
    return;
  call_begin(function);
  call_int(tag);
  call_end();
}

void wb_lidar_enable_point_cloud(WbDeviceTag tag) {
  command(tag, "wb_lidar_enable_point_cloud");
}

void wb_lidar_disable_point_cloud(WbDeviceTag tag) {
  command(tag, "wb_lidar_disable_point_cloud");
}

void wb_lidar_set_frequency(WbDeviceTag tag, double frequency) {
  if (!link_device(tag, "wb_lidar_set_frequency"))
    return;
  call_begin("wb_lidar_set_frequency");
  call_int(tag);
  call_double(frequency);
  call_end();
}

static int integer(WbDeviceTag tag, const char *function) {
  return link_device(tag, function) ? call_device_int(function, tag) : 0;
}

static double number(WbDeviceTag tag, const char *function) {
  return link_device(tag, function) ? call_device_double(function, tag) : NAN;
}

bool wb_lidar_is_point_cloud_enabled(WbDeviceTag tag) {
  return integer(tag, "wb_lidar_is_point_cloud_enabled") != 0;
}

/* A lidar's fact `fact`, an integer (`integer`) or a number (`number`). */
#define FACT(type, fact, kind)                                                                    \
  type wb_lidar_##fact(WbDeviceTag tag) {                                                       \
    return kind(tag, "wb_lidar_" #fact);                                                        \
  }

FACT(int, get_number_of_points, integer)
FACT(int, get_horizontal_resolution, integer)
FACT(int, get_number_of_layers, integer)
FACT(double, get_min_frequency, number)
FACT(double, get_max_frequency, number)
FACT(double, get_frequency, number)
FACT(double, get_fov, number)
FACT(double, get_vertical_fov, number)
FACT(double, get_min_range, number)
FACT(double, get_max_range, number)

const float *wb_range_finder_get_range_image(WbDeviceTag tag) {
  return range_image(tag, -1, "wb_range_finder_get_range_image");
}

float wb_range_finder_image_get_depth(const float *range_image, int width, int x, int y) {
  return range_image[y * width + x];
}

int wb_range_finder_get_width(WbDeviceTag tag) {
  return link_device(tag, "wb_range_finder_get_width")
           ? call_device_int("wb_range_finder_get_width", tag)
           : 0;
}

int wb_range_finder_get_height(WbDeviceTag tag) {
  return link_device(tag, "wb_range_finder_get_height")
           ? call_device_int("wb_range_finder_get_height", tag)
           : 0;
}

/* A number the range finder `tag` answers to `function` (NaN for no range finder). */
static double range_finder_number(WbDeviceTag tag, const char *function) {
  return link_device(tag, function) ? call_device_double(function, tag) : NAN;
}

double wb_range_finder_get_fov(WbDeviceTag tag) {
  return range_finder_number(tag, "wb_range_finder_get_fov");
}

double wb_range_finder_get_min_range(WbDeviceTag tag) {
  return range_finder_number(tag, "wb_range_finder_get_min_range");
}

double wb_range_finder_get_max_range(WbDeviceTag tag) {
  return range_finder_number(tag, "wb_range_finder_get_max_range");
}
