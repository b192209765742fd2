/* Webots' device functions on the link: commands are queued for the next wb_robot_step,
   readings are those the last step brought. */
#include "call.h"
#include "link.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <webots/accelerometer.h>
#include <webots/altimeter.h>
#include <webots/camera.h>
#include <webots/compass.h>
#include <webots/device.h>
#include <webots/distance_sensor.h>
#include <webots/gps.h>
#include <webots/gyro.h>
#include <webots/inertial_unit.h>
#include <webots/keyboard.h>
#include <webots/led.h>
#include <webots/lidar.h>
#include <webots/light_sensor.h>
#include <webots/motor.h>
#include <webots/position_sensor.h>
#include <webots/range_finder.h>
#include <webots/receiver.h>
#include <webots/robot.h>
#include <webots/touch_sensor.h>

/* --- any device ---------------------------------------------------------------------------- */

/* As Webots' device.c, these say nothing of a wrong tag: tag 0 is the robot, a tag past the
   devices none (NULL, WB_NODE_NO_NODE). */
static Device *any_device(WbDeviceTag tag) {
  link_start();
  return tag >= 1 && tag <= link_robot.device_count ? &link_robot.devices[tag - 1] : NULL;
}

const char *wb_device_get_name(WbDeviceTag tag) {
  Device *device = any_device(tag);
  return device ? device->name : tag == 0 ? link_robot.name : NULL;
}

const char *wb_device_get_model(WbDeviceTag tag) {
  Device *device = any_device(tag);
  return device ? device->model : NULL;
}

WbNodeType wb_device_get_node_type(WbDeviceTag tag) {
  Device *device = any_device(tag);
  return device ? device->node_type : tag == 0 ? WB_NODE_ROBOT : WB_NODE_NO_NODE;
}

WbNodeType wb_device_get_type(WbDeviceTag tag) {
  return wb_device_get_node_type(tag);
}

/* The fixed fact `index` of a device (see native_link.py), or `otherwise`. */
static double info(WbDeviceTag tag, int index, double otherwise, const char *function) {
  Device *device = link_device(tag, function);
  if (!device || index >= device->info_count)
    return otherwise;
  return device->info[index];
}

/* --- sensors: enable, disable, sampling period, readings ----------------------------------- */

static void enable(WbDeviceTag tag, int period, const char *function) {
  Device *device = link_device(tag, function);
  if (!device)
    return;
  if (period < 0) {
    fprintf(stderr, "Error: %s() called with negative sampling period.\n", function);
    return;
  }
  device->sampling_period = period;
  link_command(COMMAND_ENABLE, tag, period, 0.0);
}

static void disable(WbDeviceTag tag, const char *function) {
  Device *device = link_device(tag, function);
  if (!device)
    return;
  device->sampling_period = 0;
  link_command(COMMAND_DISABLE, tag, 0.0, 0.0);
}

static int sampling_period(WbDeviceTag tag, const char *function) {
  Device *device = link_device(tag, function);
  return device ? device->sampling_period : 0;
}

static double scalar(WbDeviceTag tag, const char *function) {
  Device *device = link_device(tag, function);
  return device ? device->values[0] : NAN;
}

static const double *vector(WbDeviceTag tag, const char *function) {
  Device *device = link_device(tag, function);
  return device ? device->values : NULL;
}

#define SAMPLED(prefix)                                                                           \
  void prefix##_enable(WbDeviceTag tag, int period) {                                           \
    enable(tag, period, #prefix "_enable");                                                     \
  }                                                                                               \
  void prefix##_disable(WbDeviceTag tag) {                                                      \
    disable(tag, #prefix "_disable");                                                           \
  }                                                                                               \
  int prefix##_get_sampling_period(WbDeviceTag tag) {                                           \
    return sampling_period(tag, #prefix "_get_sampling_period");                                \
  }

#define SCALAR_SENSOR(prefix)                                                                     \
  SAMPLED(prefix)                                                                                 \
  double prefix##_get_value(WbDeviceTag tag) {                                                  \
    return scalar(tag, #prefix "_get_value");                                                   \
  }

#define VECTOR_SENSOR(prefix)                                                                     \
  SAMPLED(prefix)                                                                                 \
  const double *prefix##_get_values(WbDeviceTag tag) {                                          \
    return vector(tag, #prefix "_get_values");                                                  \
  }

SCALAR_SENSOR(wb_distance_sensor)
SCALAR_SENSOR(wb_light_sensor)
SCALAR_SENSOR(wb_position_sensor)
SCALAR_SENSOR(wb_touch_sensor)
SCALAR_SENSOR(wb_altimeter)
VECTOR_SENSOR(wb_gps)
VECTOR_SENSOR(wb_compass)
VECTOR_SENSOR(wb_accelerometer)
VECTOR_SENSOR(wb_gyro)
SAMPLED(wb_camera)
SAMPLED(wb_inertial_unit)
SAMPLED(wb_lidar)
SAMPLED(wb_range_finder)
SAMPLED(wb_receiver)

