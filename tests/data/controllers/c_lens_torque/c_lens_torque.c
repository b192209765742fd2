/* A camera's lens, a motor's torque and force, lookup tables, sensor types and the robot's
   battery, URDF and robot window, printed as lens_torque_twin.py prints them. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <webots/accelerometer.h>
#include <webots/camera.h>
#include <webots/gps.h>
#include <webots/light_sensor.h>
#include <webots/motor.h>
#include <webots/position_sensor.h>
#include <webots/robot.h>

static const char *shown(double value, char *text) {
  if (isnan(value))
    return "none";
  sprintf(text, "%.6f", value);
  return text;
}

int main(void) {
  char a[32], b[32], c[32], d[32];
  wb_robot_init();
  int step = (int)wb_robot_get_basic_time_step();
  WbDeviceTag camera = wb_robot_get_device("camera");
  WbDeviceTag motor = wb_robot_get_device("left wheel motor");
  WbDeviceTag encoder = wb_robot_get_device("left wheel sensor");
  WbDeviceTag light = wb_robot_get_device("ls0");
  WbDeviceTag accelerometer = wb_robot_get_device("accelerometer");
  wb_camera_enable(camera, step);
  wb_camera_set_fov(camera, wb_camera_get_fov(camera));
  wb_camera_set_exposure(camera, 2.0);
  wb_camera_set_focal_distance(camera, 0.5);
  printf("fov %s %s %s\n", shown(wb_camera_get_fov(camera), a),
         shown(wb_camera_get_min_fov(camera), b), shown(wb_camera_get_max_fov(camera), c));
  printf("exposure %s near %s\n", shown(wb_camera_get_exposure(camera), a),
         shown(wb_camera_get_near(camera), b));
  printf("focus %s %s %s %s\n", shown(wb_camera_get_focal_length(camera), a),
         shown(wb_camera_get_focal_distance(camera), b),
         shown(wb_camera_get_min_focal_distance(camera), c),
         shown(wb_camera_get_max_focal_distance(camera), d));
  wb_motor_set_available_torque(motor, 5.0);
  wb_motor_enable_torque_feedback(motor, step);
  printf("torque %s %s\n", shown(wb_motor_get_available_torque(motor), a),
         shown(wb_motor_get_max_torque(motor), b));
  printf("force %s %s\n", shown(wb_motor_get_available_force(motor), a),
         shown(wb_motor_get_max_force(motor), b));
  printf("multiplier %s brake %d\n", shown(wb_motor_get_multiplier(motor), a),
         wb_motor_get_brake(motor) ? 1 : 0);
  const double *table = wb_light_sensor_get_lookup_table(light);
  printf("light table %d %s %s %s\n", wb_light_sensor_get_lookup_table_size(light),
         shown(table[0], a), shown(table[1], b), shown(table[2], c));
  printf("accelerometer table %d\n", wb_accelerometer_get_lookup_table_size(accelerometer));
  printf("encoder type %d brake %d\n", wb_position_sensor_get_type(encoder),
         wb_position_sensor_get_brake(encoder) ? 1 : 0);
  printf("dms %s\n", wb_gps_convert_to_degrees_minutes_seconds(12.5826));
  wb_robot_battery_sensor_enable(step);
  printf("battery %s %d\n", shown(wb_robot_battery_sensor_get_value(), a),
         wb_robot_battery_sensor_get_sampling_period());
  const char *urdf = strchr(wb_robot_get_urdf("my_"), '\n') + 1;
  printf("type %d urdf %.*s\n", wb_robot_get_type(), (int)(strchr(urdf, '\n') - urdf), urdf);
  wb_robot_wwi_send_text("hello");
  const char *window = wb_robot_wwi_receive_text();
  printf("window %s\n", window ? window : "none");
  int n = 0;
  while (wb_robot_step_begin(step) != -1) {
    wb_robot_step_end();
    if (++n % 16 == 0)
      printf("feedback %s %d\n", shown(wb_motor_get_torque_feedback(motor), a),
             wb_motor_get_torque_feedback_sampling_period(motor));
  }
  wb_robot_cleanup();
  return 0;
}
