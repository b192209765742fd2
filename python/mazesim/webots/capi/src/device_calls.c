/* Webots' device and robot functions answered by the robot's Python objects over calls (see
   call.h), so that a C controller reads what a Python one reads: a camera's lens, a motor's
   torque and force, a GPS's speed, the lookup tables of sensors, a touch sensor's and a
   position sensor's type, the robot's battery, URDF and robot window. The arrays and texts
   they return stay valid until the next call of the same function on the same device. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <webots/accelerometer.h>
#include <webots/camera.h>
#include <webots/compass.h>
#include <webots/gps.h>
#include <webots/gyro.h>
#include <webots/light_sensor.h>
#include <webots/motor.h>
#include <webots/position_sensor.h>
#include <webots/robot.h>
#include <webots/robot_wwi.h>
#include <webots/touch_sensor.h>

#include "call.h"
#include "link.h"

/* A function of a device tag answering a number (NaN without the device). */
#define DEVICE_DOUBLE(function)                                                                   \
  double function(WbDeviceTag tag) {                                                             \
    return link_device(tag, #function) ? call_device_double(#function, tag) : NAN;               \
  }

/* A function of a device tag answering an integer (0 without the device). */
#define DEVICE_INT(type, function)                                                                \
  type function(WbDeviceTag tag) {                                                               \
    return (type)(link_device(tag, #function) ? call_device_int(#function, tag) : 0);            \
  }

/* A function of a device tag and a number, answering nothing. */
#define DEVICE_SET_DOUBLE(function)                                                               \
  void function(WbDeviceTag tag, double value) {                                                 \
    if (link_device(tag, #function))                                                             \
      call_device_set_double(#function, tag, value);                                             \
  }

/* A function of a device tag and an integer, answering nothing. */
#define DEVICE_SET_INT(function)                                                                  \
  void function(WbDeviceTag tag, int value) {                                                    \
    if (link_device(tag, #function))                                                             \
      call_device_set_int(#function, tag, value);                                                \
  }

/* A function of a device tag answering nothing. */
#define DEVICE_DO(function)                                                                       \
  void function(WbDeviceTag tag) {                                                               \
    if (link_device(tag, #function))                                                             \
      call_device_int(#function, tag);                                                           \
  }

/* The numbers a function of a device tag answers, kept for the caller. */
static const double *device_numbers(WbDeviceTag tag, const char *function, int *count) {
  *count = 0;
  if (!link_device(tag, function))
    return NULL;
  call_begin(function);
  call_int(tag);
  call_end();
  return answer_kept_doubles(0, function, tag, count);
}

/* --- cameras: field of view, exposure, focus, near plane, saved images --------------------- */

DEVICE_DOUBLE(wb_camera_get_min_fov)
DEVICE_DOUBLE(wb_camera_get_max_fov)
DEVICE_DOUBLE(wb_camera_get_exposure)
DEVICE_SET_DOUBLE(wb_camera_set_exposure)
DEVICE_DOUBLE(wb_camera_get_focal_length)
DEVICE_DOUBLE(wb_camera_get_focal_distance)
DEVICE_DOUBLE(wb_camera_get_min_focal_distance)
DEVICE_DOUBLE(wb_camera_get_max_focal_distance)
DEVICE_SET_DOUBLE(wb_camera_set_focal_distance)
DEVICE_DOUBLE(wb_camera_get_near)

/* The new field of view is the one wb_camera_get_fov reads from then on. */
void wb_camera_set_fov(WbDeviceTag tag, double fov) {
  Device *device = link_device(tag, "wb_camera_set_fov");
  if (!device)
    return;
  call_device_set_double("wb_camera_set_fov", tag, fov);
  if (device->info_count > 2)
    device->info[2] = call_device_double("wb_camera_get_fov", tag);
}

static int save(WbDeviceTag tag, const char *filename, int quality, const char *function) {
  if (!link_device(tag, function))
    return -1;
  call_begin(function);
  call_int(tag);
  call_text(filename);
  call_int(quality);
  call_end();
  return answer_int(0);
}

int wb_camera_save_image(WbDeviceTag tag, const char *filename, int quality) {
  return save(tag, filename, quality, "wb_camera_save_image");
}

int wb_camera_recognition_save_segmentation_image(WbDeviceTag tag, const char *filename,
                                                  int quality) {
  return save(tag, filename, quality, "wb_camera_recognition_save_segmentation_image");
}

/* --- motors: torque and force, their feedback, coupling and brake ------------------------- */

DEVICE_SET_DOUBLE(wb_motor_set_available_torque)
DEVICE_SET_DOUBLE(wb_motor_set_available_force)
DEVICE_SET_DOUBLE(wb_motor_set_torque)
DEVICE_SET_DOUBLE(wb_motor_set_force)
DEVICE_DOUBLE(wb_motor_get_available_torque)
DEVICE_DOUBLE(wb_motor_get_available_force)
DEVICE_DOUBLE(wb_motor_get_max_torque)
DEVICE_DOUBLE(wb_motor_get_max_force)
DEVICE_SET_INT(wb_motor_enable_torque_feedback)
DEVICE_SET_INT(wb_motor_enable_force_feedback)
DEVICE_DO(wb_motor_disable_torque_feedback)
DEVICE_DO(wb_motor_disable_force_feedback)
DEVICE_DOUBLE(wb_motor_get_torque_feedback)
DEVICE_DOUBLE(wb_motor_get_force_feedback)
DEVICE_INT(int, wb_motor_get_torque_feedback_sampling_period)
DEVICE_INT(int, wb_motor_get_force_feedback_sampling_period)
DEVICE_DOUBLE(wb_motor_get_multiplier)
DEVICE_INT(WbDeviceTag, wb_motor_get_brake)

/* --- GPS: speed and coordinates ------------------------------------------------------------ */

DEVICE_DOUBLE(wb_gps_get_speed)
DEVICE_INT(WbGpsCoordinateSystem, wb_gps_get_coordinate_system)

const double *wb_gps_get_speed_vector(WbDeviceTag tag) {
  int count;
  const double *speed = device_numbers(tag, "wb_gps_get_speed_vector", &count);
  return count == 3 ? speed : NULL;
}

/* Degrees, minutes and seconds (two decimals) as the Python GPS writes them: 12°34'56.78". */
const char *wb_gps_convert_to_degrees_minutes_seconds(double decimal_degree) {
  static char text[64];
  int degrees = (int)decimal_degree;
  double minutes = fabs(decimal_degree - degrees) * 60.0;
  int whole_minutes = (int)minutes;
  snprintf(text, sizeof text, "%d\xc2\xb0%d'%.2f\"", degrees, whole_minutes,
           (minutes - whole_minutes) * 60.0);
  return text;
}

/* --- lookup tables: rows of (input, output, noise) ---------------------------------------- */

#define LOOKUP_TABLE(prefix)                                                                      \
  int prefix##_get_lookup_table_size(WbDeviceTag tag) {                                          \
    int count;                                                                                    \
    device_numbers(tag, #prefix "_get_lookup_table", &count);                                    \
    return count / 3;                                                                             \
  }                                                                                               \
  const double *prefix##_get_lookup_table(WbDeviceTag tag) {                                     \
    int count;                                                                                    \
    const double *table = device_numbers(tag, #prefix "_get_lookup_table", &count);              \
    return count >= 3 ? table : NULL;                                                             \
  }

LOOKUP_TABLE(wb_accelerometer)
LOOKUP_TABLE(wb_compass)
LOOKUP_TABLE(wb_gyro)
LOOKUP_TABLE(wb_light_sensor)
LOOKUP_TABLE(wb_touch_sensor)

/* --- touch and position sensors ------------------------------------------------------------ */

DEVICE_INT(WbTouchSensorType, wb_touch_sensor_get_type)
DEVICE_INT(WbJointType, wb_position_sensor_get_type)
DEVICE_INT(WbDeviceTag, wb_position_sensor_get_brake)

const double *wb_touch_sensor_get_values(WbDeviceTag tag) {
  int count;
  const double *values = device_numbers(tag, "wb_touch_sensor_get_values", &count);
  return count == 3 ? values : NULL;
}

/* --- the robot: battery, type, URDF, user input, robot window ----------------------------- */

static void robot_call(const char *function) {
  link_start();
  call_begin(function);
}

void wb_robot_battery_sensor_enable(int sampling_period) {
  robot_call("wb_robot_battery_sensor_enable");
  call_int(sampling_period);
  call_end();
}

void wb_robot_battery_sensor_disable(void) {
  robot_call("wb_robot_battery_sensor_disable");
  call_end();
}

int wb_robot_battery_sensor_get_sampling_period(void) {
  robot_call("wb_robot_battery_sensor_get_sampling_period");
  call_end();
  return answer_int(0);
}

double wb_robot_battery_sensor_get_value(void) {
  robot_call("wb_robot_battery_sensor_get_value");
  call_end();
  return answer_double(0);
}

WbNodeType wb_robot_get_type(void) {
  robot_call("wb_robot_get_type");
  call_end();
  return (WbNodeType)answer_int(0);
}

const char *wb_robot_get_urdf(const char *prefix) {
  robot_call("wb_robot_get_urdf");
  call_text(prefix ? prefix : "");
  call_end();
  return answer_kept_text(0, "wb_robot_get_urdf", 0);
}

WbUserInputEvent wb_robot_wait_for_user_input_event(WbUserInputEvent event_type, int timeout) {
  robot_call("wb_robot_wait_for_user_input_event");
  call_int(event_type);
  call_int(timeout);
  call_end();
  return (WbUserInputEvent)answer_int(0);
}

void wb_robot_wwi_send_text(const char *text) {
  robot_call("wb_robot_wwi_send_text");
  call_text(text);
  call_end();
}

const char *wb_robot_wwi_receive_text(void) {
  robot_call("wb_robot_wwi_receive_text");
  call_end();
  return answer_kept_text(0, "wb_robot_wwi_receive_text", 0);
}

/* A step in two halves, as the Python Robot runs it: the first runs the whole step, the second
   answers its result. */
static int step_result;

int wb_robot_step_begin(int duration) {
  step_result = wb_robot_step(duration);
  return step_result == 0 ? 0 : -1;
}

int wb_robot_step_end(void) {
  return step_result;
}

/* Webots' names before the Robot's data field became customData. */
const char *wb_robot_get_data(void) {
  return wb_robot_get_custom_data();
}

void wb_robot_set_data(const char *data) {
  wb_robot_set_custom_data(data);
}