/* An inertial unit's roll, pitch and yaw come with each step's readings; its quaternion and
   noise are calls, as the Python InertialUnit computes them. */
const double *wb_inertial_unit_get_roll_pitch_yaw(WbDeviceTag tag) {
  return vector(tag, "wb_inertial_unit_get_roll_pitch_yaw");
}

const double *wb_inertial_unit_get_quaternion(WbDeviceTag tag) {
  Device *device = link_device(tag, "wb_inertial_unit_get_quaternion");
  if (!device)
    return NULL;
  call_begin("wb_inertial_unit_get_quaternion");
  call_int(tag);
  call_end();
  int count;
  const double *quaternion = answer_doubles(0, &count);
  if (!quaternion || count != 4)
    return NULL;
  for (int i = 0; i < 4; i++)
    device->quaternion[i] = quaternion[i];
  return device->quaternion;
}

double wb_inertial_unit_get_noise(WbDeviceTag tag) {
  return link_device(tag, "wb_inertial_unit_get_noise")
           ? call_device_double("wb_inertial_unit_get_noise", tag)
           : NAN;
}

/* A distance sensor's facts: min value, max value, aperture, type, lookup table rows. */
double wb_distance_sensor_get_min_value(WbDeviceTag tag) {
  return info(tag, 0, NAN, "wb_distance_sensor_get_min_value");
}

double wb_distance_sensor_get_max_value(WbDeviceTag tag) {
  return info(tag, 1, NAN, "wb_distance_sensor_get_max_value");
}

double wb_distance_sensor_get_aperture(WbDeviceTag tag) {
  return info(tag, 2, NAN, "wb_distance_sensor_get_aperture");
}

WbDistanceSensorType wb_distance_sensor_get_type(WbDeviceTag tag) {
  return (WbDistanceSensorType)info(tag, 3, 0, "wb_distance_sensor_get_type");
}

int wb_distance_sensor_get_lookup_table_size(WbDeviceTag tag) {
  Device *device = link_device(tag, "wb_distance_sensor_get_lookup_table_size");
  return device && device->info_count > 4 ? (device->info_count - 4) / 3 : 0;
}

const double *wb_distance_sensor_get_lookup_table(WbDeviceTag tag) {
  Device *device = link_device(tag, "wb_distance_sensor_get_lookup_table");
  return device && device->info_count > 4 ? device->info + 4 : NULL;
}

/* A position sensor's facts: its motor's tag. */
WbDeviceTag wb_position_sensor_get_motor(WbDeviceTag tag) {
  return (WbDeviceTag)info(tag, 0, 0, "wb_position_sensor_get_motor");
}

/* --- motors: max velocity, min position, max position, acceleration, position sensor tag --- */

static void set_point(WbDeviceTag tag, int index, int op, double value, const char *function) {
  Device *device = link_device(tag, function);
  if (!device)
    return;
  device->set_point[index] = value;
  link_command(op, tag, value, 0.0);
}

void wb_motor_set_position(WbDeviceTag tag, double position) {
  set_point(tag, 0, COMMAND_SET_POSITION, position, "wb_motor_set_position");
}

void wb_motor_set_velocity(WbDeviceTag tag, double velocity) {
  set_point(tag, 1, COMMAND_SET_VELOCITY, velocity, "wb_motor_set_velocity");
}

void wb_motor_set_acceleration(WbDeviceTag tag, double acceleration) {
  set_point(tag, 2, COMMAND_SET_ACCELERATION, acceleration, "wb_motor_set_acceleration");
}

/* The gains of position control, set by the Python Motor (a call, so that C and Python share
   Webots' PID). */
void wb_motor_set_control_pid(WbDeviceTag tag, double p, double i, double d) {
  if (!link_device(tag, "wb_motor_set_control_pid"))
    return;
  call_begin("wb_motor_set_control_pid");
  call_int(tag);
  call_double(p);
  call_double(i);
  call_double(d);
  call_end();
}

static double set_value(WbDeviceTag tag, int index, const char *function) {
  Device *device = link_device(tag, function);
  return device ? device->set_point[index] : NAN;
}

double wb_motor_get_target_position(WbDeviceTag tag) {
  return set_value(tag, 0, "wb_motor_get_target_position");
}

double wb_motor_get_velocity(WbDeviceTag tag) {
  return set_value(tag, 1, "wb_motor_get_velocity");
}

double wb_motor_get_acceleration(WbDeviceTag tag) {
  return set_value(tag, 2, "wb_motor_get_acceleration");
}

double wb_motor_get_max_velocity(WbDeviceTag tag) {
  return info(tag, 0, NAN, "wb_motor_get_max_velocity");
}

double wb_motor_get_min_position(WbDeviceTag tag) {
  return info(tag, 1, 0.0, "wb_motor_get_min_position");
}

double wb_motor_get_max_position(WbDeviceTag tag) {
  return info(tag, 2, 0.0, "wb_motor_get_max_position");
}

WbJointType wb_motor_get_type(WbDeviceTag tag) {
  return link_device(tag, "wb_motor_get_type") ? WB_ROTATIONAL : WB_ROTATIONAL;
}

WbDeviceTag wb_motor_get_position_sensor(WbDeviceTag tag) {
  return (WbDeviceTag)info(tag, 4, 0, "wb_motor_get_position_sensor");
}

/* --- LEDs ----------------------------------------------------------------------------------- */

void wb_led_set(WbDeviceTag tag, int value) {
  Device *device = link_device(tag, "wb_led_set");
  if (!device)
    return;
  device->led = value;
  link_command(COMMAND_LED_SET, tag, value, 0.0);
}

int wb_led_get(WbDeviceTag tag) {
  Device *device = link_device(tag, "wb_led_get");
  return device ? device->led : 0;
}

/* --- cameras: width, height, field of view -------------------------------------------------- */

const unsigned char *wb_camera_get_image(WbDeviceTag tag) {
  Device *device = link_device(tag, "wb_camera_get_image");
  if (!device)
    return NULL;
  /* Asked for once a step, when first read: a camera that is enabled and never read costs no
     image. As in Webots, the image stays valid until the next step. */
  if (device->image && device->image_time == link_robot.time)
    return device->image;
  call_begin("wb_camera_get_image");
  call_int(tag);
  call_end();
  int size = 0;
  const void *bytes = answer_bytes(0, &size);
  if (!bytes || size <= 0)
    return NULL;
  if (size != device->image_size) {
    free(device->image);
    device->image = malloc((size_t)size);
    if (!device->image)
      link_failed("out of memory");
    device->image_size = size;
  }
  memcpy(device->image, bytes, (size_t)size);
  device->image_time = link_robot.time;
  return device->image;
}

int wb_camera_get_width(WbDeviceTag tag) {
  return (int)info(tag, 0, 0, "wb_camera_get_width");
}

int wb_camera_get_height(WbDeviceTag tag) {
  return (int)info(tag, 1, 0, "wb_camera_get_height");
}

double wb_camera_get_fov(WbDeviceTag tag) {
  return info(tag, 2, NAN, "wb_camera_get_fov");
}

static unsigned char channel(const unsigned char *image, int width, int x, int y, int offset) {
  return image[4 * (y * width + x) + offset];
}

unsigned char wb_camera_image_get_blue(const unsigned char *image, int width, int x, int y) {
  return channel(image, width, x, y, 0);
}

unsigned char wb_camera_image_get_green(const unsigned char *image, int width, int x, int y) {
  return channel(image, width, x, y, 1);
}

unsigned char wb_camera_image_get_red(const unsigned char *image, int width, int x, int y) {
  return channel(image, width, x, y, 2);
}

unsigned char wb_camera_image_get_gray(const unsigned char *image, int width, int x, int y) {
  int sum = channel(image, width, x, y, 0) + channel(image, width, x, y, 1) +
            channel(image, width, x, y, 2);
  return (unsigned char)(sum / 3);
}

unsigned char wb_camera_image_get_grey(const unsigned char *image, int width, int x, int y) {
  return wb_camera_image_get_gray(image, width, x, y);
}

/* --- the keyboard --------------------------------------------------------------------------- */

void wb_keyboard_enable(int period) {
  link_start();
  link_robot.keyboard_period = period;
  link_command(COMMAND_ENABLE, KEYBOARD_TAG, period, 0.0);
}

void wb_keyboard_disable(void) {
  link_start();
  link_robot.keyboard_period = 0;
  link_command(COMMAND_DISABLE, KEYBOARD_TAG, 0.0, 0.0);
}

int wb_keyboard_get_sampling_period(void) {
  link_start();
  return link_robot.keyboard_period;
}

int wb_keyboard_get_key(void) {
  link_start();
  if (link_robot.key_next >= link_robot.key_count)
    return -1;
  return link_robot.keys[link_robot.key_next++];
}

void wb_robot_keyboard_enable(int period) {
  wb_keyboard_enable(period);
}

void wb_robot_keyboard_disable(void) {
  wb_keyboard_disable();
}

int wb_robot_keyboard_get_key(void) {
  return wb_keyboard_get_key();
}
